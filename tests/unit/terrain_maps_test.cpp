// 2D maps: plasma is grey, hillshade and slope behave as the usual DEM tools'
// do on planes, and the colour bar's legend labels the colours it shows.

#include <sierra/terrain/Maps.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

namespace sierra::terrain {
namespace {

// A plane z = a * i + b * j (stored heights) on a w x h grid.
Heightfield plane(int w, int h, float a, float b) {
    Heightfield f(w, h);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) f.at(i, j) = a * float(i) + b * float(j);
    return f;
}

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
    RgbImage image = renderMap(f, MapScheme::Plasma, ramp);
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

TEST(Maps, HillshadeOfPlaneFacingTheSunIsUniformAndBrighter) {
    // Sun in the north-west (315 degrees), 45 degrees up. Row 0 is north: a
    // plane that rises to the south-east (+i, +j) faces the sun.
    const Sun sun{315.0f, 45.0f};
    Heightfield towards = plane(33, 33, 0.5f, 0.5f);
    Heightfield away = plane(33, 33, -0.5f, -0.5f);
    std::vector<float> lit = hillshade(towards, sun);
    std::vector<float> dark = hillshade(away, sun);
    for (size_t k = 0; k < lit.size(); ++k) {
        ASSERT_NEAR(lit[k], lit[0], 1e-3f) << k;  // uniform, edges included
        ASSERT_NEAR(dark[k], dark[0], 1e-3f) << k;
    }
    EXPECT_GT(lit[0], dark[0] + 50.0f);
    // Facing the sun exactly (normal along the sun): slope 45 degrees towards
    // the sun at altitude 45 is lit at 255 * cos(0)... here the normal is
    // tilted atan(0.5 * sqrt 2) from vertical towards the sun: the value is
    // 255 * cos(45 deg - that tilt).
    const double tilt = std::atan(0.5 * std::sqrt(2.0));
    EXPECT_NEAR(lit[0], 255.0 * std::cos(M_PI / 4 - tilt), 0.5);
    // A flat plane is lit by sin(altitude).
    std::vector<float> flat = hillshade(plane(9, 9, 0.0f, 0.0f), sun);
    EXPECT_NEAR(flat[40], 255.0 * std::sin(M_PI / 4), 0.5);
}

TEST(Maps, HillshadeUsesVerticalScaleAndSpacing) {
    // The same world plane stored two ways shades the same: a falls 1 stored
    // unit (x1) per 1 world unit; b falls 2 stored units (x2 = 4 world) per 4.
    // Both descend to the east, towards the sun.
    Heightfield a = plane(17, 17, -1.0f, 0.0f);
    Heightfield b = plane(17, 17, -2.0f, 0.0f);
    b.setVerticalScale(2.0f);
    b.setSpacing(4.0f, 4.0f);
    const Sun sun{90.0f, 30.0f};
    EXPECT_NEAR(hillshade(a, sun)[100], hillshade(b, sun)[100], 1e-3f);
    // A gentler plane (vertical scale 0.3) turns from the low sun: darker.
    Heightfield gentler = plane(17, 17, -1.0f, 0.0f);
    gentler.setVerticalScale(0.3f);
    EXPECT_LT(hillshade(gentler, sun)[100], hillshade(a, sun)[100] - 30.0f);
}

TEST(Maps, SlopeInDegrees) {
    std::vector<float> s = slopeDegrees(plane(9, 9, 1.0f, 0.0f));  // rise 1 per 1: 45 degrees
    for (float v : s) ASSERT_NEAR(v, 45.0f, 1e-3f);
    std::vector<float> flat = slopeDegrees(plane(9, 9, 0.0f, 0.0f));
    for (float v : flat) ASSERT_NEAR(v, 0.0f, 1e-6f);
    RgbImage image = renderMap(plane(9, 9, 1.0f, 0.0f), MapScheme::Slope, ColourRamp());
    EXPECT_EQ(image.at(4, 4).r, 128);  // 255 * (1 - 45 / 90), rounded
}

TEST(Maps, AtlasLegendColoursMatchRampAtLabelledHeights) {
    Heightfield f = bumpy(129);
    f.setVerticalScale(2.5f);  // labels in world units = stored * 2.5
    ColourRamp ramp = ColourRamp::forField(f, RampScheme::Atlas, 5.0f);
    RgbImage image = renderMap(f, MapScheme::Atlas, ramp);
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
    EXPECT_THROW(parseMapScheme("rainbow"), Error);
    EXPECT_EQ(parseMapScheme("hillshade"), MapScheme::Hillshade);
}

}  // namespace
}  // namespace sierra::terrain
