#pragma once
// Pieces shared by the analysis sources: world heights with NaN for no data,
// and the unnormalised vertex normal of each method.

#include <sierra/analysis/Normals.h>
#include <sierra/terrain/Heightfield.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

// Before a loop whose stores never alias its loads: GCC vectorises it
// without run-time alias checks. Other compilers (Clang: the fuzz build) keep
// their own checks.
#if defined(__GNUC__) && !defined(__clang__)
#define SIERRA_IVDEP _Pragma("GCC ivdep")
#else
#define SIERRA_IVDEP
#endif

namespace sierra::analysis::detail {

// World heights: raw[k] * scale, with raw either the heightfield's own
// samples or, where it has a no-data mask, a copy with NaN for no data, so
// that a stencil touching no data yields NaN by plain arithmetic.
struct WorldGrid {
    int width = 0;
    int height = 0;
    float spacingX = 1.0f;
    float spacingZ = 1.0f;
    bool hasNoData = false;
    const float* raw = nullptr;
    float scale = 1.0f;  // the vertical scale
    std::vector<float> storage;

    WorldGrid() = default;
    WorldGrid(const WorldGrid&) = delete;  // raw may point into storage
    WorldGrid& operator=(const WorldGrid&) = delete;

    float at(int64_t k) const { return raw[k] * scale; }
    float at(int i, int j) const { return at(int64_t(j) * width + i); }
};

// Fills g (no copy of the heights unless the field has a no-data mask).
void makeWorldGrid(const terrain::Heightfield& field, int threads, WorldGrid& g);

// Runs body(rowBegin, rowEnd) over the rows, in parallel when the grid is
// large enough to pay for it. Rows are independent, so the result does not
// depend on the thread count.
template <typename Body>
void forRows(int width, int height, int threads, const Body& body);

struct V3 {
    float x, y, z;
};
inline V3 operator+(V3 a, V3 b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline V3 cross(V3 a, V3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
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
inline V3 triangleNormal(V3 a, V3 b) {
    return normalized(cross(b, a));
}

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
            ok[k] =
                ni >= 0 && nj >= 0 && ni < g.width && nj < g.height && !std::isnan(g.at(ni, nj));
            e[k] = {float(kRingDi[k]) * g.spacingX, ok[k] ? g.at(ni, nj) - yc : 0.0f,
                    float(kRingDj[k]) * g.spacingZ};
        } else {
            ok[k] = true;
            e[k] = {float(kRingDi[k]) * g.spacingX, g.at(ni, nj) - yc,
                    float(kRingDj[k]) * g.spacingZ};
        }
    }
    if constexpr (kMethod == NormalMethod::Edge) {
        // Mean edge slope per axis: central where both edges exist.
        auto axisSlope = [&](int plus, int minus, float step) {
            float sum = 0.0f;
            int n = 0;
            if (ok[plus]) {
                sum += e[plus].y / step;
                ++n;
            }
            if (ok[minus]) {
                sum -= e[minus].y / step;
                ++n;
            }
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

// Unnormalised normals of vertices [iLo, iHi) of interior row j (all 8
// neighbours in the grid, no missing data) into ox, oy, oz: the same sums as
// normalSum, written as one branch-free loop over restrict pointers so that
// the compiler vectorises it.
template <NormalMethod kMethod>
inline void interiorNormalSums(const WorldGrid& g, int j, int iLo, int iHi, float* __restrict ox,
                               float* __restrict oy, float* __restrict oz) {
    const float* __restrict ys = g.raw + size_t(j - 1) * size_t(g.width);
    const float* __restrict yc = ys + g.width;
    const float* __restrict yn = yc + g.width;
    const float hx = g.spacingX, hz = g.spacingZ, k = g.scale;
    for (int i = iLo; i < iHi; ++i) {
        const float c = yc[i] * k;
        const V3 e{hx, yc[i + 1] * k - c, 0.0f}, w{-hx, yc[i - 1] * k - c, 0.0f};
        const V3 n{0.0f, yn[i] * k - c, hz}, s{0.0f, ys[i] * k - c, -hz};
        V3 sum;
        if constexpr (kMethod == NormalMethod::Edge) {
            sum = {-(e.y - w.y) / (2.0f * hx), 1.0f, -(n.y - s.y) / (2.0f * hz)};
        } else if constexpr (kMethod == NormalMethod::Triangle) {
            sum = triangleNormal(e, n) + triangleNormal(n, w) + triangleNormal(w, s) +
                  triangleNormal(s, e);
        } else {
            const V3 ne{hx, yn[i + 1] * k - c, hz}, nw{-hx, yn[i - 1] * k - c, hz};
            const V3 sw{-hx, ys[i - 1] * k - c, -hz}, se{hx, ys[i + 1] * k - c, -hz};
            sum = normalized(triangleNormal(e, ne) + triangleNormal(ne, n)) +
                  normalized(triangleNormal(n, nw) + triangleNormal(nw, w)) +
                  normalized(triangleNormal(w, sw) + triangleNormal(sw, s)) +
                  normalized(triangleNormal(s, se) + triangleNormal(se, e));
        }
        ox[i] = sum.x;
        oy[i] = sum.y;
        oz[i] = sum.z;
    }
}

// Calls row(j, ox, oy, oz) for every row of [j0, j1) with the unnormalised
// normals of the whole row in ox, oy, oz (NaN for no-data samples).
template <NormalMethod kMethod, typename Fn>
inline void forNormalRows(const WorldGrid& g, int j0, int j1, const Fn& row) {
    std::vector<float> buf(size_t(g.width) * 3);
    float* ox = buf.data();
    float* oy = ox + g.width;
    float* oz = oy + g.width;
    std::vector<uint8_t> columnOk;  // no data: column i of rows j - 1 ... j + 1 has none
    auto checked = [&](int i, int j) {
        V3 s{NAN, NAN, NAN};
        if (!std::isnan(g.at(i, j))) {
            s = normalSum<kMethod, true>(g, i, j);
            if (s.y <= 0.0f) s = {0.0f, 1.0f, 0.0f};  // no usable neighbour
        }
        ox[i] = s.x;
        oy[i] = s.y;
        oz[i] = s.z;
    };
    for (int j = j0; j < j1; ++j) {
        if (j == 0 || j == g.height - 1 || g.width < 3) {
            for (int i = 0; i < g.width; ++i) checked(i, j);
        } else if (!g.hasNoData) {
            checked(0, j);
            interiorNormalSums<kMethod>(g, j, 1, g.width - 1, ox, oy, oz);
            checked(g.width - 1, j);
        } else {
            // The stretches whose 3x3 neighbourhoods have no data missing
            // take the interior sums, the samples beside no data one by one.
            const size_t w = size_t(g.width);
            const float* ys = g.raw + size_t(j - 1) * w;
            columnOk.resize(w);
            for (size_t i = 0; i < w; ++i)
                columnOk[i] =
                    !std::isnan(ys[i]) && !std::isnan(ys[i + w]) && !std::isnan(ys[i + 2 * w]);
            auto full = [&](int i) { return columnOk[i - 1] && columnOk[i] && columnOk[i + 1]; };
            checked(0, j);
            for (int i = 1; i < g.width - 1;) {
                int end = i;
                while (end < g.width - 1 && full(end)) ++end;
                if (end > i) {
                    interiorNormalSums<kMethod>(g, j, i, end, ox, oy, oz);
                    i = end;
                } else {
                    checked(i++, j);
                }
            }
            checked(g.width - 1, j);
        }
        row(j, ox, oy, oz);
    }
}

template <typename Fn>
inline void dispatchNormalMethod(NormalMethod method, const Fn& fn) {
    switch (method) {
        case NormalMethod::Edge:
            fn.template operator()<NormalMethod::Edge>();
            break;
        case NormalMethod::Triangle:
            fn.template operator()<NormalMethod::Triangle>();
            break;
        case NormalMethod::Quad:
            fn.template operator()<NormalMethod::Quad>();
            break;
    }
}

}  // namespace sierra::analysis::detail

#include <sierra/core/Parallel.h>

namespace sierra::analysis::detail {

template <typename Body>
void forRows(int width, int height, int threads, const Body& body) {
    if (threads <= 0) threads = defaultThreadCount();
    if (int64_t(width) * height < kParallelMinSamples) threads = 1;
    // Several chunks per thread so a slow core does not hold the rest up, but
    // at least 64 rows each: a chunk recomputes the normals of a few rows
    // beyond its ends. Chunks run in order on one thread when threads = 1.
    int chunks = std::max(1, std::min(threads * 8, height / 64));
    parallelChunks(
        0, height, chunks, [&](int64_t lo, int64_t hi, int) { body(int(lo), int(hi)); }, threads);
}

}  // namespace sierra::analysis::detail
