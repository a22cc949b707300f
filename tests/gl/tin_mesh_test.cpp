// A TIN as the frame's mesh (--mesh): sierra-tin's OBJ of the terrain, with the
// zone borderlines as constrained edges, drawn through the same passes as the
// SBT (zone tiles and bands, wireframe), against golden images; a mesh made
// for another terrain is refused.
//
// SIERRA_UPDATE_GOLDEN=1 rewrites the references in tests/golden/.

#include "GlTest.h"
#include "GoldenCompare.h"

#include <sierra/core/Error.h>
#include <sierra/facade/SceneView.h>
#include <sierra/render/Capture.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/Assets.h>
#include <sierra/scene/Terrain.h>
#include <sierra/tin/Export.h>
#include <sierra/tin/Tin.h>
#include <sierra/tin/ZoneTin.h>
#include <sierra/zones/Palette.h>
#include <sierra/zones/ZoneMap.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

using namespace sierra;

namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;

// The TIN sierra-tin writes for `scene` with --zones auto --max-error-rel 0.01.
std::string writeTin(const scene::Scene& s, const std::string& name, size_t* triangles) {
    const terrain::Heightfield field = scene::loadTerrain(s.terrain, nullptr, scene::Padding::None);
    const zones::Palette palette = zones::loadPalette(scene::assetPath("palettes/default.json"));
    zones::AutoZoneDesc a;
    const float sea = scene::resolveSeaLevel(s.terrain, field);
    a.seaLevel = std::isnan(sea) ? field.range().first - 1.0f : sea;
    const zones::ZoneMap map = zones::autoZones(field, palette, a);
    const zones::Borderlines lines =
        tin::gridBorderlines(map, palette, {.epsilon = 0.5, .bandWidth = palette.bandWidth},
                             field.width(), field.height());
    const tin::TinResult r =
        tin::buildTin(field, tin::constraintsFromBorderlines(lines, field.width(), field.height()),
                      {.maxErrorRel = 0.01});
    std::filesystem::create_directories(SIERRA_TEST_OUTPUT_DIR);
    const std::string path = std::string(SIERRA_TEST_OUTPUT_DIR) + "/" + name;
    tin::writeObj(path, r.mesh);
    *triangles = r.mesh.triangles.size();
    return path;
}

class TinMesh : public test::GlTest {
  protected:
    void SetUp() override {
        createContext(kWidth, kHeight);
        scene_.terrain.generateSize = 129;
        scene_.zones.map = "auto";
        scene_.lod.mesh = writeTin(scene_, "tin_mesh_test.obj", &tinTriangles_);
        field_ = scene::loadTerrain(scene_.terrain);
        sea_ = scene::resolveSeaLevel(scene_.terrain, field_);
        renderer_.emplace(
            render::TerrainRenderer::create(facade::sceneTerrainDesc(scene_, field_, sea_)));
        facade::applySceneSurface(*renderer_, scene_, field_, sea_);
        target_.emplace(
            render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4}));
    }

    gpu::Image renderFrame(const render::DrawOptions& options) {
        render::Camera camera =
            render::defaultCamera(renderer_->bounds(), float(kWidth) / float(kHeight));
        target_->begin(render::TerrainRenderer::clearColour(options.lighting));
        stats_ = renderer_->draw(camera, kWidth, kHeight, options);
        return target_->read();
    }

    scene::Scene scene_;
    size_t tinTriangles_ = 0;
    terrain::Heightfield field_;
    float sea_ = 0.0f;
    std::optional<render::TerrainRenderer> renderer_;
    std::optional<render::FrameTarget> target_;
    render::DrawStats stats_;
};

TEST_F(TinMesh, ZoneTilesOnTheTinMatchReferenceAndFullGrid) {
    const std::string line = facade::applySceneMesh(*renderer_, scene_, field_);
    EXPECT_NE(line.find("triangles"), std::string::npos) << line;
    render::DrawOptions options = facade::sceneDrawOptions(scene_);
    ASSERT_EQ(options.lod, render::Lod::Mesh);
    const gpu::Image tin = renderFrame(options);
    EXPECT_EQ(stats_.triangles, tinTriangles_);
    options.lod = render::Lod::Full;
    const gpu::Image full = renderFrame(options);
    EXPECT_GT(stats_.triangles, 4 * tinTriangles_);
    // The TIN at 1% of the relief looks like the full grid, not like another frame.
    const render::ImageDifference d = render::compareImages(tin, full, 8);
    std::printf("TIN (%zu triangles) against the full grid: PSNR %.2f dB\n", tinTriangles_, d.psnr);
    EXPECT_GE(d.psnr, 24.0);
    test::expectMatchesGolden(tin, "tin_zones.png");
}

TEST_F(TinMesh, WireframeShowsTheTin) {
    facade::applySceneMesh(*renderer_, scene_, field_);
    render::DrawOptions options = facade::sceneDrawOptions(scene_);
    options.wireframe = true;
    const gpu::Image tin = renderFrame(options);
    options.lod = render::Lod::Full;
    const gpu::Image full = renderFrame(options);
    // Other edges: the wireframes differ where the shaded frames agree.
    EXPECT_LT(render::compareImages(tin, full, 8).psnr, 30.0);
    test::expectMatchesGolden(tin, "tin_wireframe.png", test::GoldenKind::Lines);
}

TEST_F(TinMesh, MeshOfAnotherTerrainIsRefused) {
    scene::Scene other = scene_;
    other.terrain.seed = 2;
    size_t triangles = 0;
    other.lod.mesh = writeTin(other, "tin_mesh_other.obj", &triangles);
    try {
        facade::applySceneMesh(*renderer_, other, field_);
        FAIL() << "a mesh of another terrain was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("tin_mesh_other.obj"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("same terrain options"), std::string::npos)
            << e.what();
    }
    other.lod.mesh = std::string(SIERRA_TEST_OUTPUT_DIR) + "/none.obj";
    EXPECT_THROW(facade::applySceneMesh(*renderer_, other, field_), Error);
}

}  // namespace
