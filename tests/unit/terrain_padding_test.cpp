// Padding to (2^n+1)^2 by edge clamping, and filling no-data samples.

#include <sierra/terrain/Padding.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace sierra::terrain {
namespace {

TEST(TerrainPadding, PaddedSide) {
    EXPECT_EQ(paddedSide(1), 3);
    EXPECT_EQ(paddedSide(3), 3);
    EXPECT_EQ(paddedSide(4), 5);
    EXPECT_EQ(paddedSide(300), 513);
    EXPECT_EQ(paddedSide(513), 513);
    EXPECT_EQ(paddedSide(514), 1025);
    EXPECT_EQ(paddedSide(65537), 65537);
    EXPECT_THROW(paddedSide(0), Error);
    EXPECT_THROW(paddedSide(65538), Error);
}

TEST(TerrainPadding, WarnsWhenPaddingIsMoreThanFourTimesTheSamples) {
    // 1000x3 pads to 1025^2 = 1050625 samples, 350x the 3000 real ones.
    EXPECT_EQ(paddingWarning(1000, 3),
              "a 1000x3 heightfield is padded to 1025x1025 = 1050625 samples, 350.2x its 3000 "
              "real samples (the padding costs memory and refinement time but is not drawn); "
              "crop or tile it closer to a 2^n+1 square to avoid this");
    EXPECT_EQ(paddingWarning(1025, 1025), "");
    EXPECT_NE(paddingWarning(300, 200), "");  // 513^2 / 60000 = 4.39x
    EXPECT_EQ(paddingWarning(513, 129), "");  // 3.98x
    EXPECT_NE(paddingWarning(513, 128), "");  // 4.01x
    EXPECT_EQ(paddingWarning(514, 514), "");  // 1025^2 / 514^2 = 3.98x
}

TEST(TerrainPadding, Pads300x200To513WithClampedEdgesAndMask) {
    Heightfield f(300, 200);
    for (int j = 0; j < 200; ++j)
        for (int i = 0; i < 300; ++i) f.at(i, j) = float(i + 1000 * j);
    f.setSpacing(2.0f, 3.0f);
    f.setVerticalScale(0.5f);
    const Heightfield p = padToPowerOfTwoPlusOne(f);
    ASSERT_EQ(p.width(), 513);
    ASSERT_EQ(p.height(), 513);
    EXPECT_EQ(p.spacingX(), 2.0f);
    EXPECT_EQ(p.spacingZ(), 3.0f);
    EXPECT_EQ(p.verticalScale(), 0.5f);
    ASSERT_TRUE(p.hasMask());
    int ones = 0;
    for (int j = 0; j < 513; ++j)
        for (int i = 0; i < 513; ++i) {
            const bool inside = i < 300 && j < 200;
            ASSERT_EQ(p.valid(i, j), inside) << i << "," << j;
            ones += p.valid(i, j);
            ASSERT_EQ(p.at(i, j), f.at(std::min(i, 299), std::min(j, 199))) << i << "," << j;
        }
    EXPECT_EQ(ones, 300 * 200);
    EXPECT_EQ(p.at(400, 100), f.at(299, 100));
    EXPECT_EQ(p.at(100, 400), f.at(100, 199));
    EXPECT_EQ(p.at(512, 512), f.at(299, 199));
    EXPECT_EQ(p.range(), f.range());  // padding adds no heights of its own
}

TEST(TerrainPadding, AlreadyPowerOfTwoPlusOneIsUnchanged) {
    Heightfield f(513, 513);
    for (int j = 0; j < 513; ++j)
        for (int i = 0; i < 513; ++i) f.at(i, j) = float(i * 3 - j);
    const Heightfield p = padToPowerOfTwoPlusOne(f);
    ASSERT_EQ(p.width(), 513);
    EXPECT_FALSE(p.hasMask());
    EXPECT_TRUE(std::equal(f.samples().begin(), f.samples().end(), p.samples().begin()));

    std::vector<uint8_t> mask(513 * 513, 1);
    mask[5] = 0;
    f.setMask(mask);
    const Heightfield q = padToPowerOfTwoPlusOne(f);
    EXPECT_FALSE(q.valid(5, 0));
    EXPECT_TRUE(q.valid(6, 0));
}

TEST(TerrainPadding, KeepsNoDataOfTheInputAndRejectsEmpty) {
    Heightfield f(4, 2, 1.0f);
    std::vector<uint8_t> mask(8, 1);
    mask[1 * 4 + 2] = 0;  // (2, 1)
    f.setMask(mask);
    const Heightfield p = padToPowerOfTwoPlusOne(f);
    ASSERT_EQ(p.width(), 5);
    EXPECT_FALSE(p.valid(2, 1));
    EXPECT_TRUE(p.valid(3, 1));
    EXPECT_FALSE(p.valid(4, 1));
    EXPECT_FALSE(p.valid(0, 2));
    EXPECT_THROW(padToPowerOfTwoPlusOne(Heightfield()), Error);
}

TEST(TerrainPadding, FillNoDataGrowsFromValidNeighbours) {
    Heightfield f(5, 1);
    for (int i = 0; i < 5; ++i) f.at(i, 0) = float(10 * i);
    std::vector<uint8_t> mask = {1, 0, 0, 0, 1};
    f.at(1, 0) = f.at(2, 0) = f.at(3, 0) = -32768.0f;
    f.setMask(mask);
    fillNoData(f);
    EXPECT_EQ(f.at(1, 0), 0.0f);   // ring 1: from (0,0)
    EXPECT_EQ(f.at(3, 0), 40.0f);  // ring 1: from (4,0)
    EXPECT_EQ(f.at(2, 0), 20.0f);  // ring 2: mean of both
    EXPECT_FALSE(f.valid(2, 0));   // mask kept

    Heightfield none(3, 3, 5.0f);
    none.setMask(std::vector<uint8_t>(9, 0));
    fillNoData(none);
    EXPECT_EQ(none.at(1, 1), 0.0f);
}

}  // namespace
}  // namespace sierra::terrain
