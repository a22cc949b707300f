// Colour ramps: the hypsometric scheme's bands (water by depth, sand at the
// coast, grass, rock, snow), plasma and atlas, the 1D table and the 2D map.

#include <sierra/terrain/ColourRamp.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace sierra::terrain {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

int brightness(Rgb c) {
    return c.r + c.g + c.b;
}
bool blueDominant(Rgb c) {
    return c.b > c.r && c.b > c.g;
}
bool greenDominant(Rgb c) {
    return c.g > c.r && c.g > c.b;
}
bool sandy(Rgb c) {
    return c.r > 180 && c.r > c.g && c.g > c.b && c.b > 100;
}
bool snowy(Rgb c) {
    return c.r > 230 && c.g > 230 && c.b > 230;
}

// Heights -100..1000 m, sea at 0: the land relief is 1000 m, sand up to 30 m.
const ColourRampDesc kHyps{.scheme = RampScheme::Hypsometric,
                           .minHeight = -100.0f,
                           .maxHeight = 1000.0f,
                           .seaLevel = 0.0f};

TEST(TerrainColourRamp, HypsometricWaterIsBlueAndDarkerWhenDeeper) {
    const ColourRamp ramp(kHyps);
    const Rgb deep = ramp.colourAt(-95.0f), mid = ramp.colourAt(-50.0f),
              shallow = ramp.colourAt(-2.0f);
    EXPECT_TRUE(blueDominant(deep));
    EXPECT_TRUE(blueDominant(mid));
    EXPECT_TRUE(blueDominant(shallow));
    EXPECT_LT(brightness(deep), brightness(mid));
    EXPECT_LT(brightness(mid), brightness(shallow));
    // Below the range clamps to the deepest colour.
    EXPECT_EQ(brightness(ramp.colourAt(-1e9f)), brightness(ramp.colourAt(-100.0f)));
}

TEST(TerrainColourRamp, HypsometricThinSandBandAtTheCoast) {
    const ColourRamp ramp(kHyps);
    EXPECT_TRUE(sandy(ramp.colourAt(0.0f)));  // sea level itself is land
    EXPECT_TRUE(sandy(ramp.colourAt(15.0f)));
    EXPECT_TRUE(sandy(ramp.colourAt(29.0f)));
    EXPECT_FALSE(sandy(ramp.colourAt(-0.5f)));
    EXPECT_TRUE(blueDominant(ramp.colourAt(-0.5f)));
    EXPECT_FALSE(sandy(ramp.colourAt(60.0f)));  // the band is thin
    EXPECT_TRUE(greenDominant(ramp.colourAt(60.0f)));
    EXPECT_TRUE(greenDominant(ramp.colourAt(300.0f)));
}

TEST(TerrainColourRamp, HypsometricRockThenSnowOnTheHeights) {
    const ColourRamp ramp(kHyps);
    for (float h : {650.0f, 750.0f, 850.0f}) {
        const Rgb rock = ramp.colourAt(h);
        EXPECT_FALSE(greenDominant(rock)) << h;
        EXPECT_FALSE(blueDominant(rock)) << h;
        EXPECT_FALSE(snowy(rock)) << h;
        EXPECT_GE(rock.r, rock.b) << h;  // browns and greys, never bluish
    }
    EXPECT_TRUE(snowy(ramp.colourAt(920.0f)));
    EXPECT_TRUE(snowy(ramp.colourAt(1000.0f)));
    EXPECT_TRUE(snowy(ramp.colourAt(5000.0f)));  // clamped
}

TEST(TerrainColourRamp, SeaLevelOutsideTheRange) {
    const ColourRamp land({.minHeight = 100.0f, .maxHeight = 200.0f, .seaLevel = 0.0f});
    EXPECT_FALSE(blueDominant(land.colourAt(100.0f)));
    const ColourRamp water({.minHeight = 100.0f, .maxHeight = 200.0f, .seaLevel = 500.0f});
    EXPECT_TRUE(blueDominant(water.colourAt(100.0f)));
    EXPECT_TRUE(blueDominant(water.colourAt(200.0f)));
}

TEST(TerrainColourRamp, PlasmaIsMonochromeAndAtlasBlueGreen) {
    const ColourRamp plasma({.scheme = RampScheme::Plasma, .minHeight = -1.0f, .maxHeight = 3.0f});
    int previous = -1;
    for (float h = -1.0f; h <= 3.0f; h += 0.25f) {
        const Rgb c = plasma.colourAt(h);
        EXPECT_EQ(c.r, c.g);
        EXPECT_EQ(c.g, c.b);
        EXPECT_GT(int(c.r), previous);
        previous = c.r;
    }
    EXPECT_EQ(plasma.colourAt(-1.0f).r, 0);
    EXPECT_EQ(plasma.colourAt(3.0f).r, 255);

    const ColourRamp atlas({.scheme = RampScheme::Atlas, .minHeight = -10.0f, .maxHeight = 10.0f});
    EXPECT_TRUE(blueDominant(atlas.colourAt(-9.0f)));
    EXPECT_TRUE(blueDominant(atlas.colourAt(-0.1f)));
    EXPECT_TRUE(greenDominant(atlas.colourAt(0.0f)));
    EXPECT_TRUE(greenDominant(atlas.colourAt(9.0f)));
}

TEST(TerrainColourRamp, TableSamplesTheRampAsRgba8) {
    const ColourRamp ramp(kHyps);
    const std::vector<uint8_t> table = ramp.table(256);
    ASSERT_EQ(table.size(), 256u * 4);
    for (int k = 0; k < 256; ++k) {
        const Rgb c = ramp.colourAt(-100.0f + 1100.0f * float(k) / 255.0f);
        EXPECT_EQ(table[4 * k], c.r);
        EXPECT_EQ(table[4 * k + 1], c.g);
        EXPECT_EQ(table[4 * k + 2], c.b);
        EXPECT_EQ(table[4 * k + 3], 255);
    }
    EXPECT_TRUE(blueDominant({table[0], table[1], table[2]}));
    EXPECT_TRUE(snowy({table[255 * 4], table[255 * 4 + 1], table[255 * 4 + 2]}));
    EXPECT_THROW(ramp.table(1), Error);
}

TEST(TerrainColourRamp, RejectsAnEmptyRange) {
    try {
        ColourRamp({.minHeight = 5.0f, .maxHeight = 5.0f});
        ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("need finite values and minHeight < maxHeight"));
    }
    // forField widens a flat field's range instead.
    const ColourRamp flat = ColourRamp::forField(Heightfield(4, 4, 7.0f), RampScheme::Plasma, 0.0f);
    EXPECT_EQ(flat.desc().minHeight, 7.0f);
    EXPECT_EQ(flat.desc().maxHeight, 8.0f);
}

TEST(TerrainColourRamp, MapPngWithAndWithoutColourBar) {
    const fs::path dir =
        fs::temp_directory_path() / ("sierra_terrain_map_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    Heightfield f(64, 32);
    for (int j = 0; j < 32; ++j)
        for (int i = 0; i < 64; ++i) f.at(i, j) = -100.0f + 1100.0f * float(i) / 63.0f;
    std::vector<uint8_t> mask(64 * 32, 1);
    mask[5 * 64 + 7] = 0;  // (7, 5): no data, drawn black
    f.setMask(mask);
    const ColourRamp ramp(kHyps);

    const std::string plain = (dir / "plain.png").string(), barred = (dir / "bar.png").string();
    writeMapPng(plain, f, ramp, false);
    writeMapPng(barred, f, ramp, true);
    int w = 0, h = 0, n = 0;
    unsigned char* a = stbi_load(plain.c_str(), &w, &h, &n, 3);
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(w, 64);
    EXPECT_EQ(h, 32);
    auto pixel = [](const unsigned char* img, int width, int i, int j) {
        const unsigned char* p = img + 3 * (size_t(j) * width + i);
        return Rgb{p[0], p[1], p[2]};
    };
    for (int i : {0, 10, 40, 63}) {
        const Rgb want = ramp.colourAt(f.at(i, 3)), got = pixel(a, w, i, 3);
        EXPECT_EQ(got.r, want.r);
        EXPECT_EQ(got.g, want.g);
        EXPECT_EQ(got.b, want.b);
    }
    EXPECT_EQ(brightness(pixel(a, w, 7, 5)), 0);
    stbi_image_free(a);

    unsigned char* b = stbi_load(barred.c_str(), &w, &h, &n, 3);
    ASSERT_NE(b, nullptr);
    EXPECT_GT(w, 64 + 8);
    EXPECT_EQ(h, 32);
    EXPECT_TRUE(snowy(pixel(b, w, w - 1, 0)));            // top of the bar: maxHeight
    EXPECT_TRUE(blueDominant(pixel(b, w, w - 1, 31)));    // bottom: minHeight
    EXPECT_EQ(brightness(pixel(b, w, 65, 10)), 3 * 255);  // white gap
    stbi_image_free(b);

    EXPECT_THROW(writeMapPng((dir / "e.png").string(), Heightfield(), ramp, true), Error);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace sierra::terrain

namespace {

using sierra::terrain::ColourRamp;
using sierra::terrain::RampScheme;
using sierra::terrain::Rgb;

bool sameColour(Rgb a, Rgb b) {
    return a.r == b.r && a.g == b.g && a.b == b.b;
}

TEST(ElevationRamp, SameHeightSameColourOnAnyTerrain) {
    // Absolute: 800 m looks the same on a valley DEM and on an alpine one.
    ColourRamp valley({.scheme = RampScheme::Elevation,
                       .minHeight = 236.0f,
                       .maxHeight = 1076.0f,
                       .seaLevel = -10000.0f});
    ColourRamp alps({.scheme = RampScheme::Elevation,
                     .minHeight = 400.0f,
                     .maxHeight = 4800.0f,
                     .seaLevel = -10000.0f});
    EXPECT_TRUE(sameColour(valley.colourAt(800.0f), alps.colourAt(800.0f)));
    // A relative ramp would put snow on the valley's top; the elevation ramp does not.
    Rgb top = valley.colourAt(1076.0f);
    EXPECT_LT(int(top.r) + top.g + top.b, 3 * 200) << "no snow at 1076 m";
    Rgb snow = alps.colourAt(4000.0f);
    EXPECT_GT(int(snow.r) + snow.g + snow.b, 3 * 230) << "snow above the 3000 m snow line";
}

TEST(ElevationRamp, LinesMoveTheColours) {
    ColourRamp low({.scheme = RampScheme::Elevation,
                    .minHeight = 0.0f,
                    .maxHeight = 3000.0f,
                    .seaLevel = -1.0f,
                    .treeLine = 500.0f,
                    .snowLine = 1000.0f});
    Rgb snow = low.colourAt(1500.0f);
    EXPECT_GT(int(snow.r) + snow.g + snow.b, 3 * 230) << "snow above a 1000 m snow line";
    EXPECT_THROW(ColourRamp({.scheme = RampScheme::Elevation,
                             .maxHeight = 10.0f,
                             .treeLine = 800.0f,
                             .snowLine = 500.0f}),
                 sierra::Error);
}

TEST(ElevationRamp, WaterGradedByDepthBelowSeaLevel) {
    ColourRamp coast({.scheme = RampScheme::Elevation,
                      .minHeight = -1437.0f,
                      .maxHeight = 2205.0f,
                      .seaLevel = 0.0f});
    Rgb shallow = coast.colourAt(-5.0f), deep = coast.colourAt(-1400.0f),
        beach = coast.colourAt(2.0f);
    EXPECT_GT(shallow.b, shallow.r);
    EXPECT_GT(deep.b, deep.r);
    EXPECT_LT(int(deep.r) + deep.g + deep.b, int(shallow.r) + shallow.g + shallow.b)
        << "deeper is darker";
    EXPECT_GT(beach.r, beach.b) << "sand just above sea level";
}

}  // namespace
