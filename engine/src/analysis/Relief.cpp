#include <sierra/analysis/Relief.h>

#include <sierra/analysis/ReliefLines.h>

#include "ReliefSweep.h"

#include <sierra/analysis/Normals.h>
#include <sierra/core/Error.h>
#include <sierra/core/Parallel.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <sys/mman.h>
#include <unistd.h>

namespace sierra::analysis {
namespace {

using namespace relief;

void validate(const terrain::Heightfield& field, const HorizonOptions& o, const char* caller) {
    checkHorizonOptions(field.width(), field.height(), o, caller);
}

void validateDirections(const HorizonOptions& o, const char* caller) {
    checkHorizonDirections(o, caller);
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

// sin on [-pi/2, pi/2] (NaN passes), absolute error below 1e-7: its Taylor
// polynomial to degree 11, branch-free so that loops over it vectorise.
inline float fastSin(float x) {
    const float x2 = x * x;
    return x * (1.0f + x2 * (-1.0f / 6.0f +
                             x2 * (1.0f / 120.0f +
                                   x2 * (-1.0f / 5040.0f +
                                         x2 * (1.0f / 362880.0f - x2 * (1.0f / 39916800.0f))))));
}

// Sizes `out` to `count` floats, their pages mapped on up to `threads`
// threads first: the kernel clears each fresh page on the thread that first
// touches it, about 1 s of one core for the 1 GiB of 16 azimuths at 4097^2
// on the 2-core development machine, where the zero-fill of resize() alone
// is a tenth of that. Where the kernel cannot populate (before Linux 5.14),
// resize() maps the pages itself.
void resizeMapped(std::vector<float>& out, size_t count, int threads) {
    out.clear();
    out.reserve(count);
#ifdef MADV_POPULATE_WRITE
    const size_t page = size_t(sysconf(_SC_PAGESIZE));
    const uintptr_t begin = (uintptr_t(out.data()) + page - 1) / page * page;
    const uintptr_t end = uintptr_t(out.data() + count) / page * page;
    // 2 MiB pieces: enough to share out, few enough calls.
    constexpr size_t kPiece = size_t(2) << 20;
    if (end > begin && end - begin >= 4 * kPiece) {
        const int64_t pieces = int64_t((end - begin + kPiece - 1) / kPiece);
        parallelChunks(
            0, pieces, int(std::min<int64_t>(pieces, 64)),
            [&](int64_t lo, int64_t hi, int) {
                const uintptr_t a = begin + uintptr_t(lo) * kPiece;
                const uintptr_t b = std::min<uintptr_t>(end, begin + uintptr_t(hi) * kPiece);
                madvise(reinterpret_cast<void*>(a), b - a, MADV_POPULATE_WRITE);
            },
            threads);
    }
#endif
    out.resize(count);
}

// The horizons' atan and store, one step of lanes at a time (see sweepGroup).
void storeAngles(float* a, float* slope, const int64_t* index, int g0, int g1) {
    for (int e = 0; e < kGroup; ++e) slope[e] = fastAtan(slope[e]);
    for (int e = g0; e < g1; ++e) a[index[e]] = slope[e];
}

// The horizons' azimuths (degrees) as Horizons::azimuthDegrees gives them.
float azimuthOf(const HorizonOptions& o, int d) {
    return o.firstAzimuth + 360.0f * float(d) / float(o.directions);
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
    resizeMapped(out.angle, n * size_t(options.directions), options.threads);
    for (int d = 0; d < options.directions; ++d) {
        float* a = out.angle.data() + size_t(d) * n;
        fillPadding(s, a, kNaN);
        sweepAzimuth(s, out.azimuthDegrees(d), options.radius, options.threads,
                     [a](float* slope, const int64_t* index, int g0, int g1) {
                         storeAngles(a, slope, index, g0, g1);
                     });
    }
    return out;
}

std::vector<float> sunVisibility(const terrain::Heightfield& field, const SunDisc& sun,
                                 const HorizonOptions& options) {
    validate(field, options, "sunVisibility");
    checkSunDisc(sun);
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

namespace {

// The sky-view factor's sum over azimuths of samples [lo, hi): g the angles
// of one azimuth. NaN (no data) passes through max and the sum.
void addSkyView(float* o, const float* g, size_t lo, size_t hi) {
    for (size_t k = lo; k < hi; ++k) o[k] += fastSin(g[k] < 0.0f ? 0.0f : g[k]);
}

void finishSkyView(float* o, int directions, size_t lo, size_t hi) {
    for (size_t k = lo; k < hi; ++k) o[k] = 1.0f - o[k] / float(directions);
}

// The sky light's sum over azimuths of samples [lo, hi): g the angles of
// azimuth `degrees`, nv the normals.
void addSkyLight(float* o, const float* g, const Vec3* nv, float degrees, size_t lo, size_t hi) {
    const double azimuth = double(degrees) * kPi / 180.0;
    const float ux = float(std::sin(azimuth)), uz = float(-std::cos(azimuth));
    for (size_t k = lo; k < hi; ++k) {
        // n . w = a cos e + b sin e for w at elevation e in this azimuth; the
        // tangent plane is at atan(-a / b) (b = n_y > 0).
        const float a = nv[k].x * ux + nv[k].z * uz, b = nv[k].y;
        const float tangent = fastAtan(-a / b);
        const float e0 = g[k] < tangent ? tangent : g[k];  // NaN stays
        const float sine = fastSin(e0), cos2 = 1.0f - sine * sine;
        const float sin2 = 2.0f * sine * std::sqrt(cos2);
        o[k] += a * (0.7853981633974483f - 0.5f * e0 - 0.25f * sin2) + 0.5f * b * cos2;
    }
}

void finishSkyLight(float* o, int directions, size_t lo, size_t hi) {
    for (size_t k = lo; k < hi; ++k) {
        const float v = 2.0f * o[k] / float(directions);
        o[k] = v > 1.0f ? 1.0f : v;  // NaN stays
    }
}

void checkHorizons(const Horizons& horizons, const char* caller) {
    SIERRA_CHECK(horizons.directions >= 1 &&
                     horizons.angle.size() == size_t(horizons.width) * size_t(horizons.height) *
                                                  size_t(horizons.directions),
                 caller, ": the horizons are empty or inconsistent (", horizons.width, "x",
                 horizons.height, "x", horizons.directions, " for ", horizons.angle.size(),
                 " angles)");
}

// Sky-view factor (light false) or sky light straight from the sweep:
// one azimuth's angles at a time in a buffer of one field, whose pages are
// mapped once, then summed as the stored horizons would be.
std::vector<float> skyFromSweep(const terrain::Heightfield& field, const HorizonOptions& options,
                                bool light, const char* caller) {
    validate(field, options, caller);
    validateDirections(options, caller);
    const Surface s = makeSurface(field, options, false);
    const size_t n = s.samples();
    NormalField normals;
    if (light) normals = computeNormals(field, NormalMethod::Edge);
    std::vector<float> angle;
    resizeMapped(angle, n, options.threads);
    fillPadding(s, angle.data(), kNaN);  // the sweep never visits the padding
    std::vector<float> out(n, 0.0f);
    float* o = out.data();
    float* a = angle.data();
    const int D = options.directions;
    for (int d = 0; d < D; ++d) {
        const float degrees = azimuthOf(options, d);
        sweepAzimuth(s, degrees, options.radius, options.threads,
                     [a](float* slope, const int64_t* index, int g0, int g1) {
                         storeAngles(a, slope, index, g0, g1);
                     });
        forRange(n, options.threads, [&](size_t lo, size_t hi) {
            if (light)
                addSkyLight(o, a, normals.normals.data(), degrees, lo, hi);
            else
                addSkyView(o, a, lo, hi);
        });
    }
    forRange(n, options.threads, [&](size_t lo, size_t hi) {
        light ? finishSkyLight(o, D, lo, hi) : finishSkyView(o, D, lo, hi);
    });
    return out;
}

}  // namespace

std::vector<float> skyViewFactor(const Horizons& horizons) {
    checkHorizons(horizons, "skyViewFactor");
    const size_t n = size_t(horizons.width) * size_t(horizons.height);
    std::vector<float> out(n, 0.0f);
    const int D = horizons.directions;
    float* o = out.data();
    forRange(n, 0, [&](size_t lo, size_t hi) {
        // Azimuth by azimuth over a chunk: plain loops that vectorise.
        for (int d = 0; d < D; ++d) addSkyView(o, horizons.angle.data() + size_t(d) * n, lo, hi);
        finishSkyView(o, D, lo, hi);
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
    std::vector<float> out(n, 0.0f);
    float* o = out.data();
    forRange(n, 0, [&](size_t lo, size_t hi) {
        for (int d = 0; d < D; ++d)
            addSkyLight(o, horizons.angle.data() + size_t(d) * n, normals.normals.data(),
                        horizons.azimuthDegrees(d), lo, hi);
        finishSkyLight(o, D, lo, hi);
    });
    return out;
}

std::vector<float> skyViewFactor(const terrain::Heightfield& field, const HorizonOptions& options) {
    return skyFromSweep(field, options, false, "skyViewFactor");
}

std::vector<float> skyLight(const terrain::Heightfield& field, const HorizonOptions& options) {
    return skyFromSweep(field, options, true, "skyLight");
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
