// Shadows and sky light in rendered frames (TerrainGpu::prepareRelief, the
// terrain pass's SIERRA_RELIEF_LIGHT), on the real DEM Debian ships
// (jacksboro_fault_dem.npz, 36.4 N in Tennessee): a golden image of the lit
// valley, shadows and sky light that darken what they should and nothing
// else, the same light on the SBT as on the full grid, and automatic fog that
// leaves a far camera's terrain as clear as a near one's.
//
// SIERRA_UPDATE_GOLDEN=1 rewrites the reference in tests/golden/.

#include "GlTest.h"
#include "GoldenCompare.h"

#include <sierra/facade/SceneView.h>
#include <sierra/render/Capture.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/Scene.h>
#include <sierra/scene/Terrain.h>

#include <cmath>
#include <filesystem>
#include <optional>

using namespace sierra;

namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;
const char* kDem = "/usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz";

class ReliefLighting : public test::GlTest {
  protected:
    void SetUp() override {
        if (!std::filesystem::exists(kDem))
            GTEST_SKIP() << kDem << " is missing (apt-get install python-matplotlib-data)";
        createContext(kWidth, kHeight);
        scene_.terrain.heightmap = kDem;
        scene_.terrain.verticalScale = 2.0f;
        scene_.camera.azimuth = 200.0f;
        scene_.camera.elevation = 25.0f;
        scene_.lighting.sunAzimuth = 300.0f;
        scene_.lighting.sunAltitude = 20.0f;
        scene_.output.width = kWidth;
        scene_.output.height = kHeight;
        field_ = scene::loadTerrain(scene_.terrain);
        const float sea = scene::resolveSeaLevel(scene_.terrain, field_);
        terrain_.emplace(
            render::TerrainRenderer::create(facade::sceneTerrainDesc(scene_, field_, sea)));
        target_.emplace(
            render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4}));
    }

    gpu::Image renderFrame(const render::DrawOptions& draw,
                           std::optional<render::Camera> camera = std::nullopt) {
        const render::Camera c =
            camera ? *camera : facade::sceneCameras(scene_, terrain_->bounds()).front();
        target_->begin(render::TerrainRenderer::clearColour(draw.lighting));
        terrain_->draw(c, kWidth, kHeight, draw);
        return target_->read();
    }
    render::DrawOptions options(bool shadows, bool skyLight) const {
        render::DrawOptions draw = facade::sceneDrawOptions(scene_);
        draw.lighting.shadows = shadows;
        draw.lighting.skyLight = skyLight;
        return draw;
    }

    scene::Scene scene_;
    terrain::Heightfield field_;
    std::optional<render::TerrainRenderer> terrain_;
    std::optional<render::FrameTarget> target_;
};

double meanLuminance(const gpu::Image& image) {
    double sum = 0.0;
    for (size_t k = 0; k < image.rgba.size(); k += 4)
        sum += 0.2126 * image.rgba[k] + 0.7152 * image.rgba[k + 1] + 0.0722 * image.rgba[k + 2];
    return sum / double(image.rgba.size() / 4);
}

// Pixels where `a` is darker than `b` by more than `levels`, and lighter.
std::pair<int, int> darkerLighter(const gpu::Image& a, const gpu::Image& b, int levels) {
    int darker = 0, lighter = 0;
    for (size_t k = 0; k < a.rgba.size(); k += 4) {
        int d = 0;
        for (int c = 0; c < 3; ++c) d += int(a.rgba[k + c]) - int(b.rgba[k + c]);
        darker += d < -3 * levels;
        lighter += d > 3 * levels;
    }
    return {darker, lighter};
}

TEST_F(ReliefLighting, ShadowedSkyLitValleyMatchesReference) {
    // The scene's defaults: shadows and sky light on.
    ASSERT_TRUE(scene_.lighting.shadows && scene_.lighting.skyLight);
    gpu::Image frame = renderFrame(facade::sceneDrawOptions(scene_));
    test::expectMatchesGolden(frame, "relief_jacksboro.png");
    EXPECT_GT(terrain_->terrain().reliefMs(), 0.0);
}

TEST_F(ReliefLighting, ShadowsAndSkyLightOnlyDarken) {
    const gpu::Image plain = renderFrame(options(false, false));
    const gpu::Image shadows = renderFrame(options(true, false));
    const gpu::Image sky = renderFrame(options(false, true));
    const gpu::Image both = renderFrame(options(true, true));
    const int pixels = kWidth * kHeight;
    // A low sun (20 degrees) over ridges casts shadows on a good part of the
    // valley; visibility <= 1 never lights a pixel up.
    auto [shadowed, shadowLit] = darkerLighter(shadows, plain, 4);
    EXPECT_GT(shadowed, pixels / 50);
    EXPECT_LT(shadowLit, pixels / 1000);
    // The sky light dims the ambient term in valleys; on the flattest, most
    // open ground it stays (sky light 1 on a plane).
    auto [dimmed, skyLit] = darkerLighter(sky, plain, 2);
    EXPECT_GT(dimmed, pixels / 50);
    EXPECT_LT(skyLit, pixels / 1000);
    EXPECT_LT(meanLuminance(both), meanLuminance(shadows));
    EXPECT_LT(meanLuminance(both), meanLuminance(sky));
    // The relief fields are the full grid's at every mesh: the SBT frame
    // differs from the full grid's with them no more than without them (where
    // only the silhouettes' geometry differs).
    auto againstFull = [&](bool relief) {
        render::DrawOptions sbt = options(relief, relief), full = sbt;
        full.lod = render::Lod::Full;
        return render::compareImages(renderFrame(sbt), renderFrame(full), 8).differingShare;
    };
    const double plainShare = againstFull(false), reliefShare = againstFull(true);
    EXPECT_LT(reliefShare, plainShare + 0.005) << "plain " << plainShare;
}

TEST_F(ReliefLighting, SunBelowTheHorizonLeavesTheSkyLightAlone) {
    render::DrawOptions night = options(true, true);
    night.lighting.sunDirection = render::compassDirection(300.0f, -5.0f);
    const gpu::Image dark = renderFrame(night);
    render::DrawOptions ambientOnly = options(false, true);
    ambientOnly.lighting.sunDirection = render::compassDirection(0.0f, -90.0f);
    // No direct light at all: the frame is the sky light's ambient term.
    EXPECT_LT(render::compareImages(dark, renderFrame(ambientOnly), 2).differingShare, 0.001);
    EXPECT_LT(meanLuminance(dark), meanLuminance(renderFrame(options(true, true))));
}

// Mean distance from the sky colour (sum of RGB levels) of the pixels where
// the terrain is drawn, found by its depth.
double meanDistanceFromSky(const gpu::Image& image, const render::DepthImage& depth,
                           glm::vec3 sky) {
    double sum = 0.0;
    int count = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            // Depth rows run top-down like the image's.
            if (std::isnan(depth.depth[size_t(y) * depth.width + x])) continue;
            const uint8_t* p = &image.rgba[(size_t(y) * image.width + x) * 4];
            sum += std::abs(p[0] - sky.r) + std::abs(p[1] - sky.g) + std::abs(p[2] - sky.b);
            ++count;
        }
    return count ? sum / count : 0.0;
}

TEST_F(ReliefLighting, AutomaticFogLeavesAFarCameraClear) {
    const render::SceneBounds bounds = terrain_->bounds();
    const render::Camera near = facade::sceneCameras(scene_, bounds).front();
    render::Camera far = near;
    const float extent = std::max(bounds.size().x, bounds.size().z);
    far.position = near.target + glm::normalize(near.position - near.target) * 7.0f * extent;
    render::fitClipPlanes(far, bounds);
    const render::DrawOptions draw = options(false, false);
    const glm::vec3 sky = draw.lighting.sky * 255.0f;
    const double nearClear = meanDistanceFromSky(
        renderFrame(draw, near), terrain_->renderDepth(near, kWidth, kHeight, draw), sky);
    const double farClear = meanDistanceFromSky(
        renderFrame(draw, far), terrain_->renderDepth(far, kWidth, kHeight, draw), sky);
    // Fog of 0.35 / extent everywhere left the far camera's terrain 91% sky.
    EXPECT_GT(nearClear, 60.0);
    EXPECT_GT(farClear, 0.7 * nearClear) << "near " << nearClear << ", far " << farClear;
}

}  // namespace
