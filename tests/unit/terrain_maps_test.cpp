// 2D maps: plasma is grey, scalar fields take their ramp's colours, the shaded
// relief follows its light, and the colour bar's legend labels the colours it
// shows.

#include <sierra/terrain/Maps.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

namespace sierra::terrain {
namespace {

Heightfield bumpy(int n) {
    Heightfield f(n, n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            f.at(i, j) = std::sin(0.21f * float(i)) * 40.0f + std::cos(0.13f * float(j)) * 25.0f;
    return f;
}

TEST(Maps, PlasmaIsGrey) {
    Heightfield f = bumpy(65);
    ColourRamp ramp = ColourRamp::forField(f, RampScheme::Plasma, 0.0f);
    RgbImage image = renderMap(f, ramp);
    int distinct = 0, last = -1;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            Rgb c = image.at(x, y);
            ASSERT_EQ(c.r, c.g) << x << "," << y;
            ASSERT_EQ(c.g, c.b) << x << "," << y;
            if (c.r != last) ++distinct, last = c.r;
        }
    EXPECT_GT(distinct, 10);  // a ramp of greys, not one flat colour
    // Black at the lowest sample, white at the highest.
    auto [lo, hi] = f.range();
    EXPECT_EQ(ramp.colourAt(lo).r, 0);
    EXPECT_EQ(ramp.colourAt(hi).r, 255);
}

TEST(Maps, ColourFieldUsesTheRampAndNoDataColour) {
    const float nan = std::nanf("");
    const std::vector<float> values = {0.0f, 45.0f, 90.0f, nan};
    ColourRamp ramp({{0.0f, {255, 255, 255}}, {90.0f, {0, 0, 0}}}, 0.0f, 90.0f,
                    {.noData = Rgb{1, 2, 3}});
    RgbImage image = colourField(2, 2, values, ramp);
    EXPECT_EQ(image.at(0, 0).r, 255);
    EXPECT_EQ(image.at(1, 0).r, 128);  // 255 * (1 - 45 / 90), rounded
    EXPECT_EQ(image.at(0, 1).r, 0);
    EXPECT_EQ(image.at(1, 1).b, 3);
    EXPECT_THROW(colourField(3, 2, values, ramp), Error);
    EXPECT_EQ(finiteQuantile(values, 1.0), 90.0f);
    EXPECT_EQ(finiteQuantile(values, 0.0), 0.0f);
}

TEST(Maps, ShadedReliefFollowsTheLight) {
    Heightfield f = bumpy(33);
    const auto [lo, hi] = f.range();
    ColourRamp tints({{lo, {100, 120, 90}}, {hi, {150, 160, 120}}}, lo, hi);
    const size_t n = size_t(f.sampleCount());
    std::vector<float> flat(n, 181.0f), lit(n, 255.0f), dark(n, 40.0f), open(n, 1.0f),
        closed(n, 0.3f);
    auto sum = [](const RgbImage& image, int x, int y) {
        Rgb c = image.at(x, y);
        return c.r + c.g + c.b;
    };
    RgbImage base = shadedRelief(f, tints, flat, open);
    // Flat ground under an open sky keeps the tint.
    const Rgb tint = tints.colourAt(f.at(5, 7));
    EXPECT_EQ(base.at(5, 7).r, tint.r);
    EXPECT_EQ(base.at(5, 7).g, tint.g);
    EXPECT_GT(sum(shadedRelief(f, tints, lit, open), 5, 7), sum(base, 5, 7));
    EXPECT_LT(sum(shadedRelief(f, tints, dark, open), 5, 7), sum(base, 5, 7));
    EXPECT_LT(sum(shadedRelief(f, tints, flat, closed), 5, 7), sum(base, 5, 7));
}

TEST(Maps, AtlasLegendColoursMatchRampAtLabelledHeights) {
    Heightfield f = bumpy(129);
    f.setVerticalScale(2.5f);  // labels in world units = stored * 2.5
    ColourRamp ramp = ColourRamp::forField(f, RampScheme::Atlas, 5.0f);
    RgbImage image = renderMap(f, ramp);
    const int mapWidth = image.width;
    int barX = 0;
    std::vector<LegendTick> ticks = addColourBar(image, ramp, f.verticalScale(), "m", &barX);
    EXPECT_GT(image.width, mapWidth);
    ASSERT_GE(ticks.size(), 3u);
    const double rowsPerUnit =
        (image.height - 1) / ((ramp.desc().maxHeight - ramp.desc().minHeight) * 2.5);
    for (const auto& t : ticks) {
        Rgb shown = image.at(barX + 2, t.row);
        Rgb expected = ramp.colourAt(float(t.value / 2.5));
        // One row of rounding: the colour may move by what the ramp changes in a row.
        EXPECT_LE(std::abs(shown.r - expected.r) + std::abs(shown.g - expected.g) +
                      std::abs(shown.b - expected.b),
                  6)
            << "tick " << t.label << " row " << t.row;
        // The label is the value, in world units.
        EXPECT_NEAR(std::atof(t.label.c_str()), t.value, 1e-6) << t.label;
        EXPECT_NEAR(t.row, (ramp.desc().maxHeight * 2.5 - t.value) * rowsPerUnit, 0.51);
    }
    EXPECT_NE(ticks.back().label.find(" m"), std::string::npos);
    // Numbers are drawn: the label column has ink (black) pixels beside each tick.
    int ink = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = barX + 12; x < image.width; ++x)
            if (image.at(x, y).r == 0 && image.at(x, y).g == 0) ++ink;
    EXPECT_GT(ink, int(ticks.size()) * 10);
}

TEST(Maps, DigitsAreDrawnWhole) {
    // Every stroke of every digit reaches the image: a "0" has ink in the
    // first and last columns of its box on several rows each.
    for (const char* text : {"0", "8", "-30 m"}) {
        RgbImage image{40, 20, std::vector<uint8_t>(40 * 20 * 3, 255)};
        const int width = drawText(image, 2, 2, text, {0, 0, 0}, 1);
        EXPECT_GT(width, 3) << text;
        int x0 = 40, x1 = -1;
        for (int y = 0; y < 20; ++y)
            for (int x = 0; x < 40; ++x)
                if (image.at(x, y).r == 0) x0 = std::min(x0, x), x1 = std::max(x1, x);
        ASSERT_LT(x0, x1) << text;
        int left = 0, right = 0;
        for (int y = 0; y < 20; ++y)
            left += image.at(x0, y).r == 0, right += image.at(x1, y).r == 0;
        if (std::string(text) == "0") {
            EXPECT_GE(left, 3);
            EXPECT_GE(right, 3);
        }
        EXPECT_GE(right, 1) << text;
    }
}

TEST(Maps, UnknownSchemeIsAnError) {
    MapScheme scheme = MapScheme::Plasma;
    EXPECT_FALSE(parseMapScheme("rainbow", &scheme));
    EXPECT_TRUE(parseMapScheme("atlas", &scheme));
    EXPECT_EQ(scheme, MapScheme::Atlas);
}

}  // namespace
}  // namespace sierra::terrain
