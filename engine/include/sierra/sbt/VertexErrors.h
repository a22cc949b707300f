#pragma once
// Per-vertex object-space error and bounding radius of the SBT, and the
// geometry of the hypotenuse each vertex splits (for geomorphing).
//
// Memory: two float32 arrays beside the heights, 8 bytes per grid sample.
//
// A non-corner vertex m of a (2^n+1)^2 grid splits exactly one hypotenuse
// (a, b): that of the one or two triangles of level(m) whose hypotenuse
// midpoint is m. Its children are the split vertices of the (up to four)
// children of those triangles.
//
//   error(m)  = max(|h(m) - (h(a) + h(b)) / 2|, error(c) over children c)
//               heights in world units (Heightfield::worldHeight), so the
//               error is saturated: never below any descendant's.
//   radius(m) = max(|p(m) - p(c)| + radius(c) over children c,
//                   |p(m) - p(v)| over the corners v of both triangles)
//               p in world coordinates (i * spacingX, worldHeight, j * spacingZ).
//               Nested (a vertex's sphere holds its children's spheres) and the
//               sphere holds both triangles sharing m's hypotenuse entirely, so
//               a pair whose sphere is outside a frustum plane is really outside
//               (exact culling). Radii are rounded up to the next float so the
//               nesting survives rounding.
// Corners have error 0 and radius 0 (they never split anything).

#include <sierra/terrain/Heightfield.h>

#include <cstdint>
#include <vector>

namespace sierra::sbt {

struct VertexErrors {
    int n = 0;                  // grid side 2^n + 1
    int side = 0;               // samples per side, 2^n + 1
    std::vector<float> error;   // world height units, index j * side + i
    std::vector<float> radius;  // world units, index j * side + i
};

// True when the field is (2^n + 1)^2 with n >= 1; n is returned through `n`.
bool isSbtGrid(const terrain::Heightfield& field, int* n = nullptr);

// The largest grid side the SBT takes: strips index vertices j * side + i with
// 32-bit indices and 0xFFFFFFFF as the restart index, so side^2 must stay below
// it. 32769^2 = 1.07e9 vertices fit; the next grid, 65537^2 = 4.3e9, would wrap
// and turn the restart index into a vertex. computeVertexErrors and the Refiner
// refuse larger grids before allocating.
inline constexpr int kMaxSbtSide = 32769;
static_assert(uint64_t(kMaxSbtSide) * kMaxSbtSide < 0xFFFFFFFFull);

// One bottom-up pass, level by level, each level split across `threads`
// (0 = sierra::defaultThreadCount()). Throws sierra::Error unless the field is
// (2^n + 1)^2 (pad it first with terrain::padToPowerOfTwoPlusOne).
VertexErrors computeVertexErrors(const terrain::Heightfield& field, int threads = 0);

// The level whose triangles vertex (i, j) splits (0..2n-1), or -1 for the four
// corners. Grid side 2^n + 1.
int vertexLevel(int i, int j, int n);

// The hypotenuse endpoints (a, b) vertex (i, j) bisects; false for corners
// (then a = b = (i, j)).
bool hypotenuseEndpoints(int i, int j, int n, int* ai, int* aj, int* bi, int* bj);

// Per-vertex morph base for geomorphing: (worldHeight(a) + worldHeight(b)) / 2
// for the hypotenuse (a, b) each vertex bisects, the vertex's own world height
// at the corners. Row-major, j * side + i. Built once per terrain (a GPU
// texture); multithreaded like computeVertexErrors.
std::vector<float> buildMorphBase(const terrain::Heightfield& field, int threads = 0);

}  // namespace sierra::sbt
