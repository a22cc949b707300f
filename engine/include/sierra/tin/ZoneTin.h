#pragma once
// The zones module's output as the TIN's input and output: vectorised
// borderlines become constrained edges, the zone map checks the triangles'
// zones, and the palette's tiles (blended for bands) become the OBJ's
// materials.
//
// Zone map and grid: the map's pixel centres lie on the terrain's samples and
// the map is stretched over the grid, as the terrain shader places it. Map
// position m (pixel units, pixel (i, j) covering [i, i+1] x [j, j+1]) is grid
// position (m - 0.5) * (gridSide - 1) / (mapSide - 1) on each axis, so a map
// of the grid's size puts pixel (i, j)'s centre on sample (i, j).

#include <sierra/tin/Export.h>
#include <sierra/tin/Tin.h>
#include <sierra/zones/Borderlines.h>
#include <sierra/zones/Palette.h>
#include <sierra/zones/ZoneMap.h>

#include <cstdint>
#include <functional>
#include <string>

namespace sierra::tin {

// Grid coordinates of a zone-map position (see above).
Constraints::Vertex mapToGrid(double mapX, double mapY, int mapWidth, int mapHeight, int gridWidth,
                              int gridHeight);

// Rule 3 for islands: a closed borderline with no junction (an island, its
// zone inside, the one around it outside) whose vertices all lie within
// `epsilon` (pixels) of its longest chord is a strip at most 2 epsilon wide,
// which rule 3 at epsilon would leave with no area (Douglas-Peucker keeps only
// the chord's two ends). Such an island is removed and its pixels take the
// zone around it, unless another borderline lies inside it (its zones would
// then disagree with the zone around). Vertices left without an edge are
// dropped, the others keep their order. Returns the number of islands removed.
// epsilon <= 0, or no island thin enough: nothing changes.
size_t removeThinIslands(zones::Borderlines& lines, double epsilon);

// A zone map's borderlines ready for a gridWidth x gridHeight TIN:
// vectorised, thin islands removed (removeThinIslands at desc.epsilon; in a
// TIN every borderline vertex is a mesh vertex, so an island a mesh of that
// scale cannot show would only take its budget) and simplified
// (desc.epsilon), every vertex moved to the grid
// sample the TIN snaps it to (Constraints' rule), written back in zone-map
// pixels, coincident vertices merged (rule 1), then doubled into bands
// (desc.bandWidth) with the copies snapped the same way before their crossing
// check, so the bands stay a valid subdivision on the grid. Throws
// sierra::Error as zones::buildBorderlines, and for a map or grid smaller
// than 2 x 2. `removedIslands`, when given, receives the number of islands
// removed.
zones::Borderlines gridBorderlines(const zones::ZoneMap& map, const zones::Palette& palette,
                                   const zones::BorderlineDesc& desc, int gridWidth, int gridHeight,
                                   size_t* removedIslands = nullptr);

// The borderlines (zone-map pixel units) as constraints of a gridWidth x
// gridHeight TIN: every edge becomes a segment with its two zones (the zones'
// "left as drawn", y down, is the TIN's right: cross(b - a, p - a) < 0); a frame
// edge carries its inside zone on both sides (its outside has no triangle); a
// band zone becomes a Constraints::Band of its two zones; defaultZone is the
// zone of the first frame edge (a map with one zone has no other edge).
// Throws sierra::Error for a map or grid smaller than 2 x 2.
Constraints constraintsFromBorderlines(const zones::Borderlines& lines, int gridWidth,
                                       int gridHeight);

// How far the triangles' zones agree with a zone map: each map pixel is
// counted once, in the triangle that contains its centre; it agrees when its
// zone is one of that triangle's two surface types. A centre on an edge (a
// Touching map's borderlines run through the samples after snapping, so whole
// rows of centres do) goes to the triangle on its +x side, then +y: the centre
// is moved by (1.3e-4, 0.7e-4) samples (inwards at the grid's far edges).
// Borderline pixels of Figure 1 maps belong to no zone and are not counted.
struct ZoneAgreement {
    int64_t pixels = 0;  // pixels counted
    int64_t agree = 0;   // of those, pixels whose zone the triangle carries
    double fraction() const { return pixels > 0 ? double(agree) / double(pixels) : 1.0; }
};
ZoneAgreement zoneAgreement(const TinMesh& mesh, const zones::ZoneMap& map);

// The OBJ materials of a zoned TIN: each surface type's tile (palette order)
// named relative to the OBJ's folder (absolute when no relative path exists),
// its palette colour as Kd, and for every band pair in the mesh a blended tile
// (zones::blendTiles, heightBlend the mean of the two surfaces') written as a
// PNG beside the OBJ: <obj stem>_band_<a>_<b>.png. Throws sierra::Error when a
// tile cannot be read, when two tiles of a band differ in size, or when a
// file cannot be written. The UVs are the terrain shader's zone tiles (top
// projection): a surface repeats every tileSize zone-map pixels, i.e. every
// tileSize (gridSide - 1) / (mapSide - 1) grid samples on each axis, from
// half a pixel before sample 0, so the OBJ textures like `sierra-render --mesh`
// (a band: the mean of its two periods, see ObjOptions).
ObjOptions zoneMaterials(const std::string& objPath, const TinMesh& mesh,
                         const zones::Palette& palette, int mapWidth, int mapHeight);

// A zoned TIN: the zone map's borderlines (gridBorderlines) as constraints,
// the TIN (buildTin) and its zone agreement.
//
// At a budget (TinDesc::maxTriangles or maxPoints) with no error target and
// `autoEpsilon`, the borderlines are first simplified to the budget's scale
// (budgetEpsilon), so that their vertices do not take the budget, and while
// the zone agreement is below `leastAgreement` the TIN is built again with
// the epsilon halved, never below `epsilon`. Otherwise `epsilon` is used once.
struct ZonedTinDesc {
    double epsilon = 0.5;  // borderline simplification, zone-map pixels (the least, when automatic)
    double bandWidth = 0.0;  // transition band width, zone-map pixels
    bool autoEpsilon = false;
    double leastAgreement = 0.995;  // share of zone-map pixels (zoneAgreement)
    // Called before each rebuild with the agreement reached, the epsilon it was
    // reached at and the next epsilon.
    std::function<void(double agreement, double epsilon, double next)> retry;
};

struct ZonedTin {
    TinResult result;
    zones::Borderlines lines;  // as constrained, zone-map pixels
    Constraints constraints;
    ZoneAgreement agreement;
    double epsilon = 0.0;        // the epsilon of the mesh returned
    bool autoEpsilon = false;    // that epsilon came from the budget
    size_t islandsRemoved = 0;   // by removeThinIslands
    int builds = 0;              // TINs built (1 unless the epsilon was halved)
    double borderlinesMs = 0.0;  // borderlines and constraints, every build
};

// The automatic epsilon of a triangle budget (zone-map pixels): 0.45 x the
// side of the mean triangle's square, sqrt(grid area / triangles), so that at
// a small budget the borderlines take few of its vertices, and never below
// `least`. On the default scene with the sample map: 3.3 px at 20,000
// triangles, 1.5 at 100,000, 0.84 at 300,000.
double budgetEpsilon(int64_t triangles, int gridWidth, int gridHeight, const zones::ZoneMap& map,
                     double least);

// The triangle count a budget allows: maxTriangles, or twice maxPoints (a
// grid TIN has about two triangles per vertex), the smaller when both are
// given; 0 without a budget.
int64_t budgetTriangles(const TinDesc& desc);

ZonedTin buildZonedTin(const terrain::Heightfield& field, const zones::ZoneMap& map,
                       const zones::Palette& palette, const TinDesc& desc,
                       const ZonedTinDesc& zoned);

}  // namespace sierra::tin
