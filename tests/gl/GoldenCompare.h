#pragma once
// The one comparison of a rendered frame against its golden image, shared by
// every golden test (and by the tests of the comparison itself), so the
// tolerance lives in one place when the references are regenerated with
// SIERRA_UPDATE_GOLDEN=1.
//
// What it must let through: llvmpipe versions differ in the last bits of
// rasterisation and filtering, which moves a few edge pixels by a lot and
// leaves the rest within a level or two. What it must catch: a different mesh
// (the full grid against the SBT frame: 38.5 dB, edges everywhere off), a
// uniform shift of every channel by 8 levels (30.1 dB, a wrong colour ramp or
// sRGB step), and black, flipped or channel-swapped frames.

#include <sierra/gpu/ReadBack.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>

namespace sierra::test {

// Tolerance, each limit on its own failing the match:
//  - PSNR over RGB at least 45 dB (mean squared error at most 2.1 levels^2);
//  - at most 0.2% of the pixels off by more than 24 levels in some channel;
//  - the mean signed difference of each channel within 1.5 levels, so a
//    uniform shift is caught even where PSNR alone would pass it.
// Measured on llvmpipe (Mesa 22.3.6, 640x360, 4x MSAA): references made by an
// earlier renderer build against a fresh render, 50.1 dB, 0.046% of pixels
// off, bias 0.02 (references from the same build: 66-67 dB); the full grid
// against the SBT frame, 38.4 dB and 0.44% off before the renderer became
// passes, 41.9 dB and 0.24% after (fails PSNR by 3 dB and the share); a uniform
// +8 shift, 30.1 dB, bias 8 (fails PSNR and bias).
constexpr double kGoldenMinPsnr = 45.0;
constexpr int kGoldenThreshold = 24;
constexpr double kGoldenMaxDiffering = 0.002;
constexpr double kGoldenMaxBias = 1.5;

struct GoldenComparison {
    bool matches = false;
    double psnr = 0.0;            // dB over RGB; infinity for identical images
    double differingShare = 0.0;  // share of pixels off by more than kGoldenThreshold
    double bias[3] = {0, 0, 0};   // mean signed difference (image - golden) per channel
    std::string why;              // the limits that failed, "" on a match

    std::string summary() const {
        std::ostringstream out;
        out.precision(4);
        out << "PSNR " << psnr << " dB, " << 100.0 * differingShare << "% pixels off by more than "
            << kGoldenThreshold << ", bias (" << bias[0] << ", " << bias[1] << ", " << bias[2] << ")";
        if (!why.empty()) out << ": " << why;
        return out.str();
    }
};

inline GoldenComparison compareWithGolden(const gpu::Image& image, const gpu::Image& golden) {
    GoldenComparison c;
    if (image.width != golden.width || image.height != golden.height ||
        image.rgba.size() != golden.rgba.size() || image.rgba.empty()) {
        c.why = "sizes differ";
        return c;
    }
    const size_t pixels = size_t(image.width) * image.height;
    double squared = 0.0, signedSum[3] = {0, 0, 0};
    size_t differing = 0;
    for (size_t p = 0; p < pixels; ++p) {
        int worst = 0;
        for (int ch = 0; ch < 3; ++ch) {
            const int d = int(image.rgba[p * 4 + ch]) - int(golden.rgba[p * 4 + ch]);
            squared += double(d) * d;
            signedSum[ch] += d;
            worst = std::max(worst, std::abs(d));
        }
        differing += worst > kGoldenThreshold;
    }
    const double mse = squared / double(pixels * 3);
    c.psnr = mse == 0.0 ? std::numeric_limits<double>::infinity()
                        : 10.0 * std::log10(255.0 * 255.0 / mse);
    c.differingShare = double(differing) / double(pixels);
    double worstBias = 0.0;
    for (int ch = 0; ch < 3; ++ch) {
        c.bias[ch] = signedSum[ch] / double(pixels);
        worstBias = std::max(worstBias, std::abs(c.bias[ch]));
    }
    std::ostringstream why;
    if (c.psnr < kGoldenMinPsnr) why << "PSNR below " << kGoldenMinPsnr << " dB; ";
    if (c.differingShare > kGoldenMaxDiffering)
        why << "more than " << 100.0 * kGoldenMaxDiffering << "% of pixels off; ";
    if (worstBias > kGoldenMaxBias) why << "a channel is shifted by more than " << kGoldenMaxBias << " levels; ";
    c.why = why.str();
    c.matches = c.why.empty();
    return c;
}

}  // namespace sierra::test
