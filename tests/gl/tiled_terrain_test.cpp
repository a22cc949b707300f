// The tiled terrain drawn from a tile file: the first frame comes from the
// coarse section alone, later frames from what has arrived, and once every
// tile is on the GPU the mesh is the in-memory refinement's; a GPU cache too
// small for the view still draws every frame; a drape surface colours it by
// world position.
#include "GlTest.h"

#include <sierra/render/DrapeSurface.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TiledTerrain.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/TileFile.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/terrain/GridReader.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace sierra::test {
namespace {

class TiledTerrainTest : public GlTest {};

terrain::Heightfield rough(int side) {
    terrain::Heightfield f =
        terrain::generateDiamondSquare({.size = side, .seed = 4, .roughness = 0.8f});
    f.setVerticalScale(0.25f * float(side));
    return f;
}

std::string build(const terrain::Heightfield& f, int k, const std::string& name) {
    const std::string path = testing::TempDir() + "/" + name + ".sierra";
    sbt::buildTileFile(
        *terrain::memoryGridReader(f), path,
        {.k = k, .heights = sbt::TileHeights::Float32, .verticalScale = f.verticalScale()});
    return path;
}

// Pixels that are not the sky colour (RGBA8 read-back).
std::vector<uint8_t> terrainMask(const gpu::Image& image) {
    std::vector<uint8_t> mask(size_t(image.width) * size_t(image.height));
    const uint8_t* p = image.rgba.data();
    for (size_t i = 0; i < mask.size(); ++i) {
        const uint8_t* q = p + i * 4;
        mask[i] = std::abs(q[0] - 158) + std::abs(q[1] - 189) + std::abs(q[2] - 219) > 6;
    }
    return mask;
}

TEST_F(TiledTerrainTest, ConvergesToTheInMemoryRefinement) {
    const int side = 257;
    const terrain::Heightfield field = rough(side);
    const std::string path = build(field, 4, "gl_tiled");
    auto terrain = render::TiledTerrain::open({.path = path, .memoryBudget = 64u << 20});
    render::Camera camera;
    camera.position = {-60.0f, 140.0f, -40.0f};
    camera.target = {140.0f, 20.0f, 150.0f};
    camera.fovYDegrees = 50.0f;
    camera.nearPlane = 1.0f;
    camera.farPlane = 3000.0f;
    const int w = 640, h = 360;
    render::FrameTarget target = render::FrameTarget::create({.width = w, .height = h});
    const render::TiledFrameOptions options;
    target.begin({options.sky, 1.0f});
    const render::TiledFrameStats first = terrain->draw(camera, w, h, options);
    const gpu::Image coarseImage = target.read();
    const std::vector<uint8_t> coarse = terrainMask(coarseImage);
    EXPECT_GT(first.coarseTiles, 0) << "nothing has arrived for the first frame";
    EXPECT_GT(first.triangles, 0) << "the coarse section is drawn at once";
    render::TiledFrameStats stats = first;
    for (int pass = 0; pass < 60 && (pass == 0 || stats.coarseTiles > 0); ++pass) {
        terrain->waitForTiles();
        target.begin({options.sky, 1.0f});
        stats = terrain->draw(camera, w, h, options);
    }
    const gpu::Image fineImage = target.read();
    const std::vector<uint8_t> fine = terrainMask(fineImage);
    // The coarse frame is the same terrain, simplified: its colours (the
    // heights' ramp and the light) are close to the finished frame's.
    double difference = 0.0;
    for (size_t b = 0; b < fineImage.rgba.size(); ++b)
        difference += std::abs(int(fineImage.rgba[b]) - int(coarseImage.rgba[b]));
    difference /= double(fineImage.rgba.size());
    std::printf("tiled terrain: mean colour difference coarse to finished %.2f\n", difference);
    EXPECT_LT(difference, 4.0);  // 1.5 here; a flat coarse frame (corners lost) gives 8
    EXPECT_EQ(stats.coarseTiles, 0);
    // Every tile on the GPU: the refinement of the grid in memory.
    const sbt::VertexErrors errors = sbt::computeVertexErrors(field, 1);
    sbt::Refiner refiner(field, errors, {.threads = 1});
    sbt::ViewParams view;
    view.eye = {camera.position.x, camera.position.y, camera.position.z};
    view.lambda = camera.lambda(h);
    view.tau = options.tau;
    const auto planes = camera.frustumPlanes(float(w) / float(h));
    for (size_t p = 0; p < 6; ++p)
        view.planes[p] = {planes[p].x, planes[p].y, planes[p].z, planes[p].w};
    sbt::StripMesh reference;
    refiner.refineViewReference(view, reference);
    EXPECT_EQ(stats.triangles, reference.triangleCount);
    // The same terrain in both frames: its silhouette moves little.
    size_t terrainPixels = 0, differ = 0;
    for (size_t i = 0; i < fine.size(); ++i) {
        terrainPixels += fine[i];
        differ += fine[i] != coarse[i];
    }
    EXPECT_GT(terrainPixels, fine.size() / 5) << "the terrain fills the frame";
    EXPECT_LT(differ, fine.size() / 10);
    std::remove(path.c_str());
}

TEST_F(TiledTerrainTest, ASmallGpuCacheStillDrawsEveryFrame) {
    const terrain::Heightfield field = rough(1025);
    const std::string path = build(field, 5, "gl_small");
    // 24 MiB: 6 MiB of GPU layers for a view that wants more.
    auto terrain = render::TiledTerrain::open({.path = path, .memoryBudget = 24u << 20});
    const int w = 320, h = 180;
    render::FrameTarget target = render::FrameTarget::create({.width = w, .height = h});
    const render::TiledFrameOptions options;
    for (int f = 0; f < 16; ++f) {
        render::Camera camera;
        const float x = 40.0f * float(f);
        camera.position = {x, 300.0f, x};
        camera.target = {x + 300.0f, 100.0f, x + 320.0f};
        camera.farPlane = 5000.0f;
        target.begin({options.sky, 1.0f});
        const render::TiledFrameStats stats = terrain->draw(camera, w, h, options);
        EXPECT_GT(stats.triangles, 0) << "frame " << f;
        EXPECT_LE(stats.gpuBytes, uint64_t(6) << 20);
        EXPECT_LE(stats.cache.peakBytes, uint64_t(18) << 20);
        terrain->waitForTiles();
    }
    std::remove(path.c_str());
}

}  // namespace
}  // namespace sierra::test

namespace sierra::test {
namespace {

TEST_F(TiledTerrainTest, NoDataIsNotDrawn) {
    terrain::Heightfield field = rough(129);
    std::vector<uint8_t> mask(size_t(129) * 129, 1);
    for (int j = 50; j < 80; ++j)
        for (int i = 50; i < 80; ++i) mask[size_t(j) * 129 + size_t(i)] = 0;
    field.setMask(mask);
    const std::string path = build(field, 4, "gl_nodata");
    auto terrain = render::TiledTerrain::open({.path = path, .memoryBudget = 32u << 20});
    render::Camera camera;  // straight down over the hole, the whole grid in view
    camera.position = {64.0f, 400.0f, 64.0f};
    camera.target = {64.0f, 0.0f, 64.0f};
    camera.fovYDegrees = 30.0f;
    camera.farPlane = 2000.0f;
    const int w = 320, h = 320;
    render::FrameTarget target = render::FrameTarget::create({.width = w, .height = h});
    const render::TiledFrameOptions options;
    render::TiledFrameStats stats;
    for (int pass = 0; pass < 40 && (pass == 0 || stats.coarseTiles > 0); ++pass) {
        terrain->waitForTiles();
        target.begin({options.sky, 1.0f});
        stats = terrain->draw(camera, w, h, options);
    }
    const std::vector<uint8_t> mask2 = terrainMask(target.read());
    EXPECT_EQ(mask2[size_t(h / 2) * size_t(w) + size_t(w / 2)], 0) << "the hole shows the sky";
    EXPECT_EQ(mask2[size_t(h / 2) * size_t(w) + size_t(w / 2 + 60)], 1) << "the ground around it";
    std::remove(path.c_str());
}

}  // namespace
}  // namespace sierra::test

namespace sierra::test {
namespace {

struct Finished {
    gpu::Image image;
    render::TiledFrameStats stats;
};

// The frame of `camera` once every tile it wants is on the GPU.
Finished finishedFrame(render::TiledTerrain& terrain, const render::Camera& camera, int w, int h,
                       const render::TiledFrameOptions& options) {
    render::FrameTarget target = render::FrameTarget::create({.width = w, .height = h});
    Finished out;
    for (int pass = 0; pass < 60 && (pass == 0 || out.stats.coarseTiles > 0); ++pass) {
        terrain.waitForTiles();
        target.begin({options.sky, 1.0f});
        out.stats = terrain.draw(camera, w, h, options);
    }
    out.image = target.read();
    return out;
}

TEST_F(TiledTerrainTest, TilesBeyondTheLayerLimitShareLayers) {
    const terrain::Heightfield field = rough(257);
    const std::string path = build(field, 4, "gl_layers");  // 16^2 tiles
    render::Camera camera;  // low over the ground, the far tiles in view too
    camera.position = {20.0f, 60.0f, 10.0f};
    camera.target = {200.0f, 10.0f, 230.0f};
    camera.fovYDegrees = 60.0f;
    camera.farPlane = 3000.0f;
    const int w = 480, h = 270;
    const render::TiledFrameOptions options;
    auto whole = render::TiledTerrain::open({.path = path, .memoryBudget = 64u << 20});
    const Finished reference = finishedFrame(*whole, camera, w, h, options);
    ASSERT_EQ(reference.stats.coarseTiles, 0);
    ASSERT_GT(reference.stats.gpuTiles, 100);
    for (const int layers : {1, 3}) {
        SCOPED_TRACE(layers);
        auto packed = render::TiledTerrain::open(
            {.path = path, .memoryBudget = 64u << 20, .maxLayers = layers});
        const Finished frame = finishedFrame(*packed, camera, w, h, options);
        // Every class holds all 256 tiles in its `layers` layers.
        EXPECT_EQ(frame.stats.gpuSlots, reference.stats.gpuSlots);
        EXPECT_EQ(frame.stats.coarseTiles, 0);
        EXPECT_EQ(frame.stats.gpuTiles, reference.stats.gpuTiles);
        EXPECT_EQ(frame.stats.triangles, reference.stats.triangles);
        // The same heights: the same picture (but for a few bytes a level
        // off, the filter's rounding at other texture coordinates), so no
        // slot reads its neighbours' texels.
        size_t differ = 0;
        int worst = 0;
        for (size_t b = 0; b < frame.image.rgba.size(); ++b) {
            const int d = std::abs(int(frame.image.rgba[b]) - int(reference.image.rgba[b]));
            differ += d != 0;
            worst = std::max(worst, d);
        }
        std::printf("%d layers: %zu bytes differ, by %d at most\n", layers, differ, worst);
        EXPECT_LE(worst, 2);
        EXPECT_LT(differ, frame.image.rgba.size() / 10000);
    }
    std::remove(path.c_str());
}

// An image of two halves, `left` for columns i < side / 2, `right` beyond.
terrain::DrapeImage halves(int side, std::array<uint8_t, 3> left, std::array<uint8_t, 3> right) {
    terrain::DrapeImage image;
    image.width = image.height = side;
    image.rgba.resize(size_t(side) * size_t(side) * 4);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            const auto& c = i < side / 2 ? left : right;
            uint8_t* p = &image.rgba[(size_t(j) * size_t(side) + size_t(i)) * 4];
            p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
        }
    image.coverage = 1.0;
    return image;
}

TEST_F(TiledTerrainTest, ADrapeColoursTheTerrainByWorldPosition) {
    const terrain::Heightfield field = rough(257);
    const std::string path = build(field, 4, "gl_drape");
    render::Camera camera;
    camera.position = {128.0f, 260.0f, -120.0f};
    camera.target = {128.0f, 0.0f, 128.0f};
    camera.farPlane = 3000.0f;
    const int w = 320, h = 200;
    render::TiledFrameOptions options;
    options.fogDensity = 0.0f;
    auto terrain = render::TiledTerrain::open({.path = path, .memoryBudget = 64u << 20});
    // The same drape and its mirror: red | blue, then blue | red.
    std::array<gpu::Image, 2> frames;
    const std::array<uint8_t, 3> red{230, 20, 20}, blue{20, 20, 230};
    for (int k = 0; k < 2; ++k) {
        const terrain::DrapeImage image = k == 0 ? halves(64, red, blue) : halves(64, blue, red);
        const render::DrapeLayer layer{.image = &image};
        terrain->setSurface(render::makeDrapeSurface(
            render::makeRampSurface(terrain->surfaceRamp({})), std::span(&layer, 1)));
        const Finished frame = finishedFrame(*terrain, camera, w, h, options);
        ASSERT_EQ(frame.stats.coarseTiles, 0);
        frames[size_t(k)] = frame.image;
    }
    // Every terrain pixel swaps red for blue between the two; both halves are seen.
    const std::vector<uint8_t> mask = terrainMask(frames[0]);
    size_t terrainPixels = 0, redFirst = 0, blueFirst = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        ++terrainPixels;
        const uint8_t* a = &frames[0].rgba[i * 4];
        const uint8_t* b = &frames[1].rgba[i * 4];
        const int dr = int(a[0]) - int(b[0]), db = int(a[2]) - int(b[2]);
        redFirst += dr > 8 && db < -8;
        blueFirst += dr < -8 && db > 8;
    }
    std::printf("%zu terrain pixels: %zu red then blue, %zu blue then red\n", terrainPixels,
                redFirst, blueFirst);
    ASSERT_GT(terrainPixels, size_t(w * h / 4));
    EXPECT_GT(redFirst + blueFirst, terrainPixels * 98 / 100);
    EXPECT_GT(redFirst, terrainPixels / 4);
    EXPECT_GT(blueFirst, terrainPixels / 4);
    std::remove(path.c_str());
}

}  // namespace
}  // namespace sierra::test
