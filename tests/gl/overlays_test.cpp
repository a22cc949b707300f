// The overlay passes (lines, hatches, contour edges): they restore the GL
// state, hatches on a cylinder run along or across its axis as asked, and
// golden images of a line preset, a hatch preset and contours on one terrain.
//
// SIERRA_UPDATE_GOLDEN=1 rewrites the references in tests/golden/.

#include "GlTest.h"
#include "GoldenCompare.h"

#include <sierra/core/Error.h>
#include <sierra/facade/SceneView.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/Capture.h>
#include <sierra/render/CurvatureGpu.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/render/passes/ContourPass.h>
#include <sierra/render/passes/HatchPass.h>
#include <sierra/render/passes/LinePass.h>
#include <sierra/scene/Scene.h>
#include <sierra/terrain/DiamondSquare.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

using namespace sierra;

namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;

class Overlays : public test::GlTest {
  protected:
    void SetUp() override { createContext(kWidth, kHeight); }
};

// Relief as large as the extent: curvature in world units of the order the
// presets' scales and the 0.5 line threshold expect (at a tenth of that,
// hardly a vertex reaches the threshold).
terrain::Heightfield fractal(int size) {
    terrain::Heightfield field = terrain::generateDiamondSquare({.size = size, .seed = 3});
    auto [lo, hi] = field.range();
    field.setVerticalScale(float(size - 1) / std::max(hi - lo, 1e-3f));
    return field;
}

TEST_F(Overlays, EveryOverlayPassRestoresTheGlState) {
    terrain::Heightfield field = fractal(65);
    auto renderer = render::TerrainRenderer::create({.field = &field});
    auto curvature = std::make_shared<render::CurvatureGpu>(render::CurvatureGpu::create(field));
    curvature->compute({.scale = 4.0f});
    analysis::LineSet lines =
        analysis::traceLines(curvature->read(), {.threshold = 0.3f, .minVertices = 3});
    ASSERT_GT(lines.polylineCount(), 0u);
    renderer.addPass(render::HatchPass::create(curvature));
    renderer.addPass(render::LinePass::create(lines, {.width = 2.0f}));
    renderer.addPass(render::ContourPass::create());
    auto target = render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4});
    render::Camera camera = render::defaultCamera(renderer.bounds(), float(kWidth) / kHeight);
    target.begin(render::TerrainRenderer::clearColour({}));
    gpu::Texture texture = gpu::Texture::create({.width = 4, .height = 4});
    glEnable(GL_CULL_FACE);
    glDepthFunc(GL_GREATER);
    glBlendFunc(GL_ONE, GL_ONE);
    glBindTextureUnit(3, texture.id());
    glBindTextureUnit(4, texture.id());
    gpu::GlState before = gpu::GlState::capture();
    renderer.draw(camera, kWidth, kHeight, {});
    EXPECT_EQ(before.differences(gpu::GlState::capture()), "");
}

TEST_F(Overlays, PassesRejectBadWidths) {
    EXPECT_THROW(render::LinePass::create({}, {.width = 0.0f}), Error);
    EXPECT_THROW(render::ContourPass::create({.width = -1.0f}), Error);
    terrain::Heightfield field = fractal(17);
    auto curvature = std::make_shared<render::CurvatureGpu>(render::CurvatureGpu::create(field));
    EXPECT_THROW(render::HatchPass::create(curvature, {.length = 0.0f}), Error);
    EXPECT_THROW(render::HatchPass::create(curvature, {.opacityGain = 0.0f}), Error);
}

// Orientation of the dark strokes in an image: the structure tensor of the
// grey levels; returns the unit screen direction the strokes run along (the
// tensor's minor axis: intensity changes least along a stroke). x right, y down.
glm::vec2 strokeDirection(const gpu::Image& image) {
    double sxx = 0, syy = 0, sxy = 0;
    auto grey = [&](int x, int y) {
        const uint8_t* p = &image.rgba[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
        return (double(p[0]) + p[1] + p[2]) / 3.0;
    };
    for (int y = 1; y + 1 < image.height; ++y)
        for (int x = 1; x + 1 < image.width; ++x) {
            double gx = grey(x + 1, y) - grey(x - 1, y), gy = grey(x, y + 1) - grey(x, y - 1);
            sxx += gx * gx;
            syy += gy * gy;
            sxy += gx * gy;
        }
    // The eigenvector of the smaller eigenvalue.
    double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);  // major axis (gradient direction)
    return {float(-std::sin(angle)), float(std::cos(angle))};
}

TEST_F(Overlays, HatchesOnACylinderRunAlongOrAcrossItsAxisAsAsked) {
    // A cylinder of radius 40 with its axis along x: curvature is greatest
    // along z (across the axis). Seen from straight above, north (-z) up.
    const int n = 65;
    terrain::Heightfield field(n, n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            float z = float(j - 32);
            field.at(i, j) = std::sqrt(std::max(1600.0f - z * z, 0.0f));
        }
    auto renderer = render::TerrainRenderer::create({.field = &field});
    renderer.setSurface(render::makePaperSurface());
    auto curvature = std::make_shared<render::CurvatureGpu>(render::CurvatureGpu::create(field));
    curvature->compute({.method = analysis::CurvatureMethod::ThreeVertex, .scale = 40.0f});
    auto target = render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4});
    // the middle of the cylinder only, 9 pixels a cell
    const render::Camera camera = test::topDownCamera({32.0f, 40.0f, 32.0f}, 20.0f);
    glm::mat4 viewProj = camera.viewProjection(float(kWidth) / kHeight);
    auto screen = [&](glm::vec3 p) {
        glm::vec4 c = viewProj * glm::vec4(p, 1.0f);
        return glm::vec2(c.x / c.w, -c.y / c.w) * glm::vec2(kWidth, kHeight) * 0.5f;  // y down
    };
    glm::vec2 zAxis = glm::normalize(screen({32.0f, 40.0f, 33.0f}) - screen({32.0f, 40.0f, 32.0f}));
    glm::vec2 xAxis = glm::normalize(screen({33.0f, 40.0f, 32.0f}) - screen({32.0f, 40.0f, 32.0f}));
    for (auto direction : {analysis::HatchDirection::Along, analysis::HatchDirection::Across}) {
        auto r = render::TerrainRenderer::create({.field = &field});
        r.setSurface(render::makePaperSurface());
        r.addPass(render::HatchPass::create(
            curvature, {.length = 1.0f, .width = 1.5f, .direction = direction}));
        target.begin(render::TerrainRenderer::clearColour({}));
        r.draw(camera, kWidth, kHeight, {.lod = render::Lod::Full});
        gpu::Image image = target.read();
        glm::vec2 d = strokeDirection(image);
        glm::vec2 expected = direction == analysis::HatchDirection::Along ? zAxis : xAxis;
        EXPECT_GT(std::fabs(glm::dot(d, expected)), 0.95f)
            << analysis::hatchDirectionName(direction) << ": strokes run along (" << d.x << ", "
            << d.y << ") on screen, expected (" << expected.x << ", " << expected.y << ")";
    }
    (void)renderer;
}

// The opacity gain multiplies the field's opacity: a field at a quarter of
// the scale drawn with gain 4 gives the strokes of the full scale with gain 1
// (what lets one automatic scale, chosen for lines, serve hatches too).
TEST_F(Overlays, HatchOpacityGainMultipliesTheFieldsOpacity) {
    const int n = 65;
    terrain::Heightfield field(n, n);  // a cylinder of radius 40 along x
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            float z = float(j - 32);
            field.at(i, j) = std::sqrt(std::max(1600.0f - z * z, 0.0f));
        }
    auto target = render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4});
    const render::Camera camera = test::topDownCamera({32.0f, 40.0f, 32.0f}, 20.0f);
    auto draw = [&](float scale, float gain) {
        auto curvature =
            std::make_shared<render::CurvatureGpu>(render::CurvatureGpu::create(field));
        curvature->compute({.method = analysis::CurvatureMethod::ThreeVertex, .scale = scale});
        auto r = render::TerrainRenderer::create({.field = &field});
        r.setSurface(render::makePaperSurface());
        if (gain > 0.0f)
            r.addPass(render::HatchPass::create(
                curvature, {.length = 1.0f, .width = 1.5f, .opacityGain = gain}));
        target.begin(render::TerrainRenderer::clearColour({}));
        r.draw(camera, kWidth, kHeight, {.lod = render::Lod::Full});
        gpu::Image image = target.read();
        double ink = 0.0;  // summed darkness below white
        for (size_t k = 0; k + 3 < image.rgba.size(); k += 4)
            ink += 255.0 * 3 - (double(image.rgba[k]) + image.rgba[k + 1] + image.rgba[k + 2]);
        return ink;
    };
    // Three-vertex curvature of the cylinder is about 1/40 across it: scale 40
    // makes the strokes opaque, scale 10 a quarter.
    const double paper = draw(40.0f, 0.0f);  // the shaded cylinder without strokes
    const double full = draw(40.0f, 1.0f) - paper, quarter = draw(10.0f, 1.0f) - paper,
                 restored = draw(10.0f, 4.0f) - paper;
    ASSERT_GT(full, 0.05 * paper) << "the strokes are visible";
    EXPECT_LT(quarter, 0.4 * full) << "a quarter of the opacity draws a fraction of the ink";
    EXPECT_NEAR(restored, full, 0.05 * full) << "gain 4 restores the full scale's strokes";
}

const uint8_t* pixel(const gpu::Image& image, int x, int y) {
    return &image.rgba[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
}

// Whether a frame's pixel has the sky's colour (within 6, summed over RGB).
struct SkyTest {
    const uint8_t* sky;
    // The clear colour of frames drawn with the default lighting.
    static const uint8_t* clearColour() {
        static const std::array<uint8_t, 3> bytes = [] {
            const glm::vec4 c = render::TerrainRenderer::clearColour({});
            return std::array<uint8_t, 3>{uint8_t(std::lround(c.r * 255.0f)),
                                          uint8_t(std::lround(c.g * 255.0f)),
                                          uint8_t(std::lround(c.b * 255.0f))};
        }();
        return bytes.data();
    }
    bool operator()(const gpu::Image& image, int x, int y) const {
        const uint8_t* p = pixel(image, x, y);
        return std::abs(p[0] - sky[0]) + std::abs(p[1] - sky[1]) + std::abs(p[2] - sky[2]) <= 6;
    }
};

TEST_F(Overlays, HatchesEndAtTheTerrainsEdge) {
    // Long strokes seen from straight above, the terrain framed with sky
    // around it: a stroke centred on a vertex of the outer edge is cut there
    // rather than reaching half its length into the sky (before: up to 6
    // units, 13 pixels here, where distance thinning makes the strokes 4
    // times longer).
    terrain::Heightfield field = fractal(65);
    auto curvature = std::make_shared<render::CurvatureGpu>(render::CurvatureGpu::create(field));
    curvature->compute({.scale = 4.0f}, true);
    auto renderer = render::TerrainRenderer::create({.field = &field});
    renderer.setSurface(render::makePaperSurface());
    auto target = render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4});
    const render::Camera camera = test::topDownCamera({32.0f, 0.0f, 32.0f}, 80.0f, 200.0f);
    auto frame = [&] {
        target.begin(render::TerrainRenderer::clearColour({}));
        renderer.draw(camera, kWidth, kHeight, {.lod = render::Lod::Full});
        return target.read();
    };
    const gpu::Image plain = frame();
    renderer.addPass(render::HatchPass::create(curvature, {.length = 3.0f, .width = 1.5f}));
    const gpu::Image hatched = frame();
    const SkyTest isSky{pixel(plain, 0, 0)};
    // Hatch pixels in the sky more than kRamp pixels from the terrain: the
    // quad's antialiasing ramp and half its width may pass a cut end.
    constexpr int kRamp = 2;
    int64_t terrainPixels = 0, strokePixels = 0, outside = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            terrainPixels += !isSky(plain, x, y);
            strokePixels += std::memcmp(pixel(plain, x, y), pixel(hatched, x, y), 3) != 0;
            if (isSky(hatched, x, y) || !isSky(plain, x, y)) continue;
            bool near = false;
            for (int v = std::max(0, y - kRamp); v <= std::min(kHeight - 1, y + kRamp); ++v)
                for (int u = std::max(0, x - kRamp); u <= std::min(kWidth - 1, x + kRamp); ++u)
                    near = near || !isSky(plain, u, v);
            outside += !near;
        }
    std::printf("%lld terrain pixels, %lld changed by the hatches, %lld in the sky\n",
                (long long)terrainPixels, (long long)strokePixels, (long long)outside);
    ASSERT_GT(terrainPixels, kWidth * kHeight / 4);
    EXPECT_GT(strokePixels, 2000) << "the hatches drew nothing to check";
    EXPECT_EQ(outside, 0) << "hatch pixels in the sky beside the terrain";
}

// Dark pixels of a frame (lines drawn in black over paper).
int64_t darkPixels(const gpu::Image& image) {
    int64_t n = 0;
    for (size_t p = 0; p < image.rgba.size(); p += 4)
        n += image.rgba[p] + image.rgba[p + 1] + image.rgba[p + 2] < 3 * 110;
    return n;
}

TEST_F(Overlays, LinesNeitherSinkNorFloatAtAnyTau) {
    // The same lines over the full grid and over SBT meshes of growing tau:
    // lifted by the SBT's error, they stay as visible as over the full grid
    // (none sink into a coarse mesh), and not more (none float over ridges
    // in front of them).
    terrain::Heightfield field = fractal(129);
    auto curvature = std::make_shared<render::CurvatureGpu>(render::CurvatureGpu::create(field));
    curvature->compute({.scale = 4.0f});
    analysis::LineSet lines =
        analysis::traceLines(curvature->read(), {.threshold = 0.5f, .minVertices = 4});
    auto renderer = render::TerrainRenderer::create({.field = &field});
    renderer.setSurface(render::makePaperSurface());
    renderer.addPass(render::LinePass::create(lines, {.width = 1.5f}));
    auto target = render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4});
    render::Camera camera = render::defaultCamera(renderer.bounds(), float(kWidth) / kHeight);
    auto dark = [&](render::Lod lod, float tau) {
        target.begin(render::TerrainRenderer::clearColour({}));
        renderer.draw(camera, kWidth, kHeight, {.lod = lod, .tau = tau});
        return darkPixels(target.read());
    };
    const int64_t full = dark(render::Lod::Full, 1.0f);
    ASSERT_GT(full, 200) << "too few line pixels to compare";
    // Up to 4 pixels: beyond, on a frame this small (the terrain is 180 pixels
    // wide), the coarse mesh's own outline moves enough to hide or reveal
    // whole slopes (tau 16: 14% fewer line pixels, with the lines on the
    // mesh where it is drawn).
    for (float tau : {1.0f, 2.0f, 4.0f}) {
        const int64_t sbt = dark(render::Lod::Sbt, tau);
        std::printf("tau %g: %lld dark pixels, full grid %lld\n", double(tau), (long long)sbt,
                    (long long)full);
        EXPECT_GT(double(sbt), 0.95 * double(full))
            << "tau " << tau << ": lines sink into the mesh";
        EXPECT_LT(double(sbt), 1.05 * double(full))
            << "tau " << tau << ": lines float over the mesh";
    }
}

TEST_F(Overlays, LinesThinOutWhereACellIsUnderAPixel) {
    // The same lines seen from straight above, a grid cell 2 pixels wide and
    // then 0.25: drawn whole at that size every polyline is a blob of the
    // quad's least size, and they blacken the terrain (99.4% of its pixels
    // darkened, against 42% close up); thinned to (0.25)^2, the share of
    // darkened pixels stays near the close view's.
    terrain::Heightfield field = fractal(257);
    auto curvature = std::make_shared<render::CurvatureGpu>(render::CurvatureGpu::create(field));
    // Scaled so that the top fifth of the vertices pass the threshold 0.5
    // (the lines' alpha is the curvature: at least 0.5).
    curvature->compute({.method = analysis::CurvatureMethod::ThreeVertex});
    std::vector<float> largest = analysis::largestMagnitudes(curvature->read());
    auto fifth = largest.begin() + std::ptrdiff_t(largest.size() * 2 / 5);
    std::nth_element(largest.begin(), fifth, largest.end());
    curvature->compute({.method = analysis::CurvatureMethod::ThreeVertex, .scale = 0.5f / *fifth});
    analysis::LineSet lines =
        analysis::traceLines(curvature->read(), {.threshold = 0.5f, .minVertices = 5});
    ASSERT_GT(lines.polylineCount(), 200u);
    auto plain = render::TerrainRenderer::create({.field = &field});
    plain.setSurface(render::makePaperSurface());
    auto lined = render::TerrainRenderer::create({.field = &field});
    lined.setSurface(render::makePaperSurface());
    lined.addPass(render::LinePass::create(lines));
    auto wide = render::TerrainRenderer::create({.field = &field});
    wide.setSurface(render::makePaperSurface());
    wide.addPass(render::LinePass::create(lines, {.width = 4.0f}));
    auto target = render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4});
    // The share of the terrain's pixels that the lines darken.
    auto darkShare = [&](float orthoHeight, render::TerrainRenderer& withLines) {
        const render::Camera camera =
            test::topDownCamera({128.0f, 0.0f, 128.0f}, orthoHeight, 400.0f);
        auto frame = [&](render::TerrainRenderer& r) {
            target.begin(render::TerrainRenderer::clearColour({}));
            r.draw(camera, kWidth, kHeight, {.lod = render::Lod::Full});
            return target.read();
        };
        const gpu::Image without = frame(plain), with = frame(withLines);
        const SkyTest isSky{SkyTest::clearColour()};
        int64_t terrain = 0, darkened = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                if (isSky(without, x, y)) continue;
                ++terrain;
                const uint8_t *p = pixel(without, x, y), *q = pixel(with, x, y);
                darkened += (p[0] + p[1] + p[2]) - (q[0] + q[1] + q[2]) > 30;
            }
        return double(darkened) / double(std::max<int64_t>(terrain, 1));
    };
    const double close = darkShare(float(kHeight) / 2.0f, lined),
                 far = darkShare(float(kHeight) * 4.0f, lined);
    std::printf("%zu lines, dark share: %.3f with 2 pixels a cell, %.3f with 0.25\n",
                lines.polylineCount(), close, far);
    EXPECT_GT(close, 0.02) << "too few line pixels to compare";
    EXPECT_GT(far, 0.25 * close) << "the far lines are gone";
    EXPECT_LT(far, 1.5 * close) << "the far lines blacken the terrain";
    // Lines 4 pixels wide cover 16 times the pixels of a far polyline's blob:
    // they thin out below cells of 4 pixels, to the same density of
    // polylines per screen area as the thin ones at 1.
    const double wideClose = darkShare(float(kHeight) / 2.0f, wide),
                 wideFar = darkShare(float(kHeight) * 4.0f, wide);
    std::printf("4-pixel lines, dark share: %.3f with 2 pixels a cell, %.3f with 0.25\n", wideClose,
                wideFar);
    // (Thinned by the cell alone: 0.68 and 0.82 against 0.42 for thin lines
    // close up; by the cell over the width: 0.25 and 0.12.)
    EXPECT_GT(wideFar, 0.1 * close) << "the far wide lines are gone";
    EXPECT_LT(wideFar, 1.5 * close) << "the far wide lines blacken the terrain";
    EXPECT_LT(wideClose, 1.5 * close) << "the close wide lines blacken the terrain";
}

TEST_F(Overlays, NothingIsDrawnBesideTheTerrainWhereThereIsWater) {
    // Half the terrain under water, seen low from every side: the water is
    // drawn flat at sea level, so the ground under it shows nowhere, and no
    // hatch or line may stand for it. Before the overlays took the drawn
    // surface, the hatches and lines of the sea floor hung below the water's
    // edge, outside the terrain (3,000 to 9,000 pixels here).
    terrain::Heightfield field = fractal(129);
    auto [lo, hi] = field.range();
    const float sea = lo + 0.5f * (hi - lo);
    scene::Scene s;
    s.style.overlay.layers = {.shaded = true, .lines = true, .hatch = true};
    s.style.overlay.curvature.scale = 4.0f;
    s.style.overlay.lines.minLength = 3;
    for (float azimuth : {45.0f, 135.0f, 225.0f, 315.0f}) {
        auto renderer = render::TerrainRenderer::create({.field = &field, .seaLevel = sea});
        auto target =
            render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4});
        const render::Camera camera =
            render::framedCamera(renderer.bounds(), {.target = renderer.bounds().centre(),
                                                     .azimuthDeg = azimuth,
                                                     .elevationDeg = 8.0f,
                                                     .aspect = float(kWidth) / kHeight});
        auto frame = [&] {
            target.begin(render::TerrainRenderer::clearColour({}));
            renderer.draw(camera, kWidth, kHeight, {});
            return target.read();
        };
        const gpu::Image plain = frame();
        const facade::OverlayInfo info = facade::addOverlayPasses(renderer, s);
        const gpu::Image overlaid = frame();
        // Below the terrain (rows run down the frame): beneath each column's
        // lowest pixel of the plain frame that is not the sky's colour, with
        // kMargin pixels to spare: a line along a crest on the skyline stands
        // out above it by half its width, and a stroke cut at the terrain's
        // outer edge (HatchesEndAtTheTerrainsEdge) still lies on the tangent
        // plane, off the edge's profile. The sea floor's strokes hung 10 to
        // 40 pixels below.
        constexpr int kMargin = 8;
        const SkyTest isSky{pixel(plain, 0, 0)};
        int64_t terrainPixels = 0, below = 0, changed = 0;
        std::vector<int> lowest(kWidth, -1);
        for (int x = 0; x < kWidth; ++x)
            for (int y = 0; y < kHeight; ++y) {
                if (!isSky(plain, x, y)) lowest[size_t(x)] = y, ++terrainPixels;
                changed += std::memcmp(pixel(plain, x, y), pixel(overlaid, x, y), 3) != 0;
            }
        for (int x = 0; x < kWidth; ++x) {
            int bottom = -1;  // the lowest terrain pixel within kMargin columns
            for (int u = std::max(0, x - kMargin); u <= std::min(kWidth - 1, x + kMargin); ++u)
                bottom = std::max(bottom, lowest[size_t(u)]);
            for (int y = bottom < 0 ? 0 : bottom + kMargin + 1; y < kHeight; ++y)
                below += !isSky(overlaid, x, y);
        }
        std::printf(
            "azimuth %g: %zu lines, %lld terrain pixels, %lld changed by the overlays, "
            "%lld below the terrain\n",
            double(azimuth), info.lines, (long long)terrainPixels, (long long)changed,
            (long long)below);
        ASSERT_GT(terrainPixels, kWidth * kHeight / 20);
        EXPECT_GT(changed, 500) << "azimuth " << azimuth << ": the overlays drew nothing to check";
        EXPECT_EQ(below, 0) << "azimuth " << azimuth << ": overlay pixels below the terrain";
    }
}

TEST_F(Overlays, LinesOverWaterLieOnTheWater) {
    // A basin 20 units deep under the water, and a line across it: drawn on
    // the drawn surface (the water, flat at sea level) it shows; on the sea
    // floor the water would hide it.
    const int n = 65;
    terrain::Heightfield field(n, n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float r = std::hypot(float(i - 32), float(j - 32));
            field.at(i, j) = std::min(10.0f, r - 20.0f);  // sea floor -20 at the centre
        }
    analysis::LineSet lines;
    for (int i = 20; i <= 44; ++i) lines.vertices.push_back({float(i), 32.0f, 1.0f});
    lines.offsets.push_back(uint32_t(lines.vertices.size()));
    auto target = render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4});
    auto dark = [&](float seaLevel) {
        auto renderer = render::TerrainRenderer::create({.field = &field, .seaLevel = seaLevel});
        renderer.setSurface(render::makePaperSurface());
        renderer.addPass(render::LinePass::create(lines, {.width = 3.0f}));
        const render::Camera camera = test::topDownCamera({32.0f, 0.0f, 32.0f}, 40.0f);
        target.begin(render::TerrainRenderer::clearColour({}));
        renderer.draw(camera, kWidth, kHeight, {});
        return darkPixels(target.read());
    };
    const int64_t onWater = dark(0.0f), dry = dark(-30.0f);
    std::printf("line pixels: %lld over water, %lld over the dry basin\n", (long long)onWater,
                (long long)dry);
    EXPECT_GT(dry, 100);
    EXPECT_GT(double(onWater), 0.7 * double(dry)) << "the water hides the line";
}

// Golden images of overlays on one terrain, compared with the tolerance of
// golden_test.cpp.
class OverlayGolden : public test::GlTest {
  protected:
    static constexpr int kW = 480, kH = 270;
    void SetUp() override { createContext(kW, kH); }

    void check(const std::string& name, const analysis::StyleParams& style) {
        terrain::Heightfield field = fractal(129);
        scene::Scene s;
        s.style.overlay = style;
        auto renderer = render::TerrainRenderer::create({.field = &field});
        if (!style.layers.shaded) renderer.setSurface(render::makePaperSurface());
        facade::OverlayInfo info = facade::addOverlayPasses(renderer, s);
        std::printf("%s: %zu lines, %zu segments\n", name.c_str(), info.lines, info.segments);
        auto target = render::FrameTarget::create({.width = kW, .height = kH, .samples = 4});
        render::Camera camera = render::defaultCamera(renderer.bounds(), float(kW) / kH);
        target.begin(render::TerrainRenderer::clearColour({}));
        renderer.draw(camera, kW, kH, {});
        gpu::Image image = target.read();
        const std::optional<gpu::Image> golden = test::goldenFor(image, name);
        if (!golden) return;
        render::ImageDifference d = render::compareImages(image, *golden, 24);
        std::printf("%s against golden: PSNR %.2f dB, %.4f%% pixels differ\n", name.c_str(), d.psnr,
                    100.0 * d.differingShare);
        EXPECT_TRUE(d.psnr >= 30.0 && d.differingShare <= 0.02)
            << "PSNR " << d.psnr << ", differing " << d.differingShare;
    }
};

TEST_F(OverlayGolden, LinePresetFig3a) {
    check("overlay_fig3a.png", scene::loadPreset("fig3a"));
}
TEST_F(OverlayGolden, HatchPresetFig4a) {
    check("overlay_fig4a.png", scene::loadPreset("fig4a"));
}
TEST_F(OverlayGolden, ContoursOverShadedTerrain) {
    analysis::StyleParams style;
    style.layers.contours = true;
    check("overlay_contours.png", style);
}

}  // namespace
