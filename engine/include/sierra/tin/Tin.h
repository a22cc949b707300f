#pragma once
// Triangulated irregular networks by greedy insertion (Garland and Heckbert's
// algorithm, as the zone-texturing document uses it): start from the grid's four
// corners plus the zone borderlines as constrained edges, then repeatedly insert
// the grid sample of largest vertical error over the whole triangulation until a
// stop condition holds; finally give every triangle its zone by a flood fill from
// the constrained edges.
//
// Coordinates. Every mesh vertex is a grid sample (x = column i, y = row j, both
// integers), so orientation and in-circle tests are exact integer arithmetic.
// "Left" of a directed segment a->b is the side where cross(b - a, p - a) > 0 in
// (x, y); triangles are counter-clockwise in that sense.
//
// Heights and errors are world heights: stored height * verticalScale().

#include <sierra/terrain/Heightfield.h>

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace sierra::tin {

// One grid sample: x = column (0..width-1), y = row (0..height-1).
struct GridPoint {
    int32_t x = 0;
    int32_t y = 0;
    friend bool operator==(const GridPoint&, const GridPoint&) = default;
};

// Constrained input: zone borderlines as vertices and directed segments. This is
// the TIN's own form; vectorised borderlines from a zone map are converted into it.
//
// Snapping: a vertex (x, y) in grid coordinates (fractional allowed, e.g. the
// centre of a borderline pixel) becomes the sample (floor(x + 0.5), floor(y + 0.5))
// clamped into the grid. Vertices that snap to the same sample become one vertex
// (the document's rule 1). A segment whose two ends snap to one sample is dropped.
// A vertex lying exactly on a segment (collinear borderline points) splits that
// segment there; both parts keep its zones. Segments that cross each other away
// from a shared vertex are rejected with sierra::Error.
struct Constraints {
    struct Vertex {
        double x = 0.0;
        double y = 0.0;
    };
    struct Segment {
        int32_t a = 0;          // index into vertices
        int32_t b = 0;          // index into vertices
        int32_t leftZone = 0;   // zone on the left of a->b (see "Left" above), >= 0
        int32_t rightZone = 0;  // zone on the right of a->b, >= 0
    };
    // A transition band (a doubled borderline): triangles of zone `zone` are
    // textured from the two surface types `first` and `second`.
    struct Band {
        int32_t zone = 0;
        int32_t first = 0;
        int32_t second = 0;
    };
    std::vector<Vertex> vertices;
    std::vector<Segment> segments;
    std::vector<Band> bands;
    // Zone of triangles that no constrained edge reaches (e.g. no borderlines at all).
    int32_t defaultZone = 0;
};

enum class Triangulation {
    Delaunay,       // Delaunay by Lawson flips, except across constrained edges
    DataDependent,  // flip an edge when the other diagonal fits the samples of the quad better
};

// Which mesh a triangle or point budget keeps. The max error of a greedy mesh
// is not monotone in the number of insertions: an insertion and its flips can
// leave a worse sample in a new triangle, which a later insertion removes. So
// the mesh at the last insertion the budget allows may have a larger max error
// than an earlier one within the same budget.
enum class BudgetStop {
    // Keep the mesh of smallest max error among all those the run went through
    // within the budget (on a tie the later, larger one): the max error at a
    // budget is then the running minimum, never larger at a larger budget.
    BestMax,
    // Keep the mesh at the last insertion the budget allows.
    Last,
};

const char* toString(BudgetStop rule);  // "best-max", "last"

struct TinProgress {
    int64_t points = 0;        // vertices so far
    int64_t triangles = 0;     // triangles so far
    double worstError = 0.0;   // largest vertical error left (world units)
    double targetError = 0.0;  // error at which insertion stops (world units)
};

struct TinDesc {
    // Stop at the first of these that holds (0 = not used). With no limit at
    // all, insertion goes on until every sample is interpolated exactly.
    double maxError = 0.0;     // largest vertical error, world height units
    double maxErrorRel = 0.0;  // largest vertical error as a fraction of the height range
    int64_t maxTriangles = 0;  // no insertion that would make more triangles than this
    int64_t maxPoints = 0;     // no insertion that would make more vertices than this
    // When maxTriangles or maxPoints stops insertion: which mesh is kept (see
    // BudgetStop). An error target or an exhausted grid stops at a mesh whose max
    // error is already the smallest so far, so this only matters for budgets.
    BudgetStop budgetStop = BudgetStop::BestMax;
    Triangulation triangulation = Triangulation::Delaunay;
    // The snap() rule: a point inserted into a triangle next to one of the
    // triangle's constrained edges (its foot strictly inside that edge, and its
    // distance from the input segment the edge comes from below snapDistance,
    // grid units, default 1 sample) splits that edge at the point itself: the
    // borderline is bent through the grid sample instead of the sample being
    // moved onto the borderline, so no slit opens, every vertex stays a grid
    // sample and a borderline never strays further than snapDistance from its
    // input segment. A point exactly on a constrained edge always splits it.
    // 0 = split only when exactly on the edge.
    double snapDistance = 1.0;
    // Called about every progressEvery insertions (and once at the end), if set.
    std::function<void(const TinProgress&)> progress;
    int64_t progressEvery = 100000;
};

// The result: an indexed mesh on grid samples.
struct TinMesh {
    int32_t gridWidth = 0;
    int32_t gridHeight = 0;
    float spacingX = 1.0f;  // world distance between samples along x (from the heightfield)
    float spacingZ = 1.0f;  // ... along z (grid y)
    std::vector<GridPoint> vertices;
    std::vector<float> heights;                     // world height per vertex
    std::vector<std::array<int32_t, 3>> triangles;  // counter-clockwise in (x, y)
    // Per triangle, bit k set: edge k (vertex k -> vertex k+1 mod 3) is constrained.
    std::vector<uint8_t> constrainedEdges;
    // Per triangle and edge k: the zone on that triangle's side of a constrained
    // edge, -1 for an unconstrained edge. An edge on the grid's border carries its
    // triangle's zone (the frame's zone only where no inner borderline reaches).
    std::vector<std::array<int32_t, 3>> edgeZones;
    // Per triangle: its zone from the flood fill, and its two surface types
    // (equal unless the zone is a band).
    std::vector<int32_t> zone;
    std::vector<std::array<int32_t, 2>> surfaces;
};

enum class StopReason { Error, Triangles, Points, Exhausted };
const char* toString(StopReason reason);

struct TinStats {
    int64_t inserted = 0;    // points inserted by greedy insertion (not corners or borderlines)
    int64_t edgeSplits = 0;  // insertions that split an edge exactly through the point
    // Insertions that bent a constrained edge through the point (the snap rule).
    int64_t snapSplits = 0;
    int64_t flips = 0;  // edge flips in total (of the kept mesh's insertions)
    // Triangles that the flood fills from two inner constrained edges claimed with
    // different zones (border edges only seed what no inner edge reaches).
    int64_t zoneConflicts = 0;
    double targetError = 0.0;  // error threshold used (world units; 0 = none)
    double worstError = 0.0;   // largest error left in the kept mesh (world units)
    StopReason stop = StopReason::Exhausted;
    // With a budget and BudgetStop::BestMax: the insertions made when the budget
    // stopped the run and the max error of that mesh (world units). The kept mesh
    // is the one after `inserted` of them; inserted < budgetInserted when an
    // earlier mesh had a smaller max error. Otherwise equal to inserted and
    // worstError.
    int64_t budgetInserted = 0;
    double budgetWorstError = 0.0;
    double setupMs = 0.0;   // initial triangulation and constrained edges
    double insertMs = 0.0;  // greedy insertion
    double zonesMs = 0.0;   // flood fill
};

struct TinResult {
    TinMesh mesh;
    TinStats stats;
};

// Builds the TIN of `field` (any width x height >= 2 x 2). Throws sierra::Error
// for an empty field, a segment naming a missing vertex, a negative zone or
// crossing segments.
TinResult buildTin(const terrain::Heightfield& field, const Constraints& constraints = {},
                   const TinDesc& desc = {});

// Vertical error of the mesh against every grid sample (world units), each
// sample counted once.
struct ErrorStats {
    double maxError = 0.0;
    double rmsError = 0.0;
    int64_t samples = 0;
};
ErrorStats measureError(const TinMesh& mesh, const terrain::Heightfield& field);

}  // namespace sierra::tin
