// Vector layers over the terrain (render/VectorOverlay.h): polygons fill the
// texels inside them, lines are cut to follow the surface, and a line traced
// along a ridge stays visible on it whatever the tau.

#include "GlTest.h"
#include "GoldenCompare.h"

#include <sierra/render/Capture.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/render/VectorOverlay.h>

#include <gtest/gtest.h>

#include <cmath>

namespace sierra::test {
namespace {

using terrain::GridPoint;
using terrain::VectorFeature;

terrain::VectorLayer layerOf(std::vector<VectorFeature> features) {
    terrain::VectorLayer layer;
    layer.features = std::move(features);
    return layer;
}

TEST(VectorOverlay, PolygonsFillTheTexelsInsideTheirRings) {
    // A 20 x 10 sample rectangle with a 4 x 4 hole, on a 64 x 32 grid, 2 texels a sample.
    VectorFeature area{VectorFeature::Kind::Polygon,
                       {{{10, 5}, {30, 5}, {30, 15}, {10, 15}, {10, 5}},
                        {{20, 8}, {24, 8}, {24, 12}, {20, 12}, {20, 8}}},
                       ""};
    const auto d = render::polygonDrape(layerOf({area}), 64, 32, {1.0f, 0.0f, 0.0f, 1.0f}, 0.5f);
    ASSERT_EQ(d.width, 128);
    ASSERT_EQ(d.height, 64);
    int inside = 0;
    for (size_t k = 3; k < d.rgba.size(); k += 4) inside += d.rgba[k] > 0;
    EXPECT_EQ(inside, (20 * 10 - 4 * 4) * 4) << "area times texels per sample squared";
    auto texel = [&](double i,
                     double j) {  // the texel whose centre is nearest sample coordinates (i, j)
        const int u = int(std::floor((i + 0.5) * 2)), v = int(std::floor((j + 0.5) * 2));
        return &d.rgba[(size_t(v) * d.width + u) * 4];
    };
    EXPECT_EQ(texel(12, 7)[3], 128);  // opacity 0.5
    EXPECT_EQ(texel(12, 7)[0], 255);
    EXPECT_EQ(texel(22, 10)[3], 0) << "the hole";
    EXPECT_EQ(texel(40, 10)[3], 0) << "outside";
    EXPECT_NEAR(d.coverage, double(inside) / (128.0 * 64.0), 1e-12);
}

TEST(VectorOverlay, EveryTextureLevelHoldsTheLineAtItsWidthAndDashes) {
    // A line along row 31.5 of a 64 x 64 grid: 2 texels a sample at level 0.
    analysis::LineSet lines;
    lines.vertices = {{2.0f, 31.5f, 1.0f}, {61.0f, 31.5f, 1.0f}};
    lines.offsets = {0, 2};
    for (float dash : {0.0f, 4.0f}) {
        const render::LineLayer layer{
            &lines, {.colour = {1, 0, 0, 1}, .width = 3.0f, .dashOn = dash, .dashOff = dash}};
        const render::LinePyramid p = render::rasteriseLines(std::span(&layer, 1), 64, 64);
        ASSERT_EQ(p.width, 128);
        for (int level = 0; level < 4; ++level) {
            const int w = p.levelWidth(level);
            const auto& rgba = p.levels[size_t(level)];
            // Across the line, in the middle: the coverage sums to the width, 3 texels.
            float across = 0.0f;
            const int x = w / 2 + (dash > 0.0f ? 1 : 0);
            for (int y = 0; y < p.levelHeight(level); ++y)
                across += rgba[(size_t(y) * w + x) * 4 + 3] / 255.0f;
            if (dash == 0.0f) EXPECT_NEAR(across, 3.0f, 0.35f) << "level " << level;
            // Along it: dashes of 4 texels on, 4 off, at every level.
            if (dash > 0.0f && level == 0) {
                const int y = int(std::floor((31.5 + 0.5) * 2.0));
                int changes = 0;
                bool on = rgba[(size_t(y) * w + 10) * 4 + 3] > 128;
                for (int xx = 10; xx < 110; ++xx) {
                    const bool now = rgba[(size_t(y) * w + xx) * 4 + 3] > 128;
                    changes += now != on;
                    on = now;
                }
                EXPECT_NEAR(changes, 25, 2) << "a change every 4 texels over 100";
            }
        }
    }
}

TEST(VectorOverlay, LinesAreCutToFollowTheSurface) {
    VectorFeature line{VectorFeature::Kind::Line, {{{0, 0}, {10, 0}, {10, 2.5}}}, ""};
    VectorFeature area{VectorFeature::Kind::Polygon, {{{0, 0}, {3, 0}, {0, 3}, {0, 0}}}, ""};
    const auto lines = render::vectorLines(layerOf({line, area}), true, 1.0f);
    ASSERT_EQ(lines.polylineCount(), 2u);
    const auto first = lines.polyline(0);
    EXPECT_EQ(first.size(), 1u + 10u + 3u);
    for (size_t k = 1; k < first.size(); ++k)
        EXPECT_LE(std::hypot(first[k].x - first[k - 1].x, first[k].z - first[k - 1].z),
                  1.0f + 1e-5f);
    EXPECT_FLOAT_EQ(first.back().x, 10.0f);
    EXPECT_FLOAT_EQ(first.back().z, 2.5f);
    EXPECT_EQ(render::vectorLines(layerOf({line, area}), false).polylineCount(), 1u);
}

class VectorOnTerrain : public GlTest {};

// A ridge along column 64 of a 129 x 129 grid, seen from the west, 25 degrees up: a
// red line on its crest must show along the crest at tau 1 and at tau 8.
TEST_F(VectorOnTerrain, ALineAlongARidgeStaysVisibleAtAnyTau) {
    constexpr int kW = 640, kH = 360, kN = 129;
    terrain::Heightfield field(kN, kN);
    for (int j = 0; j < kN; ++j)
        for (int i = 0; i < kN; ++i)
            field.at(i, j) = 30.0f * std::exp(-std::pow((i - 64) / 7.0f, 2.0f)) +
                             3.0f * std::sin(0.37f * float(i)) * std::cos(0.23f * float(j)) +
                             4.0f * std::sin(0.11f * float(j));
    auto renderer = render::TerrainRenderer::create({.field = &field});
    std::vector<GridPoint> crest;
    for (int j = 8; j <= 120; ++j) crest.push_back({64.0, double(j)});
    const auto layer = layerOf({{VectorFeature::Kind::Line, {crest}, ""}});
    renderer.addPass(render::LinePass::create(
        render::vectorLines(layer),
        {.width = 3.0f, .colour = {1.0f, 0.0f, 0.0f, 1.0f}, .thin = false}));
    auto target = render::FrameTarget::create({.width = kW, .height = kH});
    const render::SceneBounds bounds = renderer.bounds();
    render::Camera camera = render::framedCamera(bounds, {.target = render::defaultTarget(bounds),
                                                          .azimuthDeg = 265.0f,
                                                          .elevationDeg = 25.0f,
                                                          .aspect = float(kW) / kH});
    for (float tau : {1.0f, 8.0f}) {
        target.begin(render::TerrainRenderer::clearColour({}));
        const auto stats = renderer.draw(camera, kW, kH, {.tau = tau});
        const gpu::Image image = target.read();
        render::writePng(testOutputPath("vector_ridge_tau" + std::to_string(int(tau)) + ".png"),
                         image);
        const glm::mat4 vp = camera.viewProjection(float(kW) / kH);
        int seen = 0, inFrame = 0;
        for (const GridPoint& p : crest) {
            const glm::vec4 c =
                vp * glm::vec4(float(p.i), field.worldHeight(int(p.i), int(p.j)), float(p.j), 1.0f);
            const int x = int((c.x / c.w * 0.5f + 0.5f) * kW),
                      y = int((0.5f - c.y / c.w * 0.5f) * kH);
            if (x < 2 || y < 2 || x >= kW - 2 || y >= kH - 2) continue;
            ++inFrame;
            bool red = false;
            for (int dy = -2; dy <= 2 && !red; ++dy)
                for (int dx = -2; dx <= 2 && !red; ++dx) {
                    const uint8_t* q = &image.rgba[(size_t(y + dy) * kW + size_t(x + dx)) * 4];
                    red = q[0] > 170 && q[1] < 90 && q[2] < 90;
                }
            seen += red;
        }
        std::printf("tau %g: %lld triangles, the line seen at %d of %d crest samples\n", tau,
                    (long long)stats.triangles, seen, inFrame);
        EXPECT_GT(inFrame, 100);
        EXPECT_GE(seen, inFrame * 98 / 100) << "tau " << tau;
    }
}

}  // namespace
}  // namespace sierra::test
