#pragma once
// Mesh invariants of SBT refinements, shared by the in-memory and the tiled
// refiner's tests: triangles as linear indices j * side + i.

#include <sierra/sbt/Refiner.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

namespace sierra::test {

using Tri = std::array<uint32_t, 3>;

// A camera somewhere above or beside a side^2 grid looking at a point on it.
inline sbt::ViewParams randomView(std::mt19937& random, int side, float tau, bool cull) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float s = float(side - 1);
    const std::array<float, 3> eye{(u(random) * 1.6f - 0.3f) * s, (0.05f + u(random)) * 0.6f * s,
                                   (u(random) * 1.6f - 0.3f) * s};
    const std::array<float, 3> target{u(random) * s, 0.0f, u(random) * s};
    return sbt::lookAtView(eye, target, 0.9f, 16.0f / 9.0f, 720.0f, 0.5f, 10.0f * s, tau, cull);
}

// Each triangle turned so its least vertex comes first (its winding kept).
inline std::vector<Tri> canonical(std::vector<Tri> tris) {
    for (Tri& t : tris) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return tris;
}

// Twice the signed area of t in the (i, j) plane.
inline int64_t cross2(const Tri& t, int side) {
    int64_t i0 = t[0] % side, j0 = t[0] / side, i1 = t[1] % side, j1 = t[1] / side,
            i2 = t[2] % side, j2 = t[2] / side;
    return (i1 - i0) * (j2 - j0) - (j1 - j0) * (i2 - i0);
}

// Mesh invariants: clockwise winding in (i, j); every edge shared by two
// triangles with opposite directions or on the border (when `full`); no vertex
// inside another triangle's edge (no T-junction); areas sum to the square.
inline void expectConforming(const std::vector<Tri>& tris, int side, bool full) {
    const int S = side - 1;
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    std::vector<uint8_t> isVertex(size_t(side) * side, 0);
    int64_t area2 = 0;
    for (const Tri& t : tris) {
        int64_t c = cross2(t, side);
        ASSERT_LT(c, 0) << "every decoded triangle is clockwise in (i, j)";
        area2 += -c;
        for (int k = 0; k < 3; ++k) {
            ++directed[{t[k], t[(k + 1) % 3]}];
            isVertex[t[k]] = 1;
        }
    }
    if (full) {
        EXPECT_EQ(area2, 2 * int64_t(S) * S) << "areas sum to the square";
    }
    for (const auto& [e, count] : directed) {
        ASSERT_EQ(count, 1) << "an edge used twice in the same direction";
        if (directed.count({e.second, e.first})) continue;
        if (!full) continue;
        int i0 = e.first % side, j0 = e.first / side, i1 = e.second % side, j1 = e.second / side;
        bool border = (i0 == i1 && (i0 == 0 || i0 == S)) || (j0 == j1 && (j0 == 0 || j0 == S));
        ASSERT_TRUE(border) << "hanging interior edge (" << i0 << "," << j0 << ")-(" << i1 << ","
                            << j1 << ")";
    }
    for (const auto& [e, count] : directed) {
        int i0 = e.first % side, j0 = e.first / side, i1 = e.second % side, j1 = e.second / side;
        int g = std::gcd(std::abs(i1 - i0), std::abs(j1 - j0));
        for (int s = 1; s < g; ++s) {
            int i = i0 + (i1 - i0) / g * s, j = j0 + (j1 - j0) / g * s;
            ASSERT_FALSE(isVertex[size_t(j) * side + i])
                << "T-junction at (" << i << "," << j << ")";
        }
    }
}

}  // namespace sierra::test
