#include <sierra/render/MeshInspector.h>

#include <sierra/render/TerrainGpu.h>
#include <sierra/sbt/Refiner.h>

#include "render/SbtBridge.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace sierra::render {

int triangleLevel(uint32_t a, uint32_t b, uint32_t c, int side) {
    auto len2 = [side](uint32_t p, uint32_t q) {
        const int64_t di = int64_t(p % uint32_t(side)) - int64_t(q % uint32_t(side));
        const int64_t dj = int64_t(p / uint32_t(side)) - int64_t(q / uint32_t(side));
        return di * di + dj * dj;
    };
    const int64_t leg = std::min({len2(a, b), len2(b, c), len2(c, a)});
    const int64_t full = int64_t(side - 1) * (side - 1);
    if (leg <= 0 || full % leg != 0) return -1;
    const uint64_t ratio = uint64_t(full / leg);  // 2^level
    if (!std::has_single_bit(ratio)) return -1;
    return std::countr_zero(ratio);
}

MeshInspection inspectMesh(TerrainGpu& terrain, const Camera& camera, int width, int height,
                           float tau, bool cull, int threads, bool geomorph) {
    // The same view as SbtStream::prepare builds.
    const LodView lv = camera.lodView(height);
    SbtView view;
    view.eye = lv.eye;
    view.lambda = lv.lambda;
    view.tau = tau;
    view.cull = cull;
    view.geomorph = geomorph;
    view.planes = camera.frustumPlanes(float(width) / float(height));
    std::vector<uint32_t> strip;
    SbtBridge& sbt = terrain.sbt();
    sbt.refineView(view, strip, threads);

    MeshInspection out;
    out.tau = tau;
    out.lambda = lv.lambda;
    out.indices = int64_t(strip.size());
    out.culledSubtrees = sbt.lastCulledSubtrees();
    const int side = terrain.side();
    out.distinctVertices = sbt::countDistinctVertices(strip, side);
    auto triangles = sbt::decodeStrip(strip);
    out.triangles = int64_t(triangles.size());
    int levels = 0;
    while ((1 << (levels / 2)) < side - 1 || levels % 2) ++levels;  // 2n: (side - 1) = 2^n
    out.levelCounts.assign(size_t(levels + 1), 0);
    const auto errors = sbt.errors();
    const auto radii = sbt.radii();
    const glm::vec2 spacing = terrain.spacing();
    const terrain::Heightfield& surface = sbt.field();
    double worst = 0.0;
    for (const auto& t : triangles) {
        const int level = triangleLevel(t[0], t[1], t[2], side);
        if (level >= 0 && level < int(out.levelCounts.size())) ++out.levelCounts[size_t(level)];
        // Hypotenuse: the longest edge; its midpoint is the split vertex.
        auto len2 = [side](uint32_t p, uint32_t q) {
            const int64_t di = int64_t(p % uint32_t(side)) - int64_t(q % uint32_t(side));
            const int64_t dj = int64_t(p / uint32_t(side)) - int64_t(q / uint32_t(side));
            return di * di + dj * dj;
        };
        uint32_t p = t[0], q = t[1];
        if (len2(t[1], t[2]) > len2(p, q)) p = t[1], q = t[2];
        if (len2(t[2], t[0]) > len2(p, q)) p = t[2], q = t[0];
        const int64_t si = (int64_t(p % uint32_t(side)) + int64_t(q % uint32_t(side)));
        const int64_t sj = (int64_t(p / uint32_t(side)) + int64_t(q / uint32_t(side)));
        if (si % 2 || sj % 2) continue;  // finest level: no split vertex
        const size_t m = size_t(sj / 2) * size_t(side) + size_t(si / 2);
        const float e = errors[m];
        if (!(e > 0.0f)) continue;
        // The split vertex where the refiner measures its distance: on the
        // refined surface (water flattened to sea level).
        const int mi = int(si / 2), mj = int(sj / 2);
        const glm::vec3 world(float(mi) * spacing.x, surface.worldHeight(mi, mj),
                              float(mj) * spacing.y);
        const double d = glm::length(world - lv.eye) - radii[m];
        const double px = d > 0.0 ? lv.lambda * e / d : INFINITY;
        worst = std::max(worst, px);
    }
    out.maxProjectedErrorPx = worst;
    out.triangleList = std::move(triangles);
    return out;
}

}  // namespace sierra::render
