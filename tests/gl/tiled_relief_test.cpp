// Cast shadows and sky light on a tiled terrain (render/TiledRelief.h): a
// ridge across flat ground casts a shadow into its lee, the fields are the
// in-memory renderer's GPU relief (ReliefGpu) of the same grid, and the lee
// is darker with shadows on than off.
#include "GlTest.h"

#include <sierra/render/Camera.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/ReliefGpu.h>
#include <sierra/render/TiledTerrain.h>
#include <sierra/sbt/TileFile.h>
#include <sierra/terrain/GridReader.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

namespace sierra::test {
namespace {

class TiledReliefTest : public GlTest {};

constexpr int kSide = 257;
constexpr float kSunAzimuth = 270.0f;  // from the west: the shadow falls east
constexpr float kSunAltitude = 30.0f;  // a 60-unit ridge casts about 104 units

// Flat ground at 0 with a ridge 60 high over x = 100..110, z = 20..236
// (spacing 1, world heights).
terrain::Heightfield ridge() {
    terrain::Heightfield f{kSide, kSide};
    for (int j = 0; j < kSide; ++j)
        for (int i = 0; i < kSide; ++i)
            f.at(i, j) = (i >= 100 && i <= 110 && j >= 20 && j <= 236) ? 60.0f : 0.0f;
    return f;
}

std::string build(const terrain::Heightfield& f, const std::string& name) {
    const std::string path = testing::TempDir() + "/" + name + ".sierra";
    sbt::buildTileFile(*terrain::memoryGridReader(f), path,
                       {.k = 4, .heights = sbt::TileHeights::Float32, .verticalScale = 1.0f});
    return path;
}

render::Camera overhead() {
    render::Camera camera;  // straight down over the middle, the whole grid in view
    camera.position = {128.0f, 330.0f, 128.0f};
    camera.target = {128.0f, 0.0f, 128.0f};
    camera.fovYDegrees = 50.0f;
    camera.farPlane = 2000.0f;
    return camera;
}

constexpr int kW = 320, kH = 320;

// The grey level (mean of RGB) of the pixel showing world point p.
double brightnessAt(const gpu::Image& image, const render::Camera& camera, glm::vec3 p) {
    const glm::vec4 clip = camera.viewProjection(float(kW) / float(kH)) * glm::vec4(p, 1.0f);
    const int x = int((clip.x / clip.w * 0.5f + 0.5f) * float(kW));
    const int y = int((0.5f - clip.y / clip.w * 0.5f) * float(kH));
    const uint8_t* q = image.rgba.data() + (size_t(y) * size_t(kW) + size_t(x)) * 4;
    return (double(q[0]) + double(q[1]) + double(q[2])) / 3.0;
}

gpu::Image finished(render::TiledTerrain& terrain, const render::TiledFrameOptions& options) {
    render::FrameTarget target = render::FrameTarget::create({.width = kW, .height = kH});
    render::TiledFrameStats stats;
    for (int pass = 0; pass < 40 && (pass == 0 || stats.coarseTiles > 0); ++pass) {
        terrain.waitForTiles();
        target.begin({options.sky, 1.0f});
        stats = terrain.draw(overhead(), kW, kH, options);
    }
    EXPECT_EQ(stats.coarseTiles, 0);
    return target.read();
}

// The ridge as a tile file, opened, and frame options with the test's sun
// and no haze.
struct RidgeScene {
    terrain::Heightfield field = ridge();
    std::string path;
    std::unique_ptr<render::TiledTerrain> terrain;
    render::TiledFrameOptions options;
    explicit RidgeScene(const std::string& name) : path(build(field, name)) {
        terrain = render::TiledTerrain::open({.path = path, .memoryBudget = 64u << 20});
        options.sunDirection = render::compassDirection(kSunAzimuth, kSunAltitude);
        options.fogDensity = 0.0f;
    }
};

TEST_F(TiledReliefTest, ARidgeShadowsItsLee) {
    RidgeScene scene("gl_relief");
    const terrain::Heightfield& field = scene.field;
    const std::string& path = scene.path;
    render::TiledTerrain* terrain = scene.terrain.get();
    render::TiledFrameOptions& options = scene.options;
    const gpu::Image plain = finished(*terrain, options);
    options.shadows = true;
    const gpu::Image shadowed = finished(*terrain, options);
    const render::Camera camera = overhead();
    const glm::vec3 lee{160.0f, 0.0f, 128.0f}, beyond{240.0f, 0.0f, 128.0f},
        windward{50.0f, 0.0f, 128.0f};
    const double leeOff = brightnessAt(plain, camera, lee),
                 leeOn = brightnessAt(shadowed, camera, lee);
    std::printf("lee brightness %.1f without shadows, %.1f with\n", leeOff, leeOn);
    EXPECT_LT(leeOn, 0.85 * leeOff) << "the ridge's shadow";
    // Beyond the shadow's reach and on the sun's side, the same light.
    EXPECT_NEAR(brightnessAt(shadowed, camera, beyond), brightnessAt(plain, camera, beyond), 2.0);
    EXPECT_NEAR(brightnessAt(shadowed, camera, windward), brightnessAt(plain, camera, windward),
                2.0);

    // The fields are the GPU relief of the grid itself (the overview of a
    // small file is the whole grid).
    const render::TiledRelief& relief = terrain->relief();
    ASSERT_EQ(relief.stride(), 1);
    ASSERT_EQ(relief.width(), kSide);
    const std::vector<float> tiled = relief.readSunVisibility();
    const std::vector<float> direct = render::sunVisibilityGpu(
        field, {.azimuth = kSunAzimuth, .altitude = kSunAltitude, .diameter = options.sunSize});
    ASSERT_EQ(tiled.size(), direct.size());
    for (const auto& [i, j] : {std::pair{160, 128}, std::pair{120, 50}, std::pair{200, 200},
                               std::pair{50, 128}, std::pair{105, 128}, std::pair{240, 10}}) {
        const size_t k = size_t(j) * size_t(kSide) + size_t(i);
        EXPECT_NEAR(tiled[k], direct[k], 2e-3) << "sample " << i << ", " << j;
    }
    EXPECT_LT(tiled[size_t(128) * kSide + 160], 0.01f) << "in the lee";
    EXPECT_GT(tiled[size_t(128) * kSide + 50], 0.99f) << "in the sun";
    double worst = 0.0;
    for (size_t k = 0; k < tiled.size(); ++k)
        worst = std::max(worst, double(std::abs(tiled[k] - direct[k])));
    EXPECT_LT(worst, 2e-3);
    std::remove(path.c_str());
}

TEST_F(TiledReliefTest, SkyLightDarkensTheRidgesFoot) {
    RidgeScene scene("gl_sky");
    const terrain::Heightfield& field = scene.field;
    const std::string& path = scene.path;
    render::TiledTerrain* terrain = scene.terrain.get();
    render::TiledFrameOptions& options = scene.options;
    options.shadows = true;
    const gpu::Image shadowsOnly = finished(*terrain, options);
    options.skyLight = true;
    const gpu::Image both = finished(*terrain, options);
    // The lee's foot sees half the sky: its ambient light is less.
    const render::Camera camera = overhead();
    const glm::vec3 foot{113.0f, 0.0f, 128.0f};
    EXPECT_LT(brightnessAt(both, camera, foot), brightnessAt(shadowsOnly, camera, foot) - 3.0);
    const std::vector<float> tiled = terrain->relief().readSkyLight();
    const std::vector<float> direct = render::skyLightGpu(field);
    ASSERT_EQ(tiled.size(), direct.size());
    double worst = 0.0;
    for (size_t k = 0; k < tiled.size(); ++k)
        if (std::isfinite(direct[k]))
            worst = std::max(worst, double(std::abs(tiled[k] - direct[k])));
    EXPECT_LT(worst, 2e-3);
    EXPECT_LT(tiled[size_t(128) * kSide + 113], 0.9f) << "the foot of the ridge";
    std::remove(path.c_str());
}

}  // namespace
}  // namespace sierra::test
