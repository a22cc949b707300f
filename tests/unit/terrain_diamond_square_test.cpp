// Diamond-square: determinism, and the offset ranges of the "Fractal Errata"
// measured from the output grid: diamond-step nodes within +-r*sqrt(2)/d,
// square-step nodes within +-r/d, each range actually reached.

#include <sierra/terrain/DiamondSquare.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

namespace sierra::terrain {
namespace {

using ::testing::HasSubstr;

std::string generateError(const DiamondSquareDesc& desc) {
    try {
        generateDiamondSquare(desc);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(TerrainDiamondSquare, SameSeedSameGridDifferentSeedDifferentGrid) {
    const Heightfield a = generateDiamondSquare({.size = 65, .seed = 42, .roughness = 1.0f});
    const Heightfield b = generateDiamondSquare({.size = 65, .seed = 42, .roughness = 1.0f});
    const Heightfield c = generateDiamondSquare({.size = 65, .seed = 43, .roughness = 1.0f});
    ASSERT_EQ(a.width(), 65);
    ASSERT_EQ(a.height(), 65);
    EXPECT_TRUE(std::equal(a.samples().begin(), a.samples().end(), b.samples().begin()));
    int differing = 0;
    for (size_t k = 0; k < a.samples().size(); ++k) differing += a.samples()[k] != c.samples()[k];
    EXPECT_GT(differing, int(a.samples().size()) * 9 / 10);
    for (float v : a.samples()) ASSERT_TRUE(std::isfinite(v));
}

TEST(TerrainDiamondSquare, ThreadCountDoesNotChangeTheGrid) {
    // 513: the last steps create >= 65536 nodes each and so run threaded.
    const Heightfield one = generateDiamondSquare({.size = 513, .seed = 7, .threads = 1});
    const Heightfield four = generateDiamondSquare({.size = 513, .seed = 7, .threads = 4});
    EXPECT_TRUE(std::equal(one.samples().begin(), one.samples().end(), four.samples().begin()));
}

TEST(TerrainDiamondSquare, OffsetRangesFollowTheErrata) {
    const int size = 33, n = size - 1;
    const float roughness = 2.5f;
    // Largest |offset| / bound per (half spacing, step type), over all seeds.
    std::map<std::pair<int, char>, double> worst;
    double worstCorner = 0.0;
    for (uint64_t seed = 1; seed <= 200; ++seed) {
        const Heightfield f =
            generateDiamondSquare({.size = size, .seed = seed, .roughness = roughness});
        for (int j : {0, n})
            for (int i : {0, n})
                worstCorner = std::max(worstCorner, std::abs(double(f.at(i, j))) / roughness);
        for (int step = n; step > 1; step /= 2) {
            const int half = step / 2;
            const double invD = double(half) / n;  // spacing of the new nodes in [0,1]
            const double diamondBound = roughness * std::sqrt(2.0) * invD;
            const double squareBound = roughness * invD;
            for (int y = half; y < n; y += step)
                for (int x = half; x < n; x += step) {
                    const float mean = (f.at(x - half, y - half) + f.at(x + half, y - half) +
                                        f.at(x - half, y + half) + f.at(x + half, y + half)) *
                                       0.25f;
                    double& w = worst[{half, 'd'}];
                    w = std::max(w, std::abs(double(f.at(x, y) - mean)) / diamondBound);
                }
            for (int y = 0; y <= n; y += half)
                for (int x = (y / half) % 2 == 0 ? half : 0; x <= n; x += step) {
                    float sum = 0.0f;
                    int count = 0;
                    if (x >= half) sum += f.at(x - half, y), ++count;
                    if (x + half <= n) sum += f.at(x + half, y), ++count;
                    if (y >= half) sum += f.at(x, y - half), ++count;
                    if (y + half <= n) sum += f.at(x, y + half), ++count;
                    ASSERT_EQ(count, (x == 0 || y == 0 || x == n || y == n) ? 3 : 4);
                    double& w = worst[{half, 's'}];
                    w = std::max(w,
                                 std::abs(double(f.at(x, y) - sum / float(count))) / squareBound);
                }
        }
    }
    EXPECT_LE(worstCorner, 1.0);
    EXPECT_GT(worstCorner, 0.9);
    ASSERT_EQ(worst.size(), 10u);  // 5 levels x 2 step types
    for (const auto& [key, ratio] : worst) {
        SCOPED_TRACE(::testing::Message() << "half " << key.first << " step " << key.second);
        // Within the bound (float rounding aside) and close to it, so the two
        // ranges really differ by sqrt(2).
        EXPECT_LE(ratio, 1.0 + 1e-4);
        EXPECT_GT(ratio, 0.9);
    }
}

// Mean |h(i-1) - 2 h(i) + h(i+1)| along rows at the finest spacing, relative to
// the field's height range: a scale-free roughness measure.
double finestSecondDifference(const Heightfield& f) {
    auto [lo, hi] = f.range();
    double sum = 0.0;
    int64_t count = 0;
    for (int j = 0; j < f.height(); ++j)
        for (int i = 1; i + 1 < f.width(); ++i) {
            sum += std::abs(double(f.at(i - 1, j)) - 2.0 * f.at(i, j) + f.at(i + 1, j));
            ++count;
        }
    return sum / double(count) / double(hi - lo);
}

TEST(TerrainDiamondSquare, HurstIsDeterministicAndSmallerIsRougher) {
    const DiamondSquareDesc desc{.size = 257, .seed = 5, .hurst = 0.5f};
    const Heightfield a = generateDiamondSquare(desc);
    const Heightfield b = generateDiamondSquare(
        DiamondSquareDesc{.size = 257, .seed = 5, .threads = 1, .hurst = 0.5f});
    EXPECT_TRUE(std::equal(a.samples().begin(), a.samples().end(), b.samples().begin()));
    // H = 1 is the default (errata) scaling up to pow()'s rounding.
    const Heightfield def = generateDiamondSquare({.size = 257, .seed = 5});
    const Heightfield one = generateDiamondSquare({.size = 257, .seed = 5, .hurst = 1.0f});
    for (size_t k = 0; k < def.samples().size(); ++k)
        ASSERT_NEAR(def.samples()[k], one.samples()[k], 1e-4f);
    // Rougher as H falls: a larger mean second difference at the finest level,
    // relative to the relief, over several seeds.
    double previous = 0.0;
    for (float h : {1.5f, 1.0f, 0.7f, 0.4f}) {
        double rough = 0.0;
        for (uint64_t seed = 1; seed <= 4; ++seed)
            rough += finestSecondDifference(
                generateDiamondSquare({.size = 257, .seed = seed, .hurst = h}));
        EXPECT_GT(rough, previous * 1.3) << "H " << h;
        previous = rough;
    }
}

TEST(TerrainDiamondSquare, RejectsBadHurst) {
    for (float h : {0.0f, -0.5f, 2.5f, NAN, INFINITY})
        EXPECT_THAT(generateError({.size = 9, .hurst = h}), HasSubstr("Hurst exponent")) << h;
}

TEST(TerrainDiamondSquare, RejectsBadSizeAndRoughness) {
    EXPECT_THAT(generateError({.size = 32}), HasSubstr("size 32 is not 2^n + 1 in 3..16385"));
    EXPECT_THAT(generateError({.size = 1}), HasSubstr("is not 2^n + 1"));
    EXPECT_THAT(generateError({.size = 32769}), HasSubstr("is not 2^n + 1"));
    EXPECT_THAT(generateError({.size = 0}), HasSubstr("is not 2^n + 1"));
    EXPECT_THAT(generateError({.size = 9, .roughness = 0.0f}),
                HasSubstr("roughness 0 must be in (0, 1e+06]"));
    EXPECT_THAT(generateError({.size = 9, .roughness = -1.0f}), HasSubstr("must be in (0, 1e+06]"));
    EXPECT_THAT(generateError({.size = 9, .roughness = NAN}), HasSubstr("must be in (0, 1e+06]"));
    EXPECT_THAT(generateError({.size = 9, .roughness = 1e38f}), HasSubstr("must be in (0, 1e+06]"));
    EXPECT_EQ(generateDiamondSquare({.size = 3}).width(), 3);
}

}  // namespace
}  // namespace sierra::terrain
