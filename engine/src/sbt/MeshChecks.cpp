// Checks on a refinement's output (Refiner.h): its strips decoded into
// triangles, the vertices it uses, and how far the mesh lies from the grid.
// For tests, benchmarks and tools; the refiner itself is in Refiner.cpp.
#include <sierra/core/Error.h>
#include <sierra/core/Parallel.h>
#include <sierra/sbt/Refiner.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace sierra::sbt {

std::vector<std::array<uint32_t, 3>> decodeStrip(const std::vector<uint32_t>& indices) {
    std::vector<std::array<uint32_t, 3>> tris;
    tris.reserve(indices.size());
    size_t begin = 0;
    while (begin < indices.size()) {
        size_t end = begin;
        while (end < indices.size() && indices[end] != kRestartIndex) ++end;
        for (size_t k = begin; k + 2 < end; ++k) {
            uint32_t v0 = indices[k], v1 = indices[k + 1], v2 = indices[k + 2];
            if (v0 == v1 || v1 == v2 || v0 == v2) continue;
            if ((k - begin) & 1) std::swap(v0, v1);
            tris.push_back({v0, v1, v2});
        }
        begin = end + 1;
    }
    return tris;
}

int64_t countDistinctVertices(const std::vector<uint32_t>& indices, int side) {
    std::vector<uint8_t> seen(size_t(side) * side, 0);
    int64_t count = 0;
    for (uint32_t v : indices) {
        if (v == kRestartIndex) continue;
        SIERRA_CHECK(v < seen.size(), "countDistinctVertices: index ", v, " outside a ", side, "x",
                     side, " grid");
        count += !seen[v];
        seen[v] = 1;
    }
    return count;
}

double maxVerticalDistance(const terrain::Heightfield& field,
                           const std::vector<std::array<uint32_t, 3>>& triangles, int threads) {
    const int side = field.width();
    const int64_t chunks =
        std::max<int64_t>(1, std::min<int64_t>(int64_t(triangles.size()) / 4096 + 1, 256));
    std::vector<double> best(size_t(chunks), 0.0);
    parallelChunks(
        0, int64_t(triangles.size()), int(chunks),
        [&](int64_t lo, int64_t hi, int c) {
            double worst = 0.0;
            for (int64_t t = lo; t < hi; ++t) {
                int vi[3], vj[3];
                double vh[3];
                for (int k = 0; k < 3; ++k) {
                    vi[k] = int(triangles[t][k] % uint32_t(side));
                    vj[k] = int(triangles[t][k] / uint32_t(side));
                    vh[k] = field.worldHeight(vi[k], vj[k]);
                }
                const int64_t det = int64_t(vi[1] - vi[0]) * (vj[2] - vj[0]) -
                                    int64_t(vj[1] - vj[0]) * (vi[2] - vi[0]);
                if (det == 0) continue;
                const int i0 = std::min({vi[0], vi[1], vi[2]}),
                          i1 = std::max({vi[0], vi[1], vi[2]});
                const int j0 = std::min({vj[0], vj[1], vj[2]}),
                          j1 = std::max({vj[0], vj[1], vj[2]});
                for (int j = j0; j <= j1; ++j)
                    for (int i = i0; i <= i1; ++i) {
                        // barycentric coordinates (exact integers)
                        int64_t w1 = int64_t(i - vi[0]) * (vj[2] - vj[0]) -
                                     int64_t(j - vj[0]) * (vi[2] - vi[0]);
                        int64_t w2 = int64_t(vi[1] - vi[0]) * (j - vj[0]) -
                                     int64_t(vj[1] - vj[0]) * (i - vi[0]);
                        int64_t w0 = det - w1 - w2;
                        bool inside = det > 0 ? (w0 >= 0 && w1 >= 0 && w2 >= 0)
                                              : (w0 <= 0 && w1 <= 0 && w2 <= 0);
                        if (!inside) continue;
                        double hMesh =
                            (double(w0) * vh[0] + double(w1) * vh[1] + double(w2) * vh[2]) /
                            double(det);
                        worst = std::max(worst, std::fabs(double(field.worldHeight(i, j)) - hMesh));
                    }
            }
            best[size_t(c)] = worst;
        },
        threads);
    return *std::max_element(best.begin(), best.end());
}

}  // namespace sierra::sbt
