// The GPU relief fields (render::ReliefGpu, shaders/horizon.comp and
// relief_sky.comp) against the CPU reference (analysis/Relief.h): horizons in
// 16 azimuths, the sun's visibility, the sky-view factor and the sky light
// within 1e-4 (radians, or absolute for the 0..1 fields), NaN exactly where
// the CPU has NaN, on rough square and non-square grids with unequal
// spacing, no-data holes, padding and a search radius.

#include "GlTest.h"

#include <sierra/analysis/Relief.h>
#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/ReliefGpu.h>
#include <sierra/terrain/DiamondSquare.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace sierra;
using analysis::HorizonOptions;
using analysis::SunDisc;

namespace {

class ReliefGpuTest : public test::GlTest {};

constexpr float kTolerance = 1e-4f;

// A rough fractal cut to width x height, heights about a quarter of the
// grid's extent (steep enough that most horizons are far and above 0).
terrain::Heightfield rough(int width, int height, uint64_t seed, float sx = 1.0f, float sz = 1.0f) {
    int size = 3;
    while (size < std::max(width, height)) size = 2 * size - 1;
    const terrain::Heightfield f =
        terrain::generateDiamondSquare({.size = size, .seed = seed, .roughness = 1.0f});
    terrain::Heightfield out(width, height);
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) out.at(i, j) = f.at(i, j);
    auto [lo, hi] = out.range();
    out.setSpacing(sx, sz);
    out.setVerticalScale(0.25f * float(std::max(width, height)) / std::max(hi - lo, 1e-3f));
    return out;
}

// Holes: random samples and a disc with no data.
void punchHoles(terrain::Heightfield& f, uint64_t seed) {
    std::mt19937_64 random(seed);
    std::vector<uint8_t> mask(size_t(f.sampleCount()), 1);
    for (auto& m : mask)
        if (random() % 20 == 0) m = 0;
    const int ci = f.width() / 3, cj = f.height() / 2, r = std::max(2, f.width() / 10);
    for (int j = 0; j < f.height(); ++j)
        for (int i = 0; i < f.width(); ++i)
            if ((i - ci) * (i - ci) + (j - cj) * (j - cj) <= r * r)
                mask[size_t(j) * size_t(f.width()) + size_t(i)] = 0;
    f.setMask(std::move(mask));
}

// The largest |GPU - CPU| over the samples where the CPU has a value; NaN
// must match NaN (a mismatch counts as infinite). Reports the first few
// samples beyond the tolerance.
float maxDifference(const std::vector<float>& gpu, const std::vector<float>& cpu, int width,
                    int height, const std::string& what) {
    EXPECT_EQ(gpu.size(), cpu.size()) << what;
    if (gpu.size() != cpu.size()) return INFINITY;
    const size_t layer = size_t(width) * size_t(height);
    float worst = 0.0f;
    int bad = 0;
    for (size_t k = 0; k < cpu.size(); ++k) {
        const float g = gpu[k], c = cpu[k];
        const float d = std::isnan(c) || std::isnan(g)
                            ? (std::isnan(c) == std::isnan(g) ? 0.0f : INFINITY)
                            : std::fabs(g - c);
        worst = std::max(worst, d);
        if (d > kTolerance && ++bad <= 3) {
            const size_t s = k % layer;
            ADD_FAILURE() << what << ": layer " << k / layer << " sample (" << s % size_t(width)
                          << ", " << s / size_t(width) << "): GPU " << g << ", CPU " << c;
        }
    }
    std::printf("%s: max |GPU - CPU| %.3g\n", what.c_str(), double(worst));
    return worst;
}

// Horizons, sky-view factor, sky light and the sun's visibility at a few
// positions, GPU against CPU.
void checkAll(const terrain::Heightfield& f, const HorizonOptions& o, const std::string& what) {
    render::ReliefGpu gpu = render::ReliefGpu::create(f);
    gpu.computeHorizons(o);
    const analysis::Horizons cpu = analysis::computeHorizons(f, o);
    const analysis::Horizons got = gpu.readHorizons();
    EXPECT_EQ(got.directions, cpu.directions);
    EXPECT_EQ(got.firstAzimuth, cpu.firstAzimuth);
    EXPECT_LE(maxDifference(got.angle, cpu.angle, f.width(), f.height(), what + " horizons"),
              kTolerance);
    gpu.computeSky();
    EXPECT_LE(maxDifference(gpu.readSkyViewFactor(), analysis::skyViewFactor(cpu), f.width(),
                            f.height(), what + " sky-view factor"),
              kTolerance);
    EXPECT_LE(maxDifference(gpu.readSkyLight(), analysis::skyLight(f, cpu), f.width(), f.height(),
                            what + " sky light"),
              kTolerance);
    // An off-grid azimuth, an axis, a diagonal; high, low (penumbrae on many
    // samples) and below the horizontal.
    for (const SunDisc sun : {SunDisc{.azimuth = 233.7f, .altitude = 30.0f},
                              SunDisc{.azimuth = 233.7f, .altitude = 8.0f, .diameter = 2.0f},
                              SunDisc{.azimuth = 90.0f, .altitude = 15.0f},
                              SunDisc{.azimuth = 315.0f, .altitude = 20.0f},
                              SunDisc{.azimuth = 12.0f, .altitude = -0.1f},
                              SunDisc{.azimuth = 12.0f, .altitude = -5.0f}}) {
        gpu.computeSunVisibility(sun, o);
        EXPECT_LE(maxDifference(gpu.readSunVisibility(), analysis::sunVisibility(f, sun, o),
                                f.width(), f.height(),
                                what + " sun at " + std::to_string(sun.azimuth) + "/" +
                                    std::to_string(sun.altitude)),
                  kTolerance);
    }
    // The horizons and the sun in one dispatch: the same fields.
    const SunDisc sun{.azimuth = 233.7f, .altitude = 10.0f, .diameter = 1.0f};
    gpu.computeHorizonsAndSun(o, sun);
    EXPECT_LE(maxDifference(gpu.readHorizons().angle, cpu.angle, f.width(), f.height(),
                            what + " horizons beside the sun"),
              kTolerance);
    EXPECT_LE(maxDifference(gpu.readSunVisibility(), analysis::sunVisibility(f, sun, o), f.width(),
                            f.height(), what + " sun beside the horizons"),
              kTolerance);
}

TEST_F(ReliefGpuTest, RoughSquareGridMatchesCpu) {
    checkAll(rough(65, 65, 1), {}, "65x65");
}

TEST_F(ReliefGpuTest, NonSquareUnequalSpacingMatchesCpu) {
    // Unequal spacing: the diagonals of the index grid are not 45 degrees.
    checkAll(rough(129, 97, 2, 1.5f, 1.0f), {.firstAzimuth = 7.5f}, "129x97");
}

TEST_F(ReliefGpuTest, NoDataHolesMatchCpu) {
    terrain::Heightfield f = rough(97, 65, 3);
    punchHoles(f, 3);
    checkAll(f, {}, "97x65 holes");
}

TEST_F(ReliefGpuTest, PaddingMatchesCpu) {
    terrain::Heightfield f = rough(80, 72, 4);
    punchHoles(f, 4);
    checkAll(f, {.validWidth = 65, .validHeight = 61}, "80x72 valid 65x61");
}

TEST_F(ReliefGpuTest, RadiusMatchesCpu) {
    terrain::Heightfield f = rough(81, 67, 5, 1.0f, 1.25f);
    checkAll(f, {.radius = 9.5f}, "81x67 radius 9.5");
    punchHoles(f, 5);
    checkAll(f, {.directions = 8, .firstAzimuth = 3.0f, .radius = 20.0f}, "81x67 holes radius 20");
}

// Every lane of a workgroup with data and few of them: grids thinner than
// one group of lines, and a single row and column.
TEST_F(ReliefGpuTest, ThinGridsMatchCpu) {
    checkAll(rough(70, 3, 6), {}, "70x3");
    checkAll(rough(1, 40, 7), {.directions = 4}, "1x40");
}

TEST_F(ReliefGpuTest, LeavesGlStateAsFound) {
    const terrain::Heightfield f = rough(33, 33, 8);
    render::ReliefGpu gpu = render::ReliefGpu::create(f);
    const gpu::GlState before = gpu::GlState::capture();
    gpu.computeHorizons({});
    gpu.computeSky();
    gpu.computeSunVisibility({});
    gpu.computeHorizonsAndSun({.directions = 4}, {});
    EXPECT_EQ(gpu::GlState::capture().differences(before), "");
}

TEST_F(ReliefGpuTest, BadOptionsThrowTheCpuMessages) {
    const terrain::Heightfield f = rough(17, 17, 9);
    render::ReliefGpu gpu = render::ReliefGpu::create(f);
    EXPECT_THROW(gpu.computeHorizons({.directions = 0}), Error);
    EXPECT_THROW(gpu.computeHorizons({.radius = -1.0f}), Error);
    EXPECT_THROW(gpu.computeHorizons({.validWidth = 18}), Error);
    EXPECT_THROW(gpu.computeSunVisibility({.diameter = 0.0f}), Error);
    EXPECT_THROW(gpu.computeSunVisibility({.altitude = 91.0f}), Error);
    EXPECT_THROW(gpu.computeSky(), Error);
    EXPECT_THROW(render::ReliefGpu::create(terrain::Heightfield()), Error);
}

}  // namespace
