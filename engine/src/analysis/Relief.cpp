#include <sierra/analysis/Relief.h>

#include <sierra/analysis/Normals.h>
#include <sierra/core/Error.h>
#include <sierra/core/Parallel.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace sierra::analysis {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
// The slope recorded where nothing lies ahead (the grid's edge looking out):
// its angle is -pi/2.
constexpr float kNoOccluder = -std::numeric_limits<float>::infinity();
// The most azimuths a call takes: 1024 at 4097^2 is already 64 GiB of angles.
constexpr int kMaxDirections = 1024;

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

void validate(const terrain::Heightfield& field, const HorizonOptions& o, const char* caller) {
    SIERRA_CHECK(!field.empty(), caller, ": the heightfield is empty");
    SIERRA_CHECK(o.validWidth >= 0 && o.validWidth <= field.width(), caller,
                 ": validWidth must be in 0..", field.width(), " (0 = the whole grid), got ",
                 o.validWidth);
    SIERRA_CHECK(o.validHeight >= 0 && o.validHeight <= field.height(), caller,
                 ": validHeight must be in 0..", field.height(), " (0 = the whole grid), got ",
                 o.validHeight);
    SIERRA_CHECK(std::isfinite(o.radius) && o.radius >= 0.0f, caller,
                 ": radius must be finite and >= 0 (0 = the whole grid), got ", o.radius);
    SIERRA_CHECK(o.threads >= 0, caller, ": threads must be >= 0 (0 = the default), got ",
                 o.threads);
}

void validateDirections(const HorizonOptions& o, const char* caller) {
    SIERRA_CHECK(o.directions >= 1 && o.directions <= kMaxDirections, caller,
                 ": directions must be in 1..", kMaxDirections, ", got ", o.directions);
    SIERRA_CHECK(std::isfinite(o.firstAzimuth), caller, ": firstAzimuth must be finite, got ",
                 o.firstAzimuth);
}

Surface makeSurface(const terrain::Heightfield& field, const HorizonOptions& o, bool inverted) {
    Surface s;
    s.width = field.width();
    s.height = field.height();
    s.validW = o.validWidth > 0 ? o.validWidth : s.width;
    s.validH = o.validHeight > 0 ? o.validHeight : s.height;
    s.sx = field.spacingX();
    s.sz = field.spacingZ();
    s.scale = inverted ? -field.verticalScale() : field.verticalScale();
    s.raw = field.samples().data();
    s.mask = field.hasMask() ? field.mask().data() : nullptr;
    return s;
}

// --- the digital lines of one azimuth ----------------------------------------
// The azimuth's direction in grid index space is (gi, gj) = (sin a / sx,
// -cos a / sz). Its major axis is the one with the larger |component| (i on a
// tie); `slope` is the minor index change per +1 step of the major index, so
// |slope| <= 1. Line o holds the samples (major m, minor o + r(m)) with
// r(m) = floor(slope * m + 0.5): every sample (m, n) lies on exactly the line
// o = n - r(m). Grid-aligned azimuths (slope 0 or +-1) are straight grid lines.
struct Lines {
    double ux = 0.0, uz = 0.0;  // the azimuth's world unit vector (x, z)
    bool iMajor = true;
    int look = 1;  // +1: the azimuth points towards increasing major index
    double slope = 0.0;
    bool diagonal = false;  // |slope| == 1: cell centres join the profile
    int majorCount = 0, minorCount = 0;
    int lineBegin = 0, lineEnd = 0;  // offsets o in [lineBegin, lineEnd)
    std::vector<int> r;              // r(m), m in [0, majorCount)
};

Lines makeLines(double degrees, const Surface& s) {
    Lines l;
    const double a = std::fmod(double(degrees), 360.0) * kPi / 180.0;
    double sa = std::sin(a), ca = std::cos(a);
    // sin(pi) is 1.2e-16, not 0: the four axis azimuths are snapped onto the axes.
    if (std::fabs(sa) < 1e-12) sa = 0.0;
    if (std::fabs(ca) < 1e-12) ca = 0.0;
    l.ux = sa;
    l.uz = -ca;
    const double gi = sa / s.sx, gj = -ca / s.sz;
    l.iMajor = std::fabs(gi) >= std::fabs(gj);
    const double major = l.iMajor ? gi : gj, minor = l.iMajor ? gj : gi;
    l.look = major > 0.0 ? 1 : -1;
    l.slope = minor / major;
    if (std::fabs(std::fabs(l.slope) - 1.0) < 1e-12) l.slope = l.slope > 0.0 ? 1.0 : -1.0;
    l.diagonal = std::fabs(l.slope) == 1.0;
    l.majorCount = l.iMajor ? s.validW : s.validH;
    l.minorCount = l.iMajor ? s.validH : s.validW;
    l.r.resize(size_t(l.majorCount));
    for (int m = 0; m < l.majorCount; ++m) l.r[m] = int(std::floor(l.slope * m + 0.5));
    const int rLo = std::min(l.r.front(), l.r.back()), rHi = std::max(l.r.front(), l.r.back());
    l.lineBegin = -rHi;
    l.lineEnd = l.minorCount - rLo;
    return l;
}

// The major indices [begin, end) where any of lines [o, o + count) lies
// inside the region.
std::pair<int, int> lineSpan(const Lines& l, int o, int count = 1) {
    // r is monotone: non-decreasing for slope >= 0, non-increasing otherwise.
    const int lo = -(o + count - 1), hi = l.minorCount - 1 - o;  // r(m) must lie in [lo, hi]
    auto inside = [&](int m) { return l.r[m] >= lo && l.r[m] <= hi; };
    int begin, end;
    if (l.slope >= 0.0) {
        begin = int(std::lower_bound(l.r.begin(), l.r.end(), lo) - l.r.begin());
        end = int(std::upper_bound(l.r.begin(), l.r.end(), hi) - l.r.begin());
    } else {
        begin =
            int(std::lower_bound(l.r.begin(), l.r.end(), hi, std::greater<int>()) - l.r.begin());
        end = int(std::upper_bound(l.r.begin(), l.r.end(), lo, std::greater<int>()) - l.r.begin());
    }
    if (begin < end && !inside(begin)) begin = end;
    return {begin, end};
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

// True when point b lies on or below the line from p to c, with t_p < t_b and
// t_p < t_c: then b cannot be the horizon of p or of any point before it.
inline bool notAbove(const Profile& P, int p, int b, int c) {
    const double hp = P.h[p], tp = P.t[p];
    return (double(P.h[b]) - hp) * (P.t[c] - tp) <= (double(P.h[c]) - hp) * (P.t[b] - tp);
}
// Projected slopes of p -> q and p -> c compared: true when q is strictly higher.
inline bool steeper(const Profile& P, int p, int q, int c) {
    return !notAbove(P, p, q, c);
}

// The horizon slope of every receiving point from its tangent point: the
// height difference over the true horizontal distance sqrt(dt^2 + dw^2).
void finishSlopes(Profile& P) {
    for (int k = 0; k < P.n; ++k) {
        if (!(P.flags[k] & kReceive)) {
            P.slope[k] = kNaN;
            continue;
        }
        const int q = P.best[k];
        if (q < 0) {
            P.slope[k] = kNoOccluder;
            continue;
        }
        const double dt = P.t[q] - P.t[k], dw = P.w[q] - P.w[k];
        P.slope[k] = float((double(P.h[q]) - double(P.h[k])) / std::sqrt(dt * dt + dw * dw));
    }
}

// With a radius R the occluders of p are the points q with 0 < t_q - t_p <= R.
// A vertex popped from the hull may return once the vertex that hid it moves
// out of range, so the profile is cut into blocks of length R in t (block b:
// t_0 - t in [bR, (b+1)R)). p's occluders are then (a) every point ahead of it
// in its own block and (b) a part of the previous block nearest to p's block:
// its points with t_q <= t_p + R, a set that grows as p moves back towards the
// previous block. (a) is the sweep above with the stack emptied at each block
// start (amortised O(1) per point); (b) is an upper hull built by adding the
// previous block's points in increasing t as p walks its own block in
// increasing t (amortised O(1)), queried by binary search for the tangent
// (O(log hull size)). The whole sweep is O(n log n) at worst and near O(n) on
// terrain, whose profile hulls are short.
void sweepRadius(Profile& P, double radius) {
    const int n = P.n;
    if (n == 0) return;
    const double t0 = P.t[0];
    auto block = [&](int k) { return int64_t(std::floor((t0 - P.t[k]) / radius)); };
    int* stack = P.stack.data();
    int* hull = P.hull.data();
    int prevBegin = -1, prevEnd = -1;  // the previous block's points [begin, end)
    int64_t prevBlock = -2;
    for (int begin = 0; begin < n;) {
        const int64_t b = block(begin);
        int end = begin + 1;
        while (end < n && block(end) == b) ++end;
        // (a) the own block
        int top = 0;
        for (int k = begin; k < end; ++k) {
            const uint8_t f = P.flags[k];
            if (!f) continue;
            while (top >= 2 && notAbove(P, k, stack[top - 1], stack[top - 2])) --top;
            P.best[k] = top ? stack[top - 1] : -1;
            if (f & kCast) stack[top++] = k;
        }
        // (b) the previous block, if it is the adjacent one
        if (prevBlock == b - 1) {
            int size = 0;
            int q = prevEnd - 1;  // the previous block's nearest point
            for (int k = end - 1; k >= begin; --k) {
                if (!(P.flags[k] & kReceive)) continue;
                const double reach = P.t[k] + radius;
                for (; q >= prevBegin && P.t[q] <= reach; --q) {
                    if (!(P.flags[q] & kCast)) continue;
                    // hull[] runs in increasing t; pop vertices on or under the
                    // segment from their left neighbour to q.
                    while (size >= 2 && notAbove(P, hull[size - 2], hull[size - 1], q)) --size;
                    hull[size++] = q;
                }
                if (size == 0) continue;
                // The slope from k along the hull rises, then falls.
                int lo = 0, hi = size - 1;
                while (lo < hi) {
                    const int mid = (lo + hi) / 2;
                    if (steeper(P, k, hull[mid + 1], hull[mid]))
                        lo = mid + 1;
                    else
                        hi = mid;
                }
                if (P.best[k] < 0 || steeper(P, k, hull[lo], P.best[k])) P.best[k] = hull[lo];
            }
        }
        prevBlock = b;
        prevBegin = begin;
        prevEnd = end;
        begin = end;
    }
}

// Gathers line o of `l` into P in sweep order. On a diagonal the profile also
// holds the centre of every cell it crosses: the surface drawn there (the
// 4-8 mesh at full resolution splits cell (ci, cj) by its main diagonal when
// ci + cj is even, else by the anti diagonal) is the midpoint of the cell's
// drawn diagonal, which casts when both its ends have data.
void gatherLine(const Surface& s, const Lines& l, int o, Profile& P) {
    auto [mBegin, mEnd] = lineSpan(l, o);
    P.n = 0;
    if (mBegin >= mEnd) return;
    // t = (x, z) . (ux, uz), w = (x, z) . (-uz, ux)
    const double ax = s.sx * l.ux, az = s.sz * l.uz;
    const double bx = -s.sx * l.uz, bz = s.sz * l.ux;
    int pi = 0, pj = 0;
    double pt = 0.0, pw = 0.0;
    const int count = mEnd - mBegin;
    for (int c = 0; c < count; ++c) {
        const int m = l.look > 0 ? mEnd - 1 - c : mBegin + c;
        const int nn = o + l.r[m];
        const int i = l.iMajor ? m : nn, j = l.iMajor ? nn : m;
        const double t = double(i) * ax + double(j) * az;
        const double w = double(i) * bx + double(j) * bz;
        if (l.diagonal && c > 0) {
            const int ci = std::min(i, pi), cj = std::min(j, pj);
            int ai = ci, aj = cj, bi = ci + 1, bj = cj + 1;
            if ((ci + cj) & 1) {
                ai = ci + 1;
                bi = ci;
            }
            const int k = P.n++;
            P.h[k] = 0.5f * (s.h(ai, aj) + s.h(bi, bj));
            P.t[k] = 0.5 * (t + pt);
            P.w[k] = 0.5 * (w + pw);
            P.flags[k] = s.ok(ai, aj) && s.ok(bi, bj) ? kCast : 0;
            P.sample[k] = -1;
        }
        const int k = P.n++;
        P.h[k] = s.h(i, j);
        P.t[k] = t;
        P.w[k] = w;
        P.flags[k] = s.ok(i, j) ? kCast | kReceive : 0;
        P.sample[k] = int64_t(s.index(i, j));
        pi = i;
        pj = j;
        pt = t;
        pw = w;
    }
}

// Lines swept together by the fast path. At each major step their samples
// are neighbours across the azimuth: one row segment (j-major azimuths) or
// one column segment whose rows the next steps reuse (i-major), so a step
// touches a cache line or a few instead of one per line, and the pages in
// use stay few. 16 floats are one cache line.
constexpr int kGroup = 16;

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
    std::vector<Vertex> hulls;  // line e's hull at [e * capacity, (e + 1) * capacity)
    float slope[kGroup];
    int64_t index[kGroup];
    int top[kGroup];
    explicit GroupScratch(size_t perLine) : capacity(perLine), hulls(perLine * kGroup) {}
};

// Pushes (t, w, h) onto a hull after popping the vertices on or under the
// line from it to the vertex below, and returns tan of its horizon (-inf with
// no vertex) at the tangent vertex's true distance. kOnRay: every vertex lies
// on the azimuth's ray through the sample (a grid-aligned azimuth), so that
// distance is dt.
template <bool kOnRay>
inline float addToHull(Vertex* hull, int& top, double t, double w, double h) {
    if (top == 0) {
        hull[top++] = {t, w, h, -std::numeric_limits<double>::infinity()};
        return kNoOccluder;
    }
    while (hull[top - 1].h - h <= hull[top - 1].up * (hull[top - 1].t - t)) --top;
    const Vertex& q = hull[top - 1];
    const double dt = q.t - t, dw = q.w - w, dh = q.h - h;
    const double up = dh / dt;
    hull[top] = {t, w, h, up};
    ++top;
    if constexpr (kOnRay) return float(up);
    return float(dh / std::sqrt(dt * dt + dw * dw));
}

// Lines [o0, o0 + count) (count <= kGroup) without a radius, step by step in
// sweep order; the same definition as gatherLine, sweepWhole and
// finishSlopes. finish(slope, index, g0, g1) gets each step's samples: lanes
// [g0, g1) of the kGroup-long arrays (the others hold stale values, so a
// finisher may transform all kGroup lanes in one fixed-length loop that
// vectorises).
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
    Vertex* hulls = g.hulls.data();
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

// NaN in the padding (columns >= validW, rows >= validH) of a width x height
// field.
void fillPadding(const Surface& s, float* out, float value) {
    for (int j = 0; j < s.height; ++j) {
        float* row = out + size_t(j) * size_t(s.width);
        if (j >= s.validH)
            std::fill(row, row + s.width, value);
        else
            std::fill(row + s.validW, row + s.width, value);
    }
}

// Runs body(begin, end) over [0, count) on up to `threads` threads, or on the
// calling thread for small counts. Elements are independent.
template <typename Body>
void forRange(size_t count, int threads, const Body& body) {
    if (threads <= 0) threads = defaultThreadCount();
    if (count < size_t(kParallelMinSamples)) threads = 1;
    const int chunks =
        int(std::max<size_t>(1, std::min<size_t>(size_t(threads) * 8, count / 4096)));
    parallelChunks(
        0, int64_t(count), chunks,
        [&](int64_t lo, int64_t hi, int) { body(size_t(lo), size_t(hi)); }, threads);
}

// atan in float for slopes (any float, +-inf and NaN included), absolute
// error below 2e-7 rad: atan(z) on [0, 1] by the degree-17 polynomial of
// Abramowitz and Stegun, "Handbook of Mathematical Functions" (1964), 4.4.49
// (error 2e-8), and atan(x) = pi/2 - atan(1/x) beyond. Written with min and
// a 0/1 factor instead of branches so that loops over it vectorise without
// -fno-trapping-math.
inline float fastAtan(float x) {
    const float ax = std::fabs(x);
    const float z = std::min(ax, 1.0f / ax);
    const float z2 = z * z;
    const float p =
        z * (1.0f +
             z2 * (-0.3333314528f +
                   z2 * (0.1999355085f +
                         z2 * (-0.1420889944f +
                               z2 * (0.1065626393f +
                                     z2 * (-0.0752896400f +
                                           z2 * (0.0429096138f +
                                                 z2 * (-0.0161657367f + z2 * 0.0028662257f))))))));
    const float flip = ax > 1.0f ? 1.0f : 0.0f;
    return std::copysign(p + flip * (1.5707963267948966f - 2.0f * p), x);
}

}  // namespace

Horizons computeHorizons(const terrain::Heightfield& field, const HorizonOptions& options) {
    validate(field, options, "computeHorizons");
    validateDirections(options, "computeHorizons");
    const Surface s = makeSurface(field, options, false);
    Horizons out;
    out.width = s.width;
    out.height = s.height;
    out.directions = options.directions;
    out.firstAzimuth = options.firstAzimuth;
    const size_t n = s.samples();
    out.angle.resize(n * size_t(options.directions));
    for (int d = 0; d < options.directions; ++d) {
        float* a = out.angle.data() + size_t(d) * n;
        fillPadding(s, a, kNaN);
        sweepAzimuth(s, out.azimuthDegrees(d), options.radius, options.threads,
                     [a](float* slope, const int64_t* index, int g0, int g1) {
                         for (int e = 0; e < kGroup; ++e) slope[e] = fastAtan(slope[e]);
                         for (int e = g0; e < g1; ++e) a[index[e]] = slope[e];
                     });
    }
    return out;
}

std::vector<float> sunVisibility(const terrain::Heightfield& field, const SunDisc& sun,
                                 const HorizonOptions& options) {
    validate(field, options, "sunVisibility");
    SIERRA_CHECK(std::isfinite(sun.diameter) && sun.diameter > 0.0f && sun.diameter < 180.0f,
                 "sunVisibility: the sun's diameter must be in (0, 180) degrees, got ",
                 sun.diameter);
    SIERRA_CHECK(std::isfinite(sun.azimuth),
                 "sunVisibility: the sun's azimuth must be finite, got ", sun.azimuth);
    SIERRA_CHECK(std::isfinite(sun.altitude) && sun.altitude >= -90.0f && sun.altitude <= 90.0f,
                 "sunVisibility: the sun's altitude must be in [-90, 90] degrees, got ",
                 sun.altitude);
    const Surface s = makeSurface(field, options, false);
    const size_t n = s.samples();
    std::vector<float> out(n);
    fillPadding(s, out.data(), kNaN);
    const float rho = float(double(sun.diameter) * kPi / 360.0);  // the disc's radius, rad
    const float alt = float(double(sun.altitude) * kPi / 180.0);
    if (sun.altitude < -0.5f * sun.diameter) {
        // Night: the whole disc is below the horizontal.
        for (int j = 0; j < s.validH; ++j)
            for (int i = 0; i < s.validW; ++i) out[s.index(i, j)] = s.ok(i, j) ? 0.0f : kNaN;
        return out;
    }
    float* o = out.data();
    sweepAzimuth(
        s, sun.azimuth, options.radius, options.threads,
        [&](float* slope, const int64_t* index, int g0, int g1) {
            for (int e = 0; e < kGroup; ++e) slope[e] = fastAtan(slope[e]);
            for (int c = g0; c < g1; ++c) {
                const float g = slope[c];
                // The horizon's height over the disc's centre in disc radii; the
                // disc's area above it is the circular segment
                // (acos y - y sqrt(1 - y^2)) / pi.
                const float y = (g - alt) / rho;
                float v;
                if (std::isnan(g))
                    v = kNaN;
                else if (y <= -1.0f)
                    v = 1.0f;
                else if (y >= 1.0f)
                    v = 0.0f;
                else
                    v = float((std::acos(double(y)) - double(y) * std::sqrt(1.0 - double(y) * y)) /
                              kPi);
                o[index[c]] = v;
            }
        });
    return out;
}

std::vector<float> skyViewFactor(const Horizons& horizons) {
    SIERRA_CHECK(horizons.directions >= 1 &&
                     horizons.angle.size() == size_t(horizons.width) * size_t(horizons.height) *
                                                  size_t(horizons.directions),
                 "skyViewFactor: the horizons are empty or inconsistent (", horizons.width, "x",
                 horizons.height, "x", horizons.directions, " for ", horizons.angle.size(),
                 " angles)");
    const size_t n = size_t(horizons.width) * size_t(horizons.height);
    std::vector<float> out(n, 0.0f);
    const int D = horizons.directions;
    forRange(n, 0, [&](size_t lo, size_t hi) {
        for (size_t k = lo; k < hi; ++k) {
            double sum = 0.0;
            for (int d = 0; d < D; ++d) {
                const float g = horizons.angle[size_t(d) * n + k];
                sum += std::sin(std::max(double(g), 0.0));
                if (std::isnan(g)) sum = NAN;
            }
            out[k] = float(1.0 - sum / D);
        }
    });
    return out;
}

std::vector<float> skyLight(const terrain::Heightfield& field, const Horizons& horizons) {
    SIERRA_CHECK(!field.empty(), "skyLight: the heightfield is empty");
    SIERRA_CHECK(horizons.width == field.width() && horizons.height == field.height() &&
                     horizons.directions >= 1 &&
                     horizons.angle.size() == size_t(horizons.width) * size_t(horizons.height) *
                                                  size_t(horizons.directions),
                 "skyLight: the horizons (", horizons.width, "x", horizons.height, "x",
                 horizons.directions, ") do not belong to the ", field.width(), "x", field.height(),
                 " heightfield");
    const NormalField normals = computeNormals(field, NormalMethod::Edge);
    const size_t n = size_t(horizons.width) * size_t(horizons.height);
    const int D = horizons.directions;
    std::vector<double> ux(D), uz(D);
    for (int d = 0; d < D; ++d) {
        const double a = double(horizons.azimuthDegrees(d)) * kPi / 180.0;
        ux[d] = std::sin(a);
        uz[d] = -std::cos(a);
    }
    std::vector<float> out(n);
    forRange(n, 0, [&](size_t lo, size_t hi) {
        for (size_t k = lo; k < hi; ++k) {
            const Vec3 nv = normals.normals[k];
            double sum = 0.0;
            for (int d = 0; d < D; ++d) {
                const double g = horizons.angle[size_t(d) * n + k];
                // n . w = a cos e + b sin e for w at elevation e in this azimuth.
                const double a = nv.x * ux[d] + nv.z * uz[d], b = nv.y;
                const double tangent = std::atan2(-a, b);  // where n . w = 0
                const double e0 = std::max(g, tangent);
                sum += a * (kPi / 4.0 - e0 / 2.0 - std::sin(2.0 * e0) / 4.0) +
                       b / 2.0 * std::cos(e0) * std::cos(e0);
                if (std::isnan(g)) sum = NAN;
            }
            out[k] = std::isnan(sum) ? kNaN : float(std::min(1.0, 2.0 * sum / D));
        }
    });
    return out;
}

namespace {

std::vector<float> openness(const terrain::Heightfield& field, const HorizonOptions& options,
                            bool inverted, const char* caller) {
    validate(field, options, caller);
    validateDirections(options, caller);
    const Surface s = makeSurface(field, options, inverted);
    const size_t n = s.samples();
    std::vector<float> sum(n, kNaN), count(n, 0.0f);
    // NaN stays in the padding; the region starts at 0.
    for (int j = 0; j < s.validH; ++j) std::fill_n(sum.begin() + s.index(0, j), s.validW, 0.0f);
    for (int d = 0; d < options.directions; ++d) {
        const double deg = options.firstAzimuth + 360.0 * double(d) / double(options.directions);
        sweepAzimuth(s, deg, options.radius, options.threads,
                     [&](float* x, const int64_t* index, int g0, int g1) {
                         for (int c = g0; c < g1; ++c) {
                             const int64_t k = index[c];
                             if (x[c] == kNoOccluder) continue;  // nothing in this direction
                             sum[k] += 90.0f - fastAtan(x[c]) * float(180.0 / kPi);
                             count[k] += 1.0f;
                         }
                     });
    }
    std::vector<float> out(n);
    forRange(n, options.threads, [&](size_t lo, size_t hi) {
        for (size_t k = lo; k < hi; ++k)
            out[k] = std::isnan(sum[k]) || count[k] == 0.0f ? kNaN : sum[k] / count[k];
    });
    return out;
}

}  // namespace

std::vector<float> opennessPositive(const terrain::Heightfield& field,
                                    const HorizonOptions& options) {
    return openness(field, options, false, "opennessPositive");
}

std::vector<float> opennessNegative(const terrain::Heightfield& field,
                                    const HorizonOptions& options) {
    return openness(field, options, true, "opennessNegative");
}

}  // namespace sierra::analysis
