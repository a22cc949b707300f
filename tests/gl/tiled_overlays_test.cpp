// Curvature overlays on a tiled terrain: the window they are computed on
// holds the ground near the camera; where the window is the whole terrain,
// the lines, hatches and contour edges are the in-memory renderer's; a
// smaller window draws a part of them, the part near the camera, and
// follows the camera.
#include "GlTest.h"

#include <sierra/facade/SceneView.h>
#include <sierra/facade/TiledOverlays.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/render/TiledTerrain.h>
#include <sierra/render/passes/ContourPass.h>
#include <sierra/sbt/TileFile.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/terrain/GridReader.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace sierra::test {
namespace {

constexpr int kWidth = 640, kHeight = 360;

class TiledOverlaysTest : public GlTest {};

// Relief as large as the extent, so the curvature reaches the line threshold.
terrain::Heightfield relief(int side) {
    terrain::Heightfield f =
        terrain::generateDiamondSquare({.size = side, .seed = 6, .roughness = 0.6f});
    auto [lo, hi] = f.range();
    f.setVerticalScale(0.5f * float(side - 1) / std::max(hi - lo, 1e-3f));
    return f;
}

std::string build(const terrain::Heightfield& f, const std::string& name) {
    const std::string path = testing::TempDir() + "/" + name + ".sierra";
    sbt::buildTileFile(
        *terrain::memoryGridReader(f), path,
        {.k = 4, .heights = sbt::TileHeights::Float32, .verticalScale = f.verticalScale()});
    return path;
}

render::Camera lowCamera() {
    render::Camera camera;
    camera.position = {-30.0f, 110.0f, 280.0f};
    camera.target = {150.0f, 20.0f, 110.0f};
    camera.fovYDegrees = 50.0f;
    camera.nearPlane = 1.0f;
    camera.farPlane = 3000.0f;
    return camera;
}

// Pixels an overlay darkened: the summed RGB drop from `plain` over 60.
std::vector<uint8_t> darkened(const gpu::Image& plain, const gpu::Image& drawn) {
    std::vector<uint8_t> mask(size_t(plain.width) * size_t(plain.height));
    for (size_t i = 0; i < mask.size(); ++i) {
        int drop = 0;
        for (size_t c = 0; c < 3; ++c)
            drop += int(plain.rgba[i * 4 + c]) - int(drawn.rgba[i * 4 + c]);
        mask[i] = drop > 60;
    }
    return mask;
}

size_t count(const std::vector<uint8_t>& mask) {
    return size_t(std::count(mask.begin(), mask.end(), uint8_t(1)));
}

// Shared pixels over all pixels of either mask.
double overlap(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t both = 0, either = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        both += a[i] && b[i];
        either += a[i] || b[i];
    }
    return either ? double(both) / double(either) : 0.0;
}

// The share of `part`'s pixels that `whole` has within one pixel.
double within(const std::vector<uint8_t>& part, const std::vector<uint8_t>& whole) {
    size_t in = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            if (!part[size_t(y) * kWidth + size_t(x)]) continue;
            bool near = false;
            for (int dy = -1; dy <= 1 && !near; ++dy)
                for (int dx = -1; dx <= 1 && !near; ++dx) {
                    const int u = std::clamp(x + dx, 0, kWidth - 1),
                              v = std::clamp(y + dy, 0, kHeight - 1);
                    near = whole[size_t(v) * kWidth + size_t(u)] != 0;
                }
            in += near;
        }
    const size_t n = count(part);
    return n ? double(in) / double(n) : 0.0;
}

// The tiled terrain's frame once every tile is on the GPU, with the overlays
// when given.
gpu::Image tiledFrame(render::TiledTerrain& terrain, const render::Camera& camera,
                      const render::TiledFrameOptions& options,
                      facade::TiledOverlays* overlays = nullptr) {
    render::TiledFrameOptions all = options;
    all.uploadsPerFrame = 1 << 30;
    for (int pass = 0; pass < 60 && terrain.prepare(camera, kWidth, kHeight, all).coarseTiles > 0;
         ++pass)
        terrain.waitForTiles();
    render::FrameTarget target = render::FrameTarget::create({.width = kWidth, .height = kHeight});
    target.begin({options.sky, 1.0f});
    EXPECT_EQ(terrain.draw(camera, kWidth, kHeight, options).coarseTiles, 0);
    if (overlays) overlays->draw(camera, kWidth, kHeight, options.tau);
    return target.read();
}

// The in-memory renderer's frame of the same terrain, its added passes drawn or not.
gpu::Image memoryFrame(render::TerrainRenderer& renderer, const render::Camera& camera,
                       bool passes) {
    render::FrameTarget target = render::FrameTarget::create({.width = kWidth, .height = kHeight});
    target.begin(render::TerrainRenderer::clearColour({}));
    render::DrawOptions options;
    options.geomorph = false;
    options.addedPasses = passes ? ~uint64_t(0) : 0;
    renderer.draw(camera, kWidth, kHeight, options);
    return target.read();
}

scene::Scene overlayScene(bool lines, bool hatch) {
    scene::Scene s;
    s.style.overlay.layers.lines = lines;
    s.style.overlay.layers.hatch = hatch;
    s.style.overlay.autoScale = true;
    return s;
}

TEST(TiledOverlaysWindow, HoldsTheGroundUnderTheEyeAndAhead) {
    sbt::TileFileInfo info;
    info.width = 10000;
    info.height = 6000;
    info.spacingX = 2.0f;
    info.spacingZ = 1.0f;
    render::Camera camera;
    camera.position = {8000.0f, 500.0f, 3000.0f};  // sample (4000, 3000)
    camera.target = {20000.0f, 0.0f, 3000.0f};     // far to the east
    const facade::SampleWindow w = facade::nearWindow(info, camera, 1025);
    EXPECT_EQ(w.width, 1025);
    EXPECT_EQ(w.height, 1025);
    // Half a window's ground distance (512 units of the finer spacing, 256
    // samples along x) ahead of the eye.
    EXPECT_EQ(w.i0, 4256 - 512);
    EXPECT_EQ(w.j0, 3000 - 512);
    // A near target is the centre.
    camera.target = {8100.0f, 0.0f, 3100.0f};
    const facade::SampleWindow n = facade::nearWindow(info, camera, 1025);
    EXPECT_EQ(n.i0, 4050 - 512);
    EXPECT_EQ(n.j0, 3100 - 512);
    // Beyond the terrain's edge: the window lies inside the real samples.
    camera.position = {-5000.0f, 500.0f, 9000.0f};
    camera.target = {-4000.0f, 0.0f, 9500.0f};
    const facade::SampleWindow e = facade::nearWindow(info, camera, 1025);
    EXPECT_EQ(e.i0, 0);
    EXPECT_EQ(e.j0, 6000 - 1025);
    // A terrain smaller than the window: all of it.
    info.width = 300;
    info.height = 200;
    EXPECT_EQ(facade::nearWindow(info, camera, 1025), (facade::SampleWindow{0, 0, 300, 200}));
}

TEST_F(TiledOverlaysTest, AWholeTerrainWindowDrawsTheInMemoryOverlays) {
    const terrain::Heightfield field = relief(257);
    const std::string path = build(field, "gl_tiled_overlays");
    auto terrain = render::TiledTerrain::open({.path = path, .memoryBudget = 64u << 20});
    auto memory = render::TerrainRenderer::create({.field = &field});
    const render::Camera camera = lowCamera();
    const render::TiledFrameOptions options;
    const gpu::Image tiledPlain = tiledFrame(*terrain, camera, options);
    const gpu::Image memoryPlain = memoryFrame(memory, camera, false);
    const scene::Scene s = overlayScene(true, true);
    auto overlays = facade::TiledOverlays::create(terrain->file(), s);
    ASSERT_NE(overlays, nullptr);
    const gpu::Image tiledDrawn = tiledFrame(*terrain, camera, options, overlays.get());
    EXPECT_EQ(overlays->window(), (facade::SampleWindow{0, 0, 257, 257}));
    facade::addOverlayPasses(memory, s);
    const gpu::Image memoryDrawn = memoryFrame(memory, camera, true);
    const std::vector<uint8_t> tiled = darkened(tiledPlain, tiledDrawn);
    const std::vector<uint8_t> inMemory = darkened(memoryPlain, memoryDrawn);
    const double shared = overlap(tiled, inMemory);
    std::printf("tiled overlays: %zu pixels darkened, in memory %zu, overlap %.3f\n", count(tiled),
                count(inMemory), shared);
    EXPECT_GT(count(inMemory), size_t(kWidth * kHeight / 50)) << "the overlays show";
    EXPECT_GT(shared, 0.9);  // 0.96
    EXPECT_GT(overlays->info().lines, 0u);
    std::remove(path.c_str());
}

TEST_F(TiledOverlaysTest, ASmallWindowDrawsTheOverlaysNearTheCamera) {
    const terrain::Heightfield field = relief(257);
    const std::string path = build(field, "gl_tiled_window");
    auto terrain = render::TiledTerrain::open({.path = path, .memoryBudget = 64u << 20});
    const render::Camera camera = lowCamera();
    const render::TiledFrameOptions options;
    const gpu::Image plain = tiledFrame(*terrain, camera, options);
    const scene::Scene s = overlayScene(true, false);
    auto whole = facade::TiledOverlays::create(terrain->file(), s);
    auto near = facade::TiledOverlays::create(terrain->file(), s, 129);
    const std::vector<uint8_t> all =
        darkened(plain, tiledFrame(*terrain, camera, options, whole.get()));
    const std::vector<uint8_t> part =
        darkened(plain, tiledFrame(*terrain, camera, options, near.get()));
    // The eye is over sample (-30, 280): the window is the south-west corner's.
    const facade::SampleWindow w = near->window();
    EXPECT_EQ(w.width, 129);
    EXPECT_EQ(w.i0, 0);
    EXPECT_EQ(w.j0, 257 - 129);
    std::printf(
        "tiled overlays: a 129^2 window draws %zu of the 257^2 window's %zu pixels, "
        "%.3f of them there\n",
        count(part), count(all), within(part, all));
    EXPECT_GT(count(part), count(all) / 10) << "the near ground fills much of the frame";
    EXPECT_LT(count(part), count(all) * 9 / 10) << "the far lines are not drawn";
    // The window's own field (its auto scale, its borders) differs a little
    // from the whole terrain's.
    EXPECT_GT(within(part, all), 0.9);  // 0.99
    // The camera moves half a terrain north-east: the window follows.
    render::Camera moved = camera;
    moved.position += glm::vec3(130.0f, 0.0f, -130.0f);
    moved.target += glm::vec3(130.0f, 0.0f, -130.0f);
    EXPECT_EQ(near->windowsRead(), 1);
    tiledFrame(*terrain, moved, options, near.get());
    EXPECT_EQ(near->windowsRead(), 2);
    EXPECT_GT(near->window().i0, 0);
    EXPECT_LT(near->window().j0, 257 - 129);
    // A small move keeps it.
    moved.position += glm::vec3(5.0f, 0.0f, 0.0f);
    tiledFrame(*terrain, moved, options, near.get());
    EXPECT_EQ(near->windowsRead(), 2);
    EXPECT_EQ(facade::TiledOverlays::create(terrain->file(), overlayScene(false, false)), nullptr);
    std::remove(path.c_str());
}

TEST_F(TiledOverlaysTest, ContourEdgesAreTheInMemoryOnes) {
    const terrain::Heightfield field = relief(257);
    const std::string path = build(field, "gl_tiled_contours");
    auto terrain = render::TiledTerrain::open({.path = path, .memoryBudget = 64u << 20});
    auto memory = render::TerrainRenderer::create({.field = &field});
    const render::Camera camera = lowCamera();
    render::TiledFrameOptions options;
    const gpu::Image tiledPlain = tiledFrame(*terrain, camera, options);
    const gpu::Image memoryPlain = memoryFrame(memory, camera, false);
    const render::ContourPassDesc contours;
    options.contourWidth = contours.width;
    options.contourColour = contours.colour;
    const std::vector<uint8_t> tiled = darkened(tiledPlain, tiledFrame(*terrain, camera, options));
    memory.addPass(render::ContourPass::create(contours));
    const std::vector<uint8_t> inMemory = darkened(memoryPlain, memoryFrame(memory, camera, true));
    const double shared = overlap(tiled, inMemory);
    std::printf("tiled contours: %zu pixels darkened, in memory %zu, overlap %.3f\n", count(tiled),
                count(inMemory), shared);
    EXPECT_GT(count(inMemory), size_t(kWidth * kHeight / 100)) << "the edges show";
    EXPECT_GT(shared, 0.9);  // 0.98; one-sided normals at the tile borders gave 0.72
    std::remove(path.c_str());
}

}  // namespace
}  // namespace sierra::test
