// The scene's conventions and terrain loading: compass bearings map to the
// documented axes, the default sun is the direction Sierra always used, and
// loadTerrain honours height units and refuses what it cannot do yet.

#include <sierra/core/Error.h>
#include <sierra/scene/Scene.h>
#include <sierra/scene/Terrain.h>
#include <sierra/terrain/DiamondSquare.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include <algorithm>

#include <cmath>
#include <cstdio>

namespace sierra::scene {
namespace {

using ::testing::HasSubstr;

void expectNear(const Vec3& got, float x, float y, float z, float tolerance) {
    EXPECT_NEAR(got.x, x, tolerance);
    EXPECT_NEAR(got.y, y, tolerance);
    EXPECT_NEAR(got.z, z, tolerance);
}

TEST(SceneDirections, BearingsFollowTheCompass) {
    expectNear(directionFromAngles(0, 0), 0, 0, -1, 1e-6f);   // north = -z
    expectNear(directionFromAngles(90, 0), 1, 0, 0, 1e-6f);   // east = +x
    expectNear(directionFromAngles(180, 0), 0, 0, 1, 1e-6f);  // south = +z
    expectNear(directionFromAngles(270, 0), -1, 0, 0, 1e-6f);
    expectNear(directionFromAngles(123, 90), 0, 1, 0, 1e-6f);  // zenith
    Vec3 d = directionFromAngles(37, 21);
    EXPECT_NEAR(d.x * d.x + d.y * d.y + d.z * d.z, 1.0f, 1e-6f);
    EXPECT_NEAR(std::asin(d.y) * 180.0 / 3.14159265358979, 21.0, 1e-4);
}

TEST(SceneDirections, DefaultSunKeepsTheFormerDirection) {
    const float n = std::sqrt(0.45f * 0.45f + 0.75f * 0.75f + 0.35f * 0.35f);
    Scene scene;
    expectNear(directionFromAngles(scene.lighting.sunAzimuth, scene.lighting.sunAltitude),
               -0.45f / n, 0.75f / n, 0.35f / n, 2e-6f);
}

TEST(SceneTerrain, HeightUnitsChooseTheVerticalScale) {
    TerrainSource source{.generateSize = 33};
    float automatic = loadTerrain(source).verticalScale();
    EXPECT_NE(automatic, 1.0f);
    source.heightUnits = HeightUnits::Metres;
    EXPECT_EQ(loadTerrain(source).verticalScale(), 1.0f);
    source.heightUnits = HeightUnits::None;
    EXPECT_EQ(loadTerrain(source).verticalScale(), automatic);
    source.verticalScale = 3.0f;  // an explicit scale wins over the units
    EXPECT_EQ(loadTerrain(source).verticalScale(), 3.0f);
}

TEST(SceneTerrain, HurstReachesTheGenerator) {
    TerrainSource plain{.generateSize = 65};
    TerrainSource rough{.generateSize = 65, .hurst = 0.3f};
    terrain::Heightfield a = loadTerrain(plain), b = loadTerrain(rough);
    EXPECT_FALSE(std::equal(a.samples().begin(), a.samples().end(), b.samples().begin()));
    TerrainSource bad{.generateSize = 33, .hurst = -1.0f};
    EXPECT_THROW(loadTerrain(bad), Error);
}

TEST(SceneTerrain, ChannelReachesTheLoader) {
    // A colour PNG is refused as a heightmap unless a channel is chosen.
    const std::string path = ::testing::TempDir() + "/scene_colour.png";
    std::vector<uint8_t> rgb(4 * 4 * 3);
    for (size_t k = 0; k < rgb.size(); k += 3)
        rgb[k] = uint8_t(k), rgb[k + 1] = 7, rgb[k + 2] = 200;
    ASSERT_TRUE(stbi_write_png(path.c_str(), 4, 4, 3, rgb.data(), 12));
    TerrainSource grey{.heightmap = path};
    EXPECT_THROW(loadTerrain(grey), Error);
    TerrainSource green{.heightmap = path, .verticalScale = 1.0f, .channel = Channel::Green};
    terrain::Heightfield f = loadTerrain(green);
    EXPECT_EQ(f.range().first, 7.0f);
    EXPECT_EQ(f.range().second, 7.0f);
    TerrainSource red{.heightmap = path, .verticalScale = 1.0f, .channel = Channel::Red};
    EXPECT_GT(loadTerrain(red).range().second, 7.0f);
}

TEST(SceneTerrain, PaddingNoneKeepsTheSamplesAsRead) {
    // A 6x3 grey image: padded to 9x9 for the SBT, kept 6x3 for the TIN, with
    // the same samples, spacing and vertical scale.
    const std::string path = ::testing::TempDir() + "/scene_as_read.png";
    std::vector<uint8_t> grey(6 * 3);
    for (size_t k = 0; k < grey.size(); ++k) grey[k] = uint8_t(10 * k);
    ASSERT_TRUE(stbi_write_png(path.c_str(), 6, 3, 1, grey.data(), 6));
    TerrainSource source{.heightmap = path};
    std::string paddedText, plainText;
    terrain::Heightfield padded = loadTerrain(source, &paddedText);
    terrain::Heightfield plain = loadTerrain(source, &plainText, Padding::None);
    EXPECT_EQ(padded.width(), 9);
    EXPECT_EQ(padded.height(), 9);
    ASSERT_EQ(plain.width(), 6);
    ASSERT_EQ(plain.height(), 3);
    EXPECT_FALSE(plain.hasMask());
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 6; ++i) EXPECT_EQ(plain.at(i, j), padded.at(i, j)) << i << "," << j;
    EXPECT_EQ(plain.verticalScale(), padded.verticalScale());
    EXPECT_EQ(plain.spacingX(), padded.spacingX());
    EXPECT_THAT(paddedText, HasSubstr("padded to 9x9"));
    EXPECT_THAT(plainText, ::testing::Not(HasSubstr("padded")));
}

TEST(SceneTerrain, EnumNamesRoundTrip) {
    for (HeightUnits u : {HeightUnits::Auto, HeightUnits::Metres, HeightUnits::None})
        EXPECT_EQ(parseHeightUnits(toString(u), "x"), u);
    for (Channel c :
         {Channel::Grey, Channel::Luminance, Channel::Red, Channel::Green, Channel::Blue})
        EXPECT_EQ(parseChannel(toString(c), "x"), c);
    for (PathType p : {PathType::None, PathType::Orbit, PathType::Flyover, PathType::Keyframes})
        EXPECT_EQ(parsePathType(toString(p), "x"), p);
    for (LodMode m : {LodMode::Sbt, LodMode::Full}) EXPECT_EQ(parseLodMode(toString(m), "x"), m);
    for (Projection p : {Projection::Perspective, Projection::Orthographic})
        EXPECT_EQ(parseProjection(toString(p), "x"), p);
    EXPECT_EQ(parseHeightUnits("metres", "x"), HeightUnits::Metres);
}

// A grid that pads past the caller's limit (a renderer's texture size) is
// refused before its samples exist, for files and for the generator.
TEST(SceneTerrain, MaxPaddedSideBoundsFilesAndTheGenerator) {
    const std::string path = ::testing::TempDir() + "/scene_wide.pgm";
    {
        std::FILE* f = std::fopen(path.c_str(), "wb");
        ASSERT_NE(f, nullptr);
        std::fputs("P5 40 2 255\n", f);
        for (int k = 0; k < 80; ++k) std::fputc(k, f);
        std::fclose(f);
    }
    TerrainSource file{.heightmap = path};
    EXPECT_EQ(loadTerrain(file, nullptr, Padding::PowerOfTwoPlusOne, 65).width(), 65);
    try {
        loadTerrain(file, nullptr, Padding::PowerOfTwoPlusOne, 33);
        ADD_FAILURE() << "a 40x2 file was loaded under a 33x33 limit";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "pads to a 65x65 grid (4225 samples), over the limit of 33x33"),
                  std::string::npos)
            << e.what();
    }
    TerrainSource generated{.generateSize = 65};
    EXPECT_EQ(loadTerrain(generated, nullptr, Padding::PowerOfTwoPlusOne, 65).width(), 65);
    EXPECT_THROW(loadTerrain(generated, nullptr, Padding::PowerOfTwoPlusOne, 33), Error);
}

// Roughness only sets the generated heights' units; beyond kMaxRoughness the
// scene is refused by name, not by a vertical scale overflowing later.
TEST(SceneTerrain, RoughnessIsBounded) {
    Scene scene;
    scene.terrain.roughness = 1e38f;
    try {
        validateScene(scene);
        ADD_FAILURE() << "roughness 1e38 was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("--roughness"), std::string::npos) << e.what();
    }
    scene.terrain.roughness = terrain::kMaxRoughness;
    EXPECT_NO_THROW(validateScene(scene));
    TerrainSource rough{.generateSize = 33, .roughness = terrain::kMaxRoughness};
    const terrain::Heightfield field = loadTerrain(rough);
    for (float h : field.samples()) ASSERT_TRUE(std::isfinite(h));
}

}  // namespace
}  // namespace sierra::scene
