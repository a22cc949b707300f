#pragma once
// Line shading: polylines traced once per terrain and style through vertices
// of high curvature, drawn later as a static, view-independent framework.
//
// Discrete tracing (the default). Vertices are visited in row-major order; a
// vertex whose strength (its largest curvature, see LinePolarity) is at least
// the threshold and that is on no line yet starts a path. From it the path
// steps to the neighbour perpendicular to the vertex's direction of largest
// curvature (+x <-> +z, x+z <-> x-z), both ways, and at every vertex turns
// to that vertex's own perpendicular, keeping the side that continues the
// previous step (on a right-angle turn, the neighbour with the larger
// strength). An end stops at the grid edge, at a vertex below the threshold
// or with no data, or at a vertex already on a line: that vertex is appended
// (the paths join there) and the end stops, so no segment is ever traced
// twice. Paths of fewer than minVertices vertices (joining vertices
// included) are dropped; their vertices stay free for later paths to pass
// through but never start one again.
//
// Blended tracing (the document's refinement, blended = true). Points move
// in steps of `step` grid units perpendicular to the curvature-weighted axis
// of largest curvature (blendedCurvatureAxis in Hatch.h), with the 4
// curvatures interpolated bilinearly at each point. Each point claims its
// nearest vertex; a point whose nearest vertex another path claimed ends the
// path at that path's point (the join), a point returning to a vertex this
// path claimed a few points ago (more than 2 / step) closes a loop. Lines
// that cross between vertices are not detected as joined. Dropped paths
// release their vertices, which never start a path again.
//
// Alpha is the strength at the vertex (or point), clamped to [0, 1]; the
// polylines are in grid coordinates (x = column i, z = row j).

#include <sierra/analysis/Curvature.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sierra::analysis {

// Which curvature counts. Any: |k| in every direction. With a signed field
// (CurvatureOptions::signedValues), Ridges counts only convex values (k < 0,
// as their magnitude) and Valleys only concave ones (k > 0).
enum class LinePolarity { Any, Ridges, Valleys };

// "any", "ridges", "valleys".
const char* linePolarityName(LinePolarity polarity);
// Parses the names above; throws sierra::Error naming the choices.
LinePolarity parseLinePolarity(const std::string& name);

struct LineOptions {
    float threshold = 0.5f;  // strength a vertex needs to be on a line, >= 0 (after scale/levels)
    int minVertices = 5;     // shortest polyline kept, in vertices, >= 2
    LinePolarity polarity = LinePolarity::Any;
    bool blended = false;  // the refinement: blended directions, interpolated points
    float step = 1.0f;     // blended: step length in grid units, in (0, 2]
    int maxPoints = 0;     // blended: longest polyline, 0 = 4 * (width + height)
};

// Throws sierra::Error with one clear message for a bad option.
void validate(const LineOptions& options);

struct LineVertex {
    float x = 0.0f;      // grid column (along +x)
    float z = 0.0f;      // grid row (along +z)
    float alpha = 0.0f;  // strength clamped to [0, 1]
};

// All polylines back to back: polyline k is vertices[offsets[k], offsets[k+1]).
struct LineSet {
    std::vector<LineVertex> vertices;
    std::vector<uint32_t> offsets{0};

    size_t polylineCount() const { return offsets.size() - 1; }
    std::span<const LineVertex> polyline(size_t k) const {
        return {vertices.data() + offsets[k], vertices.data() + offsets[k + 1]};
    }
};

// Traces the lines of a curvature field (serial: it is run once per terrain
// and style, and its result depends on the visiting order).
LineSet traceLines(const CurvatureField& curvature, const LineOptions& options = {});

}  // namespace sierra::analysis
