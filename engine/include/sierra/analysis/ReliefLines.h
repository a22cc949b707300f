#pragma once
// What every implementation of the relief fields (analysis/Relief.h on the
// CPU, render/ReliefGpu.h on the GPU) shares, so that both sweep the same
// lines and refuse the same options with the same messages: the digital lines
// of an azimuth and the option checks. docs/relief.md describes the lines.

#include <sierra/analysis/Relief.h>

#include <utility>
#include <vector>

namespace sierra::analysis {

// The most azimuths a call takes: 1024 at 4097^2 is already 64 GiB of angles.
inline constexpr int kMaxHorizonDirections = 1024;

// One azimuth's digital lines over a validWidth x validHeight region. The
// azimuth's direction in grid index space is (gi, gj) = (sin a / sx,
// -cos a / sz). Its major axis is the one with the larger |component| (i on a
// tie); `slope` is the minor index change per +1 step of the major index, so
// |slope| <= 1. Line o holds the samples (major m, minor o + r(m)) with
// r(m) = floor(slope * m + 0.5): every sample (m, n) lies on exactly the line
// o = n - r(m). Grid-aligned azimuths (slope 0 or +-1) are straight grid lines.
struct DigitalLines {
    double ux = 0.0, uz = 0.0;  // the azimuth's world unit vector (x, z)
    bool iMajor = true;
    int look = 1;  // +1: the azimuth points towards increasing major index
    double slope = 0.0;
    bool diagonal = false;  // |slope| == 1: cell centres join the profile
    int majorCount = 0, minorCount = 0;
    int lineBegin = 0, lineEnd = 0;  // offsets o in [lineBegin, lineEnd)
    std::vector<int> r;              // r(m), m in [0, majorCount)
};

// `degrees`: compass bearing; spacings in world units; the region >= 1x1.
DigitalLines digitalLines(double degrees, double spacingX, double spacingZ, int validWidth,
                          int validHeight);

// The major indices [begin, end) where any of lines [o, o + count) lies inside
// the region (begin == end when none does).
std::pair<int, int> lineSpan(const DigitalLines& lines, int o, int count = 1);

// The relief functions' option checks, throwing sierra::Error that names
// `caller`: the region and radius of a width x height field; the azimuths;
// the sun (its messages name sunVisibility).
void checkHorizonOptions(int width, int height, const HorizonOptions& options, const char* caller);
void checkHorizonDirections(const HorizonOptions& options, const char* caller);
void checkSunDisc(const SunDisc& sun);

}  // namespace sierra::analysis
