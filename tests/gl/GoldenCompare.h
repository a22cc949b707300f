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

#include <sierra/gpu/Gl.h>
#include <sierra/gpu/ReadBack.h>
#include <sierra/render/Capture.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <optional>
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
    double psnr = 0.0;                 // dB over RGB; infinity for identical images
    double differingShare = 0.0;       // share of pixels off by more than kGoldenThreshold
    double bias[3] = {0, 0, 0};        // mean signed difference (image - golden) per channel
    std::string why;                   // the limits that failed, "" on a match
    int threshold = kGoldenThreshold;  // levels beyond which a pixel counts as off

    std::string summary() const {
        std::ostringstream out;
        out.precision(4);
        out << "PSNR " << psnr << " dB, " << 100.0 * differingShare << "% pixels off by more than "
            << threshold;
        if (threshold == kGoldenThreshold)
            out << ", bias (" << bias[0] << ", " << bias[1] << ", " << bias[2] << ")";
        if (!why.empty()) out << ": " << why;
        return out.str();
    }
};

// Both images non-empty, of one width and height.
inline bool sameSize(const gpu::Image& image, const gpu::Image& golden) {
    return image.width == golden.width && image.height == golden.height &&
           image.rgba.size() == golden.rgba.size() && !image.rgba.empty();
}

inline GoldenComparison compareWithGolden(const gpu::Image& image, const gpu::Image& golden) {
    GoldenComparison c;
    if (!sameSize(image, golden)) {
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
    if (worstBias > kGoldenMaxBias)
        why << "a channel is shifted by more than " << kGoldenMaxBias << " levels; ";
    c.why = why.str();
    c.matches = c.why.empty();
    return c;
}

// Line images (wireframes) against their golden. Drivers draw the same
// antialiased line a pixel to either side and with another coverage, so the
// shaded tolerance above fails on every line pixel while the mesh is the same.
// Here each pixel is compared with the closest of the other image's 3x3
// neighbourhood (both ways), and at most 0.1% of the pixels may still be off
// by more than 64 levels in some channel. Measured at 640x360 against the
// llvmpipe references of the default scene: NVIDIA's frames of the same
// meshes 0.000-0.002%; the SBT at tau 1.3 instead of 1, 0.43% (polygons and
// wireframe) and 0.72% (wireframe); at tau 2, 2.3%; the full grid, 17%.
constexpr int kLineThreshold = 64;
constexpr double kLineMaxDiffering = 0.001;

inline GoldenComparison compareLinesWithGolden(const gpu::Image& image, const gpu::Image& golden) {
    GoldenComparison c;
    if (!sameSize(image, golden)) {
        c.why = "sizes differ";
        return c;
    }
    c.threshold = kLineThreshold;
    const int w = image.width, h = image.height;
    // The smallest worst-channel difference between pixel (x, y) of `a` and the
    // pixels of `b` within one pixel of it.
    auto nearest = [w, h](const gpu::Image& a, const gpu::Image& b, int x, int y) {
        int best = 255;
        for (int v = std::max(y - 1, 0); v <= std::min(y + 1, h - 1); ++v)
            for (int u = std::max(x - 1, 0); u <= std::min(x + 1, w - 1); ++u) {
                int worst = 0;
                for (int ch = 0; ch < 3; ++ch)
                    worst = std::max(worst, std::abs(int(a.rgba[(size_t(y) * w + x) * 4 + ch]) -
                                                     int(b.rgba[(size_t(v) * w + u) * 4 + ch])));
                best = std::min(best, worst);
            }
        return best;
    };
    double squared = 0.0;
    size_t differing = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int d = std::max(nearest(image, golden, x, y), nearest(golden, image, x, y));
            squared += double(d) * d;
            differing += d > kLineThreshold;
        }
    const double mse = squared / (double(w) * h);
    c.psnr = mse == 0.0 ? std::numeric_limits<double>::infinity()
                        : 10.0 * std::log10(255.0 * 255.0 / mse);
    c.differingShare = double(differing) / (double(w) * h);
    if (c.differingShare > kLineMaxDiffering) {
        std::ostringstream why;
        why << "more than " << 100.0 * kLineMaxDiffering << "% of pixels off by more than "
            << kLineThreshold << " levels, one pixel of shift allowed";
        c.why = why.str();
    }
    c.matches = c.why.empty();
    return c;
}

// ------------------------------------------------------------ where goldens live
//
// tests/golden/NAME are the references CI checks, made on llvmpipe. A driver
// whose texture filtering differs from llvmpipe's by more than the shaded
// tolerance lets through (NVIDIA's anisotropic filtering of the zone tiles:
// 40.8 dB near the camera, where llvmpipe's builds agree to 47+ dB) has its own
// reference for that image in tests/golden/<driver>/NAME; every other image is
// shared. SIERRA_UPDATE_GOLDEN=1 on such a driver writes into its folder.

// "" for llvmpipe and any driver without references of its own; "nvidia" on NVIDIA's.
inline std::string goldenDriver() {
    const char* vendor = reinterpret_cast<const char*>(glGetString(GL_VENDOR));
    return vendor && std::string(vendor).find("NVIDIA") != std::string::npos ? "nvidia" : "";
}

inline bool updatingGoldens() {
    const char* env = std::getenv("SIERRA_UPDATE_GOLDEN");
    return env && std::string(env) == "1";
}

inline std::string goldenPath(const std::string& name) {
    const std::string base = std::string(SIERRA_GOLDEN_DIR) + "/";
    const std::string driver = goldenDriver();
    if (driver.empty()) return base + name;
    const std::string own = base + driver + "/" + name;
    return updatingGoldens() || std::filesystem::exists(own) ? own : base + name;
}

inline std::string testOutputPath(const std::string& name) {
    return std::string(SIERRA_TEST_OUTPUT_DIR) + "/" + name;
}

// Writes the frame to the test output folder, then either rewrites its golden
// (SIERRA_UPDATE_GOLDEN=1: the test is skipped and nullopt returned) or
// returns the golden to compare with.
inline std::optional<gpu::Image> goldenFor(const gpu::Image& image, const std::string& name) {
    std::filesystem::create_directories(SIERRA_TEST_OUTPUT_DIR);
    render::writePng(testOutputPath(name), image);
    if (updatingGoldens()) {
        std::filesystem::create_directories(std::filesystem::path(goldenPath(name)).parent_path());
        render::writePng(goldenPath(name), image);
        [&name] { GTEST_SKIP() << "golden image " << goldenPath(name) << " rewritten"; }();
        return std::nullopt;
    }
    return render::readPng(goldenPath(name));
}

enum class GoldenKind { Shaded, Lines };

// The whole golden check of a frame: compareWithGolden for shaded frames,
// compareLinesWithGolden for line images.
inline void expectMatchesGolden(const gpu::Image& image, const std::string& name,
                                GoldenKind kind = GoldenKind::Shaded) {
    const std::optional<gpu::Image> golden = goldenFor(image, name);
    if (!golden) return;
    const GoldenComparison c = kind == GoldenKind::Lines ? compareLinesWithGolden(image, *golden)
                                                         : compareWithGolden(image, *golden);
    std::printf("%s against golden %s: %s\n", name.c_str(), goldenPath(name).c_str(),
                c.summary().c_str());
    EXPECT_TRUE(c.matches) << c.summary() << " (frame written to " << testOutputPath(name) << ")";
}

}  // namespace sierra::test
