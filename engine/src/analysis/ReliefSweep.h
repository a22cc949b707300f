#pragma once
// The horizon sweep shared by the relief fields (Relief.cpp): the digital
// lines of an azimuth, the general sweep of one line (any radius) and the
// fast sweep of groups of lines (no radius). docs/relief.md describes both.

#include <sierra/analysis/Normals.h>
#include <sierra/analysis/ReliefLines.h>
#include <sierra/core/Parallel.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace sierra::analysis::relief {

constexpr double kPi = 3.14159265358979323846;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
// The slope recorded where nothing lies ahead (the grid's edge looking out):
// its angle is -pi/2.
constexpr float kNoOccluder = -std::numeric_limits<float>::infinity();

// The heights a sweep reads: world height = raw * scale (scale negated for the
// inverted surface of negative openness), and the region that casts and
// receives (columns < validW, rows < validH).
struct Surface {
    int width = 0, height = 0;
    int validW = 0, validH = 0;
    double sx = 1.0, sz = 1.0;
    float scale = 1.0f;
    const float* raw = nullptr;
    const uint8_t* mask = nullptr;  // null: every sample has data
    bool ok(int i, int j) const { return !mask || mask[size_t(j) * size_t(width) + size_t(i)]; }
    float h(int i, int j) const { return raw[size_t(j) * size_t(width) + size_t(i)] * scale; }
    size_t index(int i, int j) const { return size_t(j) * size_t(width) + size_t(i); }
    size_t samples() const { return size_t(width) * size_t(height); }
};

// --- the digital lines of one azimuth (analysis/ReliefLines.h) ------------
using Lines = DigitalLines;

inline Lines makeLines(double degrees, const Surface& s) {
    return digitalLines(degrees, s.sx, s.sz, s.validW, s.validH);
}

// --- the sweep ---------------------------------------------------------------
// One profile: points in sweep order, farthest along the azimuth first, so t
// (the distance along the azimuth, world units) strictly decreases.
enum : uint8_t { kCast = 1, kReceive = 2 };

struct Profile {
    std::vector<float> h;
    std::vector<double> t;
    std::vector<double> w;  // across the azimuth (world units): t and w give true distances
    std::vector<uint8_t> flags;
    std::vector<int64_t> sample;  // output index of a receiving point
    std::vector<int> best;        // the tangent point of a receiving point, -1: none
    std::vector<float> slope;     // the result: tan of the horizon elevation
    std::vector<int> stack;
    std::vector<int> hull;
    int n = 0;
    void reserve(size_t count) {
        h.resize(count);
        t.resize(count);
        w.resize(count);
        best.resize(count);
        flags.resize(count);
        sample.resize(count);
        slope.resize(count);
        stack.resize(count);
        hull.resize(count);
    }
};

// Gathers line o of `l` into P in sweep order (cell centres included on a
// diagonal, see ReliefSweep.cpp).
void gatherLine(const Surface& s, const Lines& l, int o, Profile& P);
// The occluder (P.best) of every receiving point with a search radius.
void sweepRadius(Profile& P, double radius);
// P.slope from P.best: tan of the horizon at the occluder's true distance.
void finishSlopes(Profile& P);

// Lines swept together by the fast path. At each major step their samples
// are neighbours across the azimuth: one row segment (j-major azimuths: 4
// cache lines of one page, fetched together) or one column segment whose
// rows the next 15 steps reuse (i-major), where one line at a time would
// fetch a cache line, and often a page, per sample.
constexpr int kGroup = 64;

// A hull vertex of the fast sweep, by value so that the pop test reads one
// entry: `up` is the projected slope from it to the vertex below it (-inf for
// the bottom one, which is then never popped). With t_p < t_b < t_c, b lies on
// or under the line from p to c exactly when slope(p, b) <= slope(b, c), so
// the pop test is h_b - h_p <= up_b (t_b - t_p): one product, no division.
struct Vertex {
    double t, w, h, up;
};

// Per-chunk scratch of the fast sweep: one hull per line of a group, and one
// step's results (tan of the horizon, output index) for the finisher.
struct GroupScratch {
    size_t capacity = 0;
    // Line e's hull at [e * capacity, (e + 1) * capacity), left uninitialised:
    // a hull uses the first few vertices of its room, and only the pages it
    // touches are ever mapped.
    std::unique_ptr<Vertex[]> hulls;
    float slope[kGroup];
    int64_t index[kGroup];
    int top[kGroup];
    explicit GroupScratch(size_t perLine)
        : capacity(perLine), hulls(std::make_unique_for_overwrite<Vertex[]>(perLine * kGroup)) {}
};

// One step of Stewart's sweep: the hull is the upper convex hull, in (t, h),
// of the casting points behind the new one (nearest on top). Pops the
// vertices on or under the line from (t, h) to the vertex below them: they
// lie under the new hull and can hide nothing from any later point, so every
// point is pushed and popped at most once. The top vertex left is where the
// tangent from (t, h) touches the hull, the occluder. Pushes (t, w, h) and
// returns tan of its horizon (-inf with no vertex) at the occluder's true
// distance. kOnRay: every vertex lies
// on the azimuth's ray through the sample (a grid-aligned azimuth), so that
// distance is dt.
template <bool kOnRay>
inline float addToHull(Vertex* hull, int& top, double t, double w, double h) {
    if (top == 0) {
        hull[top++] = {t, w, h, -std::numeric_limits<double>::infinity()};
        return kNoOccluder;
    }
    const Vertex* v = hull + top - 1;
    while (v->h - h <= v->up * (v->t - t)) --v;
    top = int(v - hull) + 1;
    const Vertex& q = *v;
    const double dt = q.t - t, dw = q.w - w, dh = q.h - h;
    const double up = dh / dt;
    hull[top] = {t, w, h, up};
    ++top;
    if constexpr (kOnRay) return float(up);
    return float(dh / std::sqrt(dt * dt + dw * dw));
}

// Lines [o0, o0 + count) (count <= kGroup) without a radius, step by step in
// sweep order: Stewart's sweep (docs/relief.md), one hull per line, on the
// points gatherLine would gather (a diagonal's centres only where the drawn
// diagonal crosses it; the others lie on the profile and change nothing). finish(slope, index, g0,
// g1) gets each step's samples: lanes [g0, g1) of the kGroup-long arrays (the others hold stale
// values, so a finisher may transform all kGroup lanes in one fixed-length loop that vectorises).
template <bool kDiagonal, bool kAligned, bool kMask, typename Finish>
void sweepGroup(const Surface& s, const Lines& l, int o0, int count, GroupScratch& g,
                const Finish& finish) {
    auto [mBegin, mEnd] = lineSpan(l, o0, count);
    if (mBegin >= mEnd) return;
    // t = major * tM + minor * tN, w likewise, k = major * kM + minor * kN
    const double tI = s.sx * l.ux, tJ = s.sz * l.uz, wI = -s.sx * l.uz, wJ = s.sz * l.ux;
    const double tM = l.iMajor ? tI : tJ, tN = l.iMajor ? tJ : tI;
    const double wM = l.iMajor ? wI : wJ, wN = l.iMajor ? wJ : wI;
    const int64_t kM = l.iMajor ? 1 : s.width, kN = l.iMajor ? s.width : 1;
    const int* r = l.r.data();
    const float* raw = s.raw;
    const uint8_t* mask = s.mask;
    const float scale = s.scale;
    const int N = l.minorCount;
    for (int e = 0; e < count; ++e) g.top[e] = 0;
    Vertex* hulls = g.hulls.get();
    const size_t capacity = g.capacity;
    int pg0 = 0, pg1 = 0, pBase = 0;  // the previous step's active lines
    const int steps = mEnd - mBegin;
    for (int c = 0; c < steps; ++c) {
        const int m = l.look > 0 ? mEnd - 1 - c : mBegin + c;
        const int base = o0 + r[m];
        const int g0 = std::max(0, -base), g1 = std::min(count, N - base);
        const double tm = double(m) * tM, wm = double(m) * wM;
        const int64_t km = int64_t(m) * kM;
        for (int e = g0; e < g1; ++e) {
            const int n = base + e;
            const int64_t k = km + int64_t(n) * kN;
            const double t = tm + double(n) * tN, w = wm + double(n) * wN;
            Vertex* hull = hulls + size_t(e) * capacity;
            int top = g.top[e];
            if constexpr (kDiagonal) {
                // The centre of the cell from this line's previous sample
                // (major m + look, minor pBase + e).
                if (e >= pg0 && e < pg1) {
                    const int pm = m + l.look, pn = pBase + e;
                    const int i = l.iMajor ? m : n, j = l.iMajor ? n : m;
                    const int pi = l.iMajor ? pm : pn, pj = l.iMajor ? pn : pm;
                    const int ci = std::min(i, pi), cj = std::min(j, pj);
                    const bool even = ((ci + cj) & 1) == 0;
                    const int64_t ka = int64_t(cj) * s.width + (even ? ci : ci + 1);
                    const int64_t kb = int64_t(cj + 1) * s.width + (even ? ci + 1 : ci);
                    // A drawn diagonal along the line puts the centre on the
                    // segment between this sample and the previous one, where it
                    // cannot change the hull: only crossing diagonals are added.
                    const bool crossing = even != (l.slope > 0.0);
                    if (crossing && (!kMask || (mask[ka] && mask[kb]))) {
                        const double pt = double(pm) * tM + double(pn) * tN;
                        const double pw = double(pm) * wM + double(pn) * wN;
                        addToHull<kAligned>(hull, top, 0.5 * (t + pt), 0.5 * (w + pw),
                                            double(0.5f * (raw[ka] * scale + raw[kb] * scale)));
                    }
                }
            }
            g.index[e] = k;
            if (kMask && !mask[k]) {
                g.slope[e] = kNaN;
                g.top[e] = top;
                continue;
            }
            g.slope[e] = addToHull<kAligned>(hull, top, t, w, double(raw[k] * scale));
            g.top[e] = top;
        }
        if (g1 > g0) finish(g.slope, g.index, g0, g1);
        pg0 = g0;
        pg1 = g1;
        pBase = base;
    }
}

// The horizon slope (tan of its elevation) of every sample of the region in
// azimuth `degrees`, -inf where nothing casts ahead and NaN at no-data
// samples, handed over in steps of up to kGroup to finish(slope, index, g0,
// g1) (see sweepGroup): index[e] is the output index j * width + i of
// slope[e]. The padding is never visited.
template <typename Finish>
void sweepAzimuth(const Surface& s, double degrees, double radius, int threads,
                  const Finish& finish) {
    const Lines l = makeLines(degrees, s);
    const int lines = l.lineEnd - l.lineBegin;
    const size_t capacity = size_t(l.diagonal ? 2 * l.majorCount : l.majorCount);
    // A radius at least the region's extent along the azimuth changes nothing.
    const double extent =
        std::fabs(double(s.validW) * s.sx * l.ux) + std::fabs(double(s.validH) * s.sz * l.uz);
    const bool limited = radius > 0.0 && radius < extent;
    if (threads <= 0) threads = defaultThreadCount();
    if (s.samples() < size_t(kParallelMinSamples)) threads = 1;
    // Without a radius the chunks hold groups of kGroup lines, else lines.
    const int units = limited ? lines : (lines + kGroup - 1) / kGroup;
    const int chunks = std::max(1, std::min(units, threads * 16));
    parallelChunks(
        0, units, chunks,
        [&](int64_t lo, int64_t hi, int) {
            if (limited) {
                Profile P;
                P.reserve(capacity);
                std::vector<float> slope(capacity);
                std::vector<int64_t> index(capacity);
                for (int64_t q = lo; q < hi; ++q) {
                    gatherLine(s, l, l.lineBegin + int(q), P);
                    sweepRadius(P, radius);
                    finishSlopes(P);
                    int count = 0;
                    for (int k = 0; k < P.n; ++k)
                        if (P.sample[k] >= 0) {
                            slope[count] = P.slope[k];
                            index[count++] = P.sample[k];
                        }
                    for (int c0 = 0; c0 < count; c0 += kGroup) {
                        float laneSlope[kGroup];
                        int64_t laneIndex[kGroup];
                        const int lanes = std::min(kGroup, count - c0);
                        for (int e = 0; e < kGroup; ++e) {
                            laneSlope[e] = e < lanes ? slope[c0 + e] : 0.0f;
                            laneIndex[e] = e < lanes ? index[c0 + e] : 0;
                        }
                        finish(laneSlope, laneIndex, 0, lanes);
                    }
                }
                return;
            }
            GroupScratch scratch(capacity);
            auto run = [&]<bool kDiagonal, bool kAligned, bool kMask>() {
                for (int64_t q = lo; q < hi; ++q) {
                    const int o0 = l.lineBegin + int(q) * kGroup;
                    sweepGroup<kDiagonal, kAligned, kMask>(
                        s, l, o0, std::min(kGroup, l.lineEnd - o0), scratch, finish);
                }
            };
            if (l.diagonal)
                s.mask ? run.template operator()<true, true, true>()
                       : run.template operator()<true, true, false>();
            else if (l.slope == 0.0)
                s.mask ? run.template operator()<false, true, true>()
                       : run.template operator()<false, true, false>();
            else
                s.mask ? run.template operator()<false, false, true>()
                       : run.template operator()<false, false, false>();
        },
        threads);
}

}  // namespace sierra::analysis::relief
