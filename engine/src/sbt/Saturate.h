#pragma once
// The saturated error and radius of VertexErrors.h over a window of a grid:
// one formula for the whole grid in memory (computeVertexErrors), for the
// tile builder's windows and for the levels a tile file recomputes on load,
// so that all of them give the same floats bit for bit.
//
// A window holds the samples (i0 + a * stride, j0 + b * stride) of a
// (2^n+1)^2 grid, a in [0, w), b in [0, h), in absolute grid coordinates: the
// world positions (i * spacingX, height * verticalScale, j * spacingZ) and so
// the roundings are those of the whole grid. A vertex's children and corners
// outside the window are skipped, exactly as those outside the grid are:
// values near a window's edge are then too small unless the window holds the
// vertex's descendants (the builder's windows reach one tile beyond the tiles
// they keep, which does).

#include "sbt/Rounding.h"

#include <sierra/core/Parallel.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sierra::sbt::detail {

struct SampleWindow {
    int n = 1;                      // grid side 2^n + 1
    int i0 = 0, j0 = 0;             // absolute coordinates of window sample (0, 0)
    int stride = 1;                 // grid samples between window samples
    int w = 0, h = 0;               // window samples per side
    const float* height = nullptr;  // stored heights, row-major, w per row
    float* error = nullptr;         // world height units, as height
    float* radius = nullptr;        // world units, as height
    double sx = 1.0, sz = 1.0, vs = 1.0;

    int i1() const { return i0 + (w - 1) * stride; }
    int j1() const { return j0 + (h - 1) * stride; }
    bool contains(int i, int j) const { return i >= i0 && i <= i1() && j >= j0 && j <= j1(); }
    size_t index(int i, int j) const {
        return size_t((j - j0) / stride) * size_t(w) + size_t((i - i0) / stride);
    }
    double x(int i) const { return i * sx; }
    double y(int i, int j) const { return double(height[index(i, j)]) * vs; }
    double z(int j) const { return j * sz; }
    double dist(int i0_, int j0_, int i1_, int j1_) const {
        double dx = x(i1_) - x(i0_), dy = y(i1_, j1_) - y(i0_, j0_), dz = z(j1_) - z(j0_);
        return std::sqrt(dx * dx + dy * dy + dz * dz);
    }
};

// Smallest x >= 0 with base + step * x >= lo, and the largest with <= hi,
// clipped to [0, count - 1]; empty when first > last.
inline void latticeRange(int base, int step, int lo, int hi, int count, int* first, int* last) {
    auto ceilDiv = [](int a, int b) { return a >= 0 ? (a + b - 1) / b : -((-a) / b); };
    auto floorDiv = [](int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
    *first = std::max(0, ceilDiv(lo - base, step));
    *last = std::min(count - 1, floorDiv(hi - base, step));
}

// Calls fn(i, j, ai, aj, bi, bj) for every vertex of level l (0..2n-1) in
// the box [ilo, ihi] x [jlo, jhi], row by row (the order the tile file stores
// them in), with the hypotenuse (a, b) it splits. rowFn(rowBegin, rowEnd,
// body) runs body(r) for each row index r in [rowBegin, rowEnd): serially or
// split across threads by the caller.
template <typename RowRunner, typename F>
void forLevelVertices(int n, int l, int ilo, int ihi, int jlo, int jhi, RowRunner&& rows, F&& fn) {
    const int S = 1 << n;
    const int k = l >> 1, s = S >> k, hh = s / 2;
    const int count = 1 << k;
    if ((l & 1) == 0) {
        int x0, x1, y0, y1;
        latticeRange(hh, s, ilo, ihi, count, &x0, &x1);
        latticeRange(hh, s, jlo, jhi, count, &y0, &y1);
        if (x0 > x1 || y0 > y1) return;
        rows(y0, y1 + 1, [&, x0, x1](int y) {
            const int j = hh + s * y;
            for (int x = x0; x <= x1; ++x) {
                const int i = hh + s * x;
                const bool main = ((x + y) & 1) == 0;
                fn(i, j, i - hh, main ? j - hh : j + hh, i + hh, main ? j + hh : j - hh);
            }
        });
    } else {
        int t0, t1;
        latticeRange(0, hh, jlo, jhi, 2 * count + 1, &t0, &t1);
        if (t0 > t1) return;
        int ax0, ax1, bx0, bx1;
        latticeRange(hh, s, ilo, ihi, count, &ax0, &ax1);     // rows along i
        latticeRange(0, s, ilo, ihi, count + 1, &bx0, &bx1);  // rows along j
        rows(t0, t1 + 1, [&, ax0, ax1, bx0, bx1](int t) {
            const int j = t * hh;
            if ((t & 1) == 0) {
                for (int x = ax0; x <= ax1; ++x) {
                    const int i = hh + s * x;
                    fn(i, j, i - hh, j, i + hh, j);
                }
            } else {
                for (int x = bx0; x <= bx1; ++x) {
                    const int i = s * x;
                    fn(i, j, i, j - hh, i, j + hh);
                }
            }
        });
    }
}

// Rows one after another.
struct SerialRows {
    template <typename Body>
    void operator()(int begin, int end, Body&& body) const {
        for (int r = begin; r < end; ++r) body(r);
    }
};

// Rows split across `threads` (serially when the level is small).
struct ParallelRows {
    int threads = 1;
    int64_t rowWork = 1;  // vertices per row, to keep small levels serial
    template <typename Body>
    void operator()(int begin, int end, Body&& body) const {
        const int64_t count = end - begin;
        int t = count * rowWork < 8192 ? 1 : threads;
        const int chunks = t <= 1 ? 1 : int(std::min<int64_t>(count, int64_t(t) * 4));
        parallelChunks(
            begin, end, chunks,
            [&](int64_t lo, int64_t hi, int) {
                for (int64_t r = lo; r < hi; ++r) body(int(r));
            },
            t);
    }
};

// Saturates the vertices of levels hi down to lo (hi >= lo) inside the window,
// finest first, keeping the stored values where keep(i, j) is true. Every
// vertex of those levels in the window must lie on its lattice.
template <typename Keep>
void saturateLevels(const SampleWindow& g, int hi, int lo, int threads, Keep&& keep) {
    const int n = g.n;
    for (int l = hi; l >= lo; --l) {
        const int k = l >> 1, S = 1 << n, s = S >> k, hh = s / 2;
        const bool hasChildren = l + 1 < 2 * n;
        int childOff[4][2], cornerOff[4][2];
        if ((l & 1) == 0) {
            const int c[4][2] = {{hh, 0}, {-hh, 0}, {0, hh}, {0, -hh}};
            const int v[4][2] = {{hh, hh}, {-hh, hh}, {hh, -hh}, {-hh, -hh}};
            std::copy(&c[0][0], &c[0][0] + 8, &childOff[0][0]);
            std::copy(&v[0][0], &v[0][0] + 8, &cornerOff[0][0]);
        } else {
            const int q = hh / 2;
            const int c[4][2] = {{q, q}, {-q, q}, {q, -q}, {-q, -q}};
            const int v[4][2] = {{hh, 0}, {-hh, 0}, {0, hh}, {0, -hh}};
            std::copy(&c[0][0], &c[0][0] + 8, &childOff[0][0]);
            std::copy(&v[0][0], &v[0][0] + 8, &cornerOff[0][0]);
        }
        const int childCount = hasChildren ? 4 : 0;
        const ParallelRows rows{threads, int64_t(1) << k};
        forLevelVertices(n, l, g.i0, g.i1(), g.j0, g.j1(), rows,
                         [&](int i, int j, int ai, int aj, int bi, int bj) {
                             if (keep(i, j)) return;
                             double e = std::fabs(g.y(i, j) - 0.5 * (g.y(ai, aj) + g.y(bi, bj)));
                             double r = 0.0;
                             float emax = float(e);
                             for (int c = 0; c < childCount; ++c) {
                                 const int ci = i + childOff[c][0], cj = j + childOff[c][1];
                                 if (!g.contains(ci, cj)) continue;
                                 const size_t ch = g.index(ci, cj);
                                 emax = std::max(emax, g.error[ch]);
                                 r = std::max(r, g.dist(i, j, ci, cj) + double(g.radius[ch]));
                             }
                             for (int c = 0; c < 4; ++c) {
                                 const int vi = i + cornerOff[c][0], vj = j + cornerOff[c][1];
                                 if (!g.contains(vi, vj)) continue;
                                 r = std::max(r, g.dist(i, j, vi, vj));
                             }
                             const size_t m = g.index(i, j);
                             g.error[m] = emax;
                             g.radius[m] = roundUp(r);
                         });
    }
}

}  // namespace sierra::sbt::detail
