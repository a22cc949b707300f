#pragma once
// What the SBT emitted for one view, measured on the CPU for the debug UI: the
// same refinement the SBT stream runs (same view, same tau), decoded into
// triangles. Costs one extra refinement; call it for snapshots only.

#include <sierra/render/Camera.h>

#include <array>
#include <cstdint>
#include <vector>

namespace sierra::render {

class TerrainGpu;

struct MeshInspection {
    int64_t triangles = 0;         // decoded, non-degenerate
    int64_t distinctVertices = 0;  // grid samples the strip references
    int64_t indices = 0;           // strip indices, restarts included
    // Subtrees of the SBT dropped whole by the frustum test (their root
    // triangle's bounding sphere outside a plane); 0 without culling.
    int64_t culledSubtrees = 0;
    // levelCounts[l] = leaf triangles of SBT level l (0..2n). A leaf's level is
    // read from its edges: legs of level l are (side - 1) / 2^(l/2) samples
    // long, so 2^l = (side - 1)^2 / leg^2.
    std::vector<int64_t> levelCounts;
    // The largest screen-space error of a drawn triangle, pixels: over every
    // leaf, lambda * e(m) / (|m - eye| - r(m)) at its split vertex m (the
    // hypotenuse midpoint; 0 on the finest level, which has none). Below tau
    // unless the finest level is reached.
    double maxProjectedErrorPx = 0.0;
    double tau = 1.0;
    double lambda = 1.0;
    // The decoded triangles (linear vertex indices j * side + i), as drawn.
    std::vector<std::array<uint32_t, 3>> triangleList;
};

// Refines `terrain`'s SBT for `camera` on a width x height viewport with the
// given tau and culling, and measures the result. geomorph: refine as the
// stream does with geomorphing on (at sbt::refinementTau(tau)).
MeshInspection inspectMesh(TerrainGpu& terrain, const Camera& camera, int width, int height,
                           float tau, bool cull, int threads = 0, bool geomorph = true);

// Level of a right isosceles grid triangle of a (side x side) SBT from its
// three linear vertex indices (j * side + i); -1 if it is not one.
int triangleLevel(uint32_t a, uint32_t b, uint32_t c, int side);

}  // namespace sierra::render
