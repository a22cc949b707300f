#pragma once
// Pieces shared by the analysis sources: world heights with NaN for no data,
// and the unnormalised vertex normal of each method.

#include <sierra/analysis/Normals.h>
#include <sierra/terrain/Heightfield.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace sierra::analysis::detail {

// World heights (stored height * verticalScale), NaN where there is no data,
// so that a stencil touching no data yields NaN by plain arithmetic.
struct WorldGrid {
    int width = 0;
    int height = 0;
    float spacingX = 1.0f;
    float spacingZ = 1.0f;
    bool hasNoData = false;
    std::vector<float> y;

    float at(int i, int j) const { return y[size_t(j) * size_t(width) + size_t(i)]; }
};

WorldGrid makeWorldGrid(const terrain::Heightfield& field, int threads);

// Runs body(rowBegin, rowEnd) over the rows, in parallel when the grid is
// large enough to pay for it. Rows are independent, so the result does not
// depend on the thread count.
template <typename Body>
void forRows(int width, int height, int threads, const Body& body);

struct V3 {
    float x, y, z;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline V3 normalized(V3 a) {
    float inv = 1.0f / std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    return {a.x * inv, a.y * inv, a.z * inv};
}

// The 8 neighbours counter-clockwise seen from above (x to z): E, NE, N, NW,
// W, SW, S, SE ("north" is +z).
inline constexpr int kRingDi[8] = {1, 1, 0, -1, -1, -1, 0, 1};
inline constexpr int kRingDj[8] = {0, 1, 1, 1, 0, -1, -1, -1};

// Upward unit normal of the triangle (centre, centre + a, centre + b) where b
// follows a counter-clockwise.
inline V3 triangleNormal(V3 a, V3 b) { return normalized(cross(b, a)); }

// Unnormalised normal direction at (i, j). kChecked: neighbours may be outside
// the grid or NaN (no data) and are then left out; otherwise all 8 exist.
template <NormalMethod kMethod, bool kChecked>
inline V3 normalSum(const WorldGrid& g, int i, int j) {
    const float yc = g.at(i, j);
    V3 e[8];
    bool ok[8];
    for (int k = 0; k < 8; ++k) {
        int ni = i + kRingDi[k], nj = j + kRingDj[k];
        if constexpr (kChecked) {
            ok[k] = ni >= 0 && nj >= 0 && ni < g.width && nj < g.height && !std::isnan(g.at(ni, nj));
            e[k] = {float(kRingDi[k]) * g.spacingX, ok[k] ? g.at(ni, nj) - yc : 0.0f, float(kRingDj[k]) * g.spacingZ};
        } else {
            ok[k] = true;
            e[k] = {float(kRingDi[k]) * g.spacingX, g.at(ni, nj) - yc, float(kRingDj[k]) * g.spacingZ};
        }
    }
    if constexpr (kMethod == NormalMethod::Edge) {
        // Mean edge slope per axis: central where both edges exist.
        auto axisSlope = [&](int plus, int minus, float step) {
            float sum = 0.0f;
            int n = 0;
            if (ok[plus]) { sum += e[plus].y / step; ++n; }
            if (ok[minus]) { sum -= e[minus].y / step; ++n; }
            return n ? sum / float(n) : 0.0f;
        };
        float sx = axisSlope(0, 4, g.spacingX);
        float sz = axisSlope(2, 6, g.spacingZ);
        return {-sx, 1.0f, -sz};
    } else if constexpr (kMethod == NormalMethod::Triangle) {
        V3 sum{0.0f, 0.0f, 0.0f};
        for (int q = 0; q < 4; ++q) {
            int a = 2 * q, b = (2 * q + 2) & 7;
            if (ok[a] && ok[b]) sum = sum + triangleNormal(e[a], e[b]);
        }
        return sum;
    } else {
        V3 sum{0.0f, 0.0f, 0.0f};
        for (int q = 0; q < 4; ++q) {
            int a = 2 * q, c = 2 * q + 1, b = (2 * q + 2) & 7;
            if (ok[a] && ok[b] && ok[c])
                sum = sum + normalized(triangleNormal(e[a], e[c]) + triangleNormal(e[c], e[b]));
        }
        return sum;
    }
}

// Calls fn(i, j, normalSum) for every valid vertex of rows [j0, j1), the
// interior without checks.
template <NormalMethod kMethod, typename Fn>
inline void forNormalSums(const WorldGrid& g, int j0, int j1, const Fn& fn) {
    for (int j = j0; j < j1; ++j) {
        bool interiorRow = !g.hasNoData && j > 0 && j < g.height - 1;
        for (int i = 0; i < g.width; ++i) {
            if (interiorRow && i > 0 && i < g.width - 1) {
                fn(i, j, normalSum<kMethod, false>(g, i, j));
            } else if (std::isnan(g.at(i, j))) {
                fn(i, j, V3{NAN, NAN, NAN});
            } else {
                V3 s = normalSum<kMethod, true>(g, i, j);
                if (s.y <= 0.0f) s = {0.0f, 1.0f, 0.0f};  // no usable neighbour
                fn(i, j, s);
            }
        }
    }
}

template <typename Fn>
inline void dispatchNormalMethod(NormalMethod method, const Fn& fn) {
    switch (method) {
        case NormalMethod::Edge: fn.template operator()<NormalMethod::Edge>(); break;
        case NormalMethod::Triangle: fn.template operator()<NormalMethod::Triangle>(); break;
        case NormalMethod::Quad: fn.template operator()<NormalMethod::Quad>(); break;
    }
}

}  // namespace sierra::analysis::detail

#include <sierra/core/Parallel.h>

namespace sierra::analysis::detail {

template <typename Body>
void forRows(int width, int height, int threads, const Body& body) {
    if (threads <= 0) threads = defaultThreadCount();
    if (threads <= 1 || int64_t(width) * height < kParallelMinSamples) {
        body(0, height);
        return;
    }
    // Several chunks per thread so a slow core does not hold the rest up.
    int chunks = std::min(height, threads * 8);
    parallelChunks(0, height, chunks, [&](int64_t lo, int64_t hi, int) { body(int(lo), int(hi)); }, threads);
}

}  // namespace sierra::analysis::detail
