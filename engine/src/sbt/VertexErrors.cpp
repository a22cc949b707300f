#include <sierra/sbt/VertexErrors.h>

#include "sbt/Saturate.h"

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
    const int side = field.width();
    VertexErrors out;
    out.n = n;
    out.side = side;
    out.error.assign(size_t(side) * side, 0.0f);
    out.radius.assign(size_t(side) * side, 0.0f);
    const detail::SampleWindow window{.n = n,
                                      .w = side,
                                      .h = side,
                                      .height = field.samples().data(),
                                      .error = out.error.data(),
                                      .radius = out.radius.data(),
                                      .sx = field.spacingX(),
                                      .sz = field.spacingZ(),
                                      .vs = field.verticalScale()};
    detail::saturateLevels(window, 2 * n - 1, 0, threads, [](int, int) { return false; });
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
