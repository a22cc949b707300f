#include <sierra/sbt/VertexErrors.h>

#include "sbt/Rounding.h"

#include <sierra/core/Error.h>
#include <sierra/core/Parallel.h>

#include <algorithm>
#include <bit>
#include <cmath>

namespace sierra::sbt {
namespace {

int trailingZeros(int v, int n) {
    return v == 0 ? n : std::countr_zero(unsigned(v));
}

struct Grid {
    const float* h;
    int side;
    double sx, sz, vs;
    double x(int i) const { return i * sx; }
    double y(int i, int j) const { return double(h[size_t(j) * side + i]) * vs; }
    double z(int j) const { return j * sz; }
    double dist(int i0, int j0, int i1, int j1) const {
        double dx = x(i1) - x(i0), dy = y(i1, j1) - y(i0, j0), dz = z(j1) - z(j0);
        return std::sqrt(dx * dx + dy * dy + dz * dz);
    }
};

// Runs body(t) for t in [0, count) on `threads`, serially for small levels.
template <typename F>
void forRows(int64_t count, int64_t work, int threads, F&& body) {
    if (work < 8192) threads = 1;
    int chunks = threads <= 1 ? 1 : int(std::min<int64_t>(count, int64_t(threads) * 4));
    parallelChunks(
        0, count, chunks,
        [&](int64_t lo, int64_t hi, int) {
            for (int64_t t = lo; t < hi; ++t) body(int(t));
        },
        threads);
}

}  // namespace

bool isSbtGrid(const terrain::Heightfield& field, int* n) {
    int w = field.width();
    if (w < 3 || field.height() != w) return false;
    int s = w - 1;
    if (!std::has_single_bit(unsigned(s))) return false;
    if (n) *n = std::countr_zero(unsigned(s));
    return true;
}

namespace {
// n of a (2^n + 1)^2 grid the SBT can index; anything else is an error.
int checkedSbtLevels(const terrain::Heightfield& field) {
    int n = 0;
    SIERRA_CHECK(isSbtGrid(field, &n), "the SBT needs a (2^n+1)^2 grid with n >= 1, got ",
                 field.width(), "x", field.height(), " (pad it with padToPowerOfTwoPlusOne)");
    SIERRA_CHECK(field.width() <= kMaxSbtSide, "a ", field.width(), "x", field.width(),
                 " grid has more vertices than 32-bit strip indices address (at most ", kMaxSbtSide,
                 "x", kMaxSbtSide, ")");
    return n;
}
}  // namespace

int vertexLevel(int i, int j, int n) {
    int ti = trailingZeros(i, n), tj = trailingZeros(j, n);
    if (ti >= n && tj >= n) return -1;
    if (ti == tj) return 2 * (n - 1 - ti);
    return 2 * (n - 1 - std::min(ti, tj)) + 1;
}

bool hypotenuseEndpoints(int i, int j, int n, int* ai, int* aj, int* bi, int* bj) {
    int ti = trailingZeros(i, n), tj = trailingZeros(j, n);
    if (ti >= n && tj >= n) {
        *ai = *bi = i, *aj = *bj = j;
        return false;
    }
    if (ti == tj) {
        int h = 1 << ti, s = 2 * h;
        bool main = (((i / s) + (j / s)) & 1) == 0;
        *ai = i - h, *bi = i + h;
        *aj = main ? j - h : j + h;
        *bj = main ? j + h : j - h;
    } else if (ti < tj) {
        int h = 1 << ti;
        *ai = i - h, *bi = i + h, *aj = *bj = j;
    } else {
        int h = 1 << tj;
        *ai = *bi = i, *aj = j - h, *bj = j + h;
    }
    return true;
}

VertexErrors computeVertexErrors(const terrain::Heightfield& field, int threads) {
    const int n = checkedSbtLevels(field);
    if (threads <= 0) threads = defaultThreadCount();
    const int side = field.width(), S = side - 1;
    VertexErrors out;
    out.n = n;
    out.side = side;
    out.error.assign(size_t(side) * side, 0.0f);
    out.radius.assign(size_t(side) * side, 0.0f);
    const Grid g{field.samples().data(), side, field.spacingX(), field.spacingZ(),
                 field.verticalScale()};
    float* err = out.error.data();
    float* rad = out.radius.data();

    // One vertex: hypotenuse (a, b), children at m + childOff (if any), corners
    // at m + cornerOff; everything out of the domain skipped.
    auto process = [&](int i, int j, int ai, int aj, int bi, int bj, const int(*childOff)[2],
                       int childCount, const int(*cornerOff)[2]) {
        double e = std::fabs(g.y(i, j) - 0.5 * (g.y(ai, aj) + g.y(bi, bj)));
        double r = 0.0;
        float emax = float(e);
        for (int k = 0; k < childCount; ++k) {
            int ci = i + childOff[k][0], cj = j + childOff[k][1];
            if (ci < 0 || ci > S || cj < 0 || cj > S) continue;
            size_t c = size_t(cj) * side + ci;
            emax = std::max(emax, err[c]);
            r = std::max(r, g.dist(i, j, ci, cj) + double(rad[c]));
        }
        for (int k = 0; k < 4; ++k) {
            int vi = i + cornerOff[k][0], vj = j + cornerOff[k][1];
            if (vi < 0 || vi > S || vj < 0 || vj > S) continue;
            r = std::max(r, g.dist(i, j, vi, vj));
        }
        size_t m = size_t(j) * side + i;
        err[m] = emax;
        rad[m] = roundUp(r);
    };

    for (int l = 2 * n - 1; l >= 0; --l) {
        const int k = l >> 1, s = S >> k, h = s / 2;
        const bool hasChildren = l + 1 < 2 * n;
        const int count = 1 << k;  // squares per side at this level
        if ((l & 1) == 0) {
            const int childOff[4][2] = {{h, 0}, {-h, 0}, {0, h}, {0, -h}};
            const int cornerOff[4][2] = {{h, h}, {-h, h}, {h, -h}, {-h, -h}};
            forRows(count, int64_t(count) * count, threads, [&](int y) {
                int j = h + s * y;
                for (int x = 0; x < count; ++x) {
                    int i = h + s * x;
                    bool main = ((x + y) & 1) == 0;
                    process(i, j, i - h, main ? j - h : j + h, i + h, main ? j + h : j - h,
                            childOff, hasChildren ? 4 : 0, cornerOff);
                }
            });
        } else {
            const int q = h / 2;
            const int childOff[4][2] = {{q, q}, {-q, q}, {q, -q}, {-q, -q}};
            const int cornerOff[4][2] = {{h, 0}, {-h, 0}, {0, h}, {0, -h}};
            forRows(2 * count + 1, int64_t(2 * count + 1) * count, threads, [&](int t) {
                int j = t * h;
                if ((t & 1) == 0) {  // midpoints of edges along i
                    for (int x = 0; x < count; ++x) {
                        int i = h + s * x;
                        process(i, j, i - h, j, i + h, j, childOff, hasChildren ? 4 : 0, cornerOff);
                    }
                } else {  // midpoints of edges along j
                    for (int x = 0; x <= count; ++x) {
                        int i = s * x;
                        process(i, j, i, j - h, i, j + h, childOff, hasChildren ? 4 : 0, cornerOff);
                    }
                }
            });
        }
    }
    return out;
}

std::vector<float> buildMorphBase(const terrain::Heightfield& field, int threads) {
    const int n = checkedSbtLevels(field);
    if (threads <= 0) threads = defaultThreadCount();
    const int side = field.width();
    std::vector<float> base(size_t(side) * side);
    forRows(side, int64_t(side) * side, threads, [&](int j) {
        for (int i = 0; i < side; ++i) {
            int ai, aj, bi, bj;
            float v;
            if (hypotenuseEndpoints(i, j, n, &ai, &aj, &bi, &bj))
                v = 0.5f * (field.worldHeight(ai, aj) + field.worldHeight(bi, bj));
            else
                v = field.worldHeight(i, j);
            base[size_t(j) * side + i] = v;
        }
    });
    return base;
}

}  // namespace sierra::sbt
