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

// The major indices [begin, end) where line o lies inside the region.
std::pair<int, int> lineSpan(const Lines& l, int o) {
    // r is monotone: non-decreasing for slope >= 0, non-increasing otherwise.
    const int lo = -o, hi = l.minorCount - 1 - o;  // r(m) must lie in [lo, hi]
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

// Stewart's sweep without a radius: the stack holds the upper convex hull, in
// (t, h), of the casting points behind the current one (nearest on top). The
// current point's tangent point is the hull vertex where the tangent from it
// touches; the vertices above that one lie under the new hull and are popped
// for good, so every point is pushed and popped at most once.
void sweepWhole(Profile& P) {
    int top = 0;
    int* stack = P.stack.data();
    for (int k = 0; k < P.n; ++k) {
        const uint8_t f = P.flags[k];
        if (!f) continue;
        while (top >= 2 && notAbove(P, k, stack[top - 1], stack[top - 2])) --top;
        P.best[k] = top ? stack[top - 1] : -1;
        if (f & kCast) stack[top++] = k;
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

// The horizon slope (tan of its elevation) of every sample of the region in
// azimuth `degrees` into out[j * width + i]: -inf where nothing casts ahead,
// NaN at no-data samples. Padding is left as it is.
void sweepAzimuth(const Surface& s, double degrees, double radius, int threads, float* out) {
    const Lines l = makeLines(degrees, s);
    const int lines = l.lineEnd - l.lineBegin;
    const size_t capacity = size_t(l.diagonal ? 2 * l.majorCount : l.majorCount);
    // A radius at least the region's extent along the azimuth changes nothing.
    const double extent =
        std::fabs(double(s.validW) * s.sx * l.ux) + std::fabs(double(s.validH) * s.sz * l.uz);
    const bool limited = radius > 0.0 && radius < extent;
    if (threads <= 0) threads = defaultThreadCount();
    if (s.samples() < size_t(kParallelMinSamples)) threads = 1;
    const int chunks = std::max(1, std::min(lines, threads * 16));
    parallelChunks(
        l.lineBegin, l.lineEnd, chunks,
        [&](int64_t lo, int64_t hi, int) {
            Profile P;
            P.reserve(capacity);
            for (int64_t o = lo; o < hi; ++o) {
                gatherLine(s, l, int(o), P);
                if (limited)
                    sweepRadius(P, radius);
                else
                    sweepWhole(P);
                finishSlopes(P);
                for (int k = 0; k < P.n; ++k)
                    if (P.sample[k] >= 0) out[P.sample[k]] = P.slope[k];
            }
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
// error below 2e-7 rad: Cephes's single-precision reduction to |x| <=
// tan(pi/8) and its minimax polynomial (S. L. Moshier, "Methods and Programs
// for Mathematical Functions", 1989), written without branches so that loops
// over it vectorise.
inline float fastAtan(float x) {
    const float ax = std::fabs(x);
    const bool big = ax > 2.414213562373095f;   // tan(3 pi / 8)
    const bool mid = ax > 0.4142135623730950f;  // tan(pi / 8)
    const float base = big ? 1.5707963267948966f : (mid ? 0.7853981633974483f : 0.0f);
    const float num = big ? -1.0f : (mid ? ax - 1.0f : ax);
    const float den = big ? ax : (mid ? ax + 1.0f : 1.0f);
    const float z = num / den;
    const float z2 = z * z;
    const float p = (((8.05374449538e-2f * z2 - 1.38776856032e-1f) * z2 + 1.99777106478e-1f) * z2 -
                     3.33329491539e-1f) *
                        z2 * z +
                    z;
    const float r = base + p;
    return std::copysign(r, x);
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
        sweepAzimuth(s, out.azimuthDegrees(d), options.radius, options.threads, a);
        forRange(n, options.threads, [&](size_t lo, size_t hi) {
            for (size_t k = lo; k < hi; ++k) a[k] = fastAtan(a[k]);
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
    sweepAzimuth(s, sun.azimuth, options.radius, options.threads, out.data());
    forRange(n, options.threads, [&](size_t lo, size_t hi) {
        for (size_t k = lo; k < hi; ++k) {
            const float g = fastAtan(out[k]);
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
            out[k] = v;
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
    std::vector<float> slope(n, kNaN), sum(n, 0.0f), count(n, 0.0f);
    for (int d = 0; d < options.directions; ++d) {
        const double deg = options.firstAzimuth + 360.0 * double(d) / double(options.directions);
        sweepAzimuth(s, deg, options.radius, options.threads, slope.data());
        forRange(n, options.threads, [&](size_t lo, size_t hi) {
            for (size_t k = lo; k < hi; ++k) {
                const float x = slope[k];
                if (x == kNoOccluder) continue;  // nothing in this direction
                sum[k] += 90.0f - fastAtan(x) * float(180.0 / kPi);
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
