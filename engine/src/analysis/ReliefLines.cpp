#include <sierra/analysis/ReliefLines.h>

#include <sierra/core/Error.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace sierra::analysis {

DigitalLines digitalLines(double degrees, double spacingX, double spacingZ, int validWidth,
                          int validHeight) {
    constexpr double kPi = 3.14159265358979323846;
    DigitalLines l;
    const double a = std::fmod(degrees, 360.0) * kPi / 180.0;
    double sa = std::sin(a), ca = std::cos(a);
    // sin(pi) is 1.2e-16, not 0: the four axis azimuths are snapped onto the axes.
    if (std::fabs(sa) < 1e-12) sa = 0.0;
    if (std::fabs(ca) < 1e-12) ca = 0.0;
    l.ux = sa;
    l.uz = -ca;
    const double gi = sa / spacingX, gj = -ca / spacingZ;
    l.iMajor = std::fabs(gi) >= std::fabs(gj);
    const double major = l.iMajor ? gi : gj, minor = l.iMajor ? gj : gi;
    l.look = major > 0.0 ? 1 : -1;
    l.slope = minor / major;
    if (std::fabs(std::fabs(l.slope) - 1.0) < 1e-12) l.slope = l.slope > 0.0 ? 1.0 : -1.0;
    l.diagonal = std::fabs(l.slope) == 1.0;
    l.majorCount = l.iMajor ? validWidth : validHeight;
    l.minorCount = l.iMajor ? validHeight : validWidth;
    l.r.resize(size_t(l.majorCount));
    for (int m = 0; m < l.majorCount; ++m) l.r[size_t(m)] = int(std::floor(l.slope * m + 0.5));
    const int rLo = std::min(l.r.front(), l.r.back()), rHi = std::max(l.r.front(), l.r.back());
    l.lineBegin = -rHi;
    l.lineEnd = l.minorCount - rLo;
    return l;
}

std::pair<int, int> lineSpan(const DigitalLines& l, int o, int count) {
    // r is monotone: non-decreasing for slope >= 0, non-increasing otherwise.
    const int lo = -(o + count - 1), hi = l.minorCount - 1 - o;  // r(m) must lie in [lo, hi]
    int begin, end;
    if (l.slope >= 0.0) {
        begin = int(std::lower_bound(l.r.begin(), l.r.end(), lo) - l.r.begin());
        end = int(std::upper_bound(l.r.begin(), l.r.end(), hi) - l.r.begin());
    } else {
        begin =
            int(std::lower_bound(l.r.begin(), l.r.end(), hi, std::greater<int>()) - l.r.begin());
        end = int(std::upper_bound(l.r.begin(), l.r.end(), lo, std::greater<int>()) - l.r.begin());
    }
    return {begin, std::max(begin, end)};
}

void checkHorizonOptions(int width, int height, const HorizonOptions& o, const char* caller) {
    SIERRA_CHECK(width > 0 && height > 0, caller, ": the heightfield is empty");
    SIERRA_CHECK(o.validWidth >= 0 && o.validWidth <= width, caller, ": validWidth must be in 0..",
                 width, " (0 = the whole grid), got ", o.validWidth);
    SIERRA_CHECK(o.validHeight >= 0 && o.validHeight <= height, caller,
                 ": validHeight must be in 0..", height, " (0 = the whole grid), got ",
                 o.validHeight);
    SIERRA_CHECK(std::isfinite(o.radius) && o.radius >= 0.0f, caller,
                 ": radius must be finite and >= 0 (0 = the whole grid), got ", o.radius);
    SIERRA_CHECK(o.threads >= 0, caller, ": threads must be >= 0 (0 = the default), got ",
                 o.threads);
}

void checkHorizonDirections(const HorizonOptions& o, const char* caller) {
    SIERRA_CHECK(o.directions >= 1 && o.directions <= kMaxHorizonDirections, caller,
                 ": directions must be in 1..", kMaxHorizonDirections, ", got ", o.directions);
    SIERRA_CHECK(std::isfinite(o.firstAzimuth), caller, ": firstAzimuth must be finite, got ",
                 o.firstAzimuth);
}

void checkSunDisc(const SunDisc& sun) {
    SIERRA_CHECK(std::isfinite(sun.diameter) && sun.diameter > 0.0f && sun.diameter < 180.0f,
                 "sunVisibility: the sun's diameter must be in (0, 180) degrees, got ",
                 sun.diameter);
    SIERRA_CHECK(std::isfinite(sun.azimuth),
                 "sunVisibility: the sun's azimuth must be finite, got ", sun.azimuth);
    SIERRA_CHECK(std::isfinite(sun.altitude) && sun.altitude >= -90.0f && sun.altitude <= 90.0f,
                 "sunVisibility: the sun's altitude must be in [-90, 90] degrees, got ",
                 sun.altitude);
}

}  // namespace sierra::analysis
