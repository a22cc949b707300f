// Golden images of the default scene (the diamond-square terrain sierra-render
// draws with no arguments), compared by GoldenCompare.h with a tolerance that
// survives llvmpipe versions but not another mesh, a shifted colour, or a
// black, flipped or wrongly coloured frame.
//
// SIERRA_UPDATE_GOLDEN=1 rewrites the references in tests/golden/.

#include "GlTest.h"
#include "GoldenCompare.h"

#include <sierra/render/Capture.h>
#include <sierra/render/DebugOverlay.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/Terrain.h>
#include <sierra/terrain/Padding.h>

#include <cstdlib>
#include <filesystem>
#include <random>

using namespace sierra;

namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 360;

bool matchesGolden(const gpu::Image& image, const gpu::Image& golden) {
    return test::compareWithGolden(image, golden).matches;
}

class Golden : public test::GlTest {
  protected:
    void SetUp() override {
        createContext(kWidth, kHeight);
        field_ = scene::loadTerrain({});  // the default scene
        terrain_.emplace(render::TerrainRenderer::create(
            {.field = &field_, .seaLevel = scene::heightQuantile(field_, 0.3)}));
        target_.emplace(
            render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4}));
    }

    gpu::Image renderFrame(render::Lod lod, float tau = 1.0f) {
        return renderFrame({.lod = lod, .tau = tau});
    }
    gpu::Image renderFrame(const render::DrawOptions& options) {
        render::Camera camera =
            render::defaultCamera(terrain_->bounds(), float(kWidth) / float(kHeight));
        target_->begin(render::TerrainRenderer::clearColour({}));
        stats_ = terrain_->draw(camera, kWidth, kHeight, options);
        return target_->read();
    }

    void checkAgainstGolden(const gpu::Image& image, const std::string& name) {
        test::expectMatchesGolden(image, name);
    }

    terrain::Heightfield field_;
    std::optional<render::TerrainRenderer> terrain_;
    std::optional<render::FrameTarget> target_;
    render::DrawStats stats_;
};

// Mean RGB of rows [y0, y1) and columns [x0, x1) (default: whole rows).
glm::vec3 meanColour(const gpu::Image& image, int y0, int y1, int x0 = 0, int x1 = -1) {
    if (x1 < 0) x1 = image.width;
    glm::dvec3 sum(0.0);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const uint8_t* p = &image.rgba[(size_t(y) * image.width + x) * 4];
            sum += glm::dvec3(p[0], p[1], p[2]);
        }
    return glm::vec3(sum / double((y1 - y0) * (x1 - x0)));
}

TEST_F(Golden, FullGridFrameMatchesReference) {
    gpu::Image frame = renderFrame(render::Lod::Full);
    // Sky around the framed terrain, terrain at the centre: the frame is not
    // blank, and the margin is kept.
    glm::vec3 sky = render::Lighting{}.sky * 255.0f;
    EXPECT_LT(glm::length(meanColour(frame, 0, 10) - sky), 6.0f) << "top rows are not sky";
    EXPECT_LT(glm::length(meanColour(frame, kHeight - 6, kHeight) - sky), 6.0f)
        << "bottom rows are not sky";
    glm::vec3 centre =
        meanColour(frame, kHeight / 2 - 30, kHeight / 2 + 30, kWidth / 2 - 60, kWidth / 2 + 60);
    EXPECT_GT(glm::length(centre - sky), 40.0f) << "the centre shows no terrain";
    checkAgainstGolden(frame, "default_full.png");
}

TEST_F(Golden, SbtFrameMatchesReferenceAndFullGrid) {
    gpu::Image sbt = renderFrame(render::Lod::Sbt, 1.0f);
    uint64_t sbtTriangles = stats_.triangles;
    gpu::Image full = renderFrame(render::Lod::Full);
    uint64_t fullTriangles = stats_.triangles;
    render::ImageDifference d = render::compareImages(sbt, full, 8);
    std::printf(
        "SBT (tau 1 px, %llu triangles) against full grid (%llu): PSNR %.2f dB, %.4f%% pixels "
        "differ\n",
        (unsigned long long)sbtTriangles, (unsigned long long)fullTriangles, d.psnr,
        100.0 * d.differingShare);
    EXPECT_GE(d.psnr, 35.0);
    EXPECT_LT(sbtTriangles * 10, fullTriangles)
        << "the SBT mesh should be far smaller than the grid";
    checkAgainstGolden(sbt, "default_sbt.png");
}

TEST_F(Golden, ComparisonRejectsBlackFlippedAndMiscolouredFrames) {
    gpu::Image frame = renderFrame(render::Lod::Sbt);
    ASSERT_TRUE(matchesGolden(frame, frame));

    gpu::Image black = frame;
    for (size_t p = 0; p < black.rgba.size(); p += 4)
        black.rgba[p] = black.rgba[p + 1] = black.rgba[p + 2] = 0;
    EXPECT_FALSE(matchesGolden(black, frame));

    gpu::Image flipped = frame;
    size_t row = size_t(kWidth) * 4;
    for (int y = 0; y < kHeight; ++y)
        std::copy_n(&frame.rgba[size_t(kHeight - 1 - y) * row], row,
                    &flipped.rgba[size_t(y) * row]);
    EXPECT_FALSE(matchesGolden(flipped, frame));

    gpu::Image swapped = frame;  // RGB -> BGR
    for (size_t p = 0; p < swapped.rgba.size(); p += 4)
        std::swap(swapped.rgba[p], swapped.rgba[p + 2]);
    EXPECT_FALSE(matchesGolden(swapped, frame));
}

// The tolerance tells meshes apart: the full grid's frame is not the SBT's.
TEST_F(Golden, ComparisonRejectsTheFullGridAgainstTheSbtFrame) {
    gpu::Image sbt = renderFrame(render::Lod::Sbt, 1.0f);
    gpu::Image full = renderFrame(render::Lod::Full);
    const test::GoldenComparison c = test::compareWithGolden(full, sbt);
    std::printf("full grid against SBT frame: %s\n", c.summary().c_str());
    EXPECT_FALSE(c.matches) << c.summary();
    EXPECT_TRUE(matchesGolden(renderFrame(render::Lod::Sbt, 1.0f), sbt)) << "re-rendering differs";
}

// Every channel shifted by 8 levels (a wrong ramp or colour step) fails, up or down.
TEST_F(Golden, ComparisonRejectsAUniformShiftOfEight) {
    gpu::Image frame = renderFrame(render::Lod::Sbt);
    for (int shift : {8, -8}) {
        gpu::Image shifted = frame;
        for (size_t p = 0; p < shifted.rgba.size(); p += 4)
            for (int ch = 0; ch < 3; ++ch)
                shifted.rgba[p + ch] = uint8_t(std::clamp(int(frame.rgba[p + ch]) + shift, 0, 255));
        const test::GoldenComparison c = test::compareWithGolden(shifted, frame);
        std::printf("shift %+d: %s\n", shift, c.summary().c_str());
        EXPECT_FALSE(c.matches) << "shift " << shift << ": " << c.summary();
    }
}

// What driver versions change passes: every channel off by up to a level at
// random, plus 0.05% of the pixels (edge pixels, the share measured between
// older references and a fresh render) off by 25 to 60 levels.
TEST_F(Golden, ComparisonAcceptsDriverNoise) {
    gpu::Image frame = renderFrame(render::Lod::Sbt);
    gpu::Image noisy = frame;
    std::mt19937 random(7);
    for (size_t p = 0; p < noisy.rgba.size(); p += 4) {
        const bool edge = random() % 2000 < 1;
        for (int ch = 0; ch < 3; ++ch) {
            const int sign = random() % 2 ? 1 : -1;
            const int delta = edge ? sign * int(25 + random() % 36) : int(random() % 3) - 1;
            noisy.rgba[p + ch] = uint8_t(std::clamp(int(frame.rgba[p + ch]) + delta, 0, 255));
        }
    }
    const test::GoldenComparison c = test::compareWithGolden(noisy, frame);
    std::printf("driver-like noise: %s\n", c.summary().c_str());
    EXPECT_TRUE(c.matches) << c.summary();
}

// The line comparison lets a wireframe drawn a pixel to the side through, and
// tells another mesh (tau 1.3 instead of 1) and a black frame apart.
TEST_F(Golden, LineComparisonAllowsAPixelOfShiftButNotAnotherMesh) {
    const gpu::Image lines = renderFrame({.tau = 1.0f, .wireframe = true, .polygons = false});
    gpu::Image shifted = lines;  // one pixel to the right
    for (int y = 0; y < kHeight; ++y)
        for (int x = kWidth - 1; x > 0; --x)
            std::copy_n(&lines.rgba[(size_t(y) * kWidth + x - 1) * 4], 4,
                        &shifted.rgba[(size_t(y) * kWidth + x) * 4]);
    const test::GoldenComparison moved = test::compareLinesWithGolden(shifted, lines);
    std::printf("wireframe one pixel to the right: %s\n", moved.summary().c_str());
    EXPECT_TRUE(moved.matches) << moved.summary();
    EXPECT_FALSE(test::compareWithGolden(shifted, lines).matches)
        << "the shaded comparison should not pass it";

    const gpu::Image other = renderFrame({.tau = 1.3f, .wireframe = true, .polygons = false});
    const test::GoldenComparison mesh = test::compareLinesWithGolden(other, lines);
    std::printf("wireframe at tau 1.3 against tau 1: %s\n", mesh.summary().c_str());
    EXPECT_FALSE(mesh.matches) << mesh.summary();

    gpu::Image black = lines;
    for (size_t p = 0; p < black.rgba.size(); p += 4)
        black.rgba[p] = black.rgba[p + 1] = black.rgba[p + 2] = 0;
    EXPECT_FALSE(test::compareLinesWithGolden(black, lines).matches);
}

TEST_F(Golden, SbtFrameIsCoarserWithLargerTau) {
    renderFrame(render::Lod::Sbt, 1.0f);
    uint64_t fine = stats_.triangles;
    renderFrame(render::Lod::Sbt, 8.0f);
    uint64_t coarse = stats_.triangles;
    EXPECT_LT(coarse * 2, fine);
    EXPECT_GT(coarse, 2u);
}

TEST_F(Golden, DebugSnapshotDrawsAPanelOverTheFrame) {
    gpu::Image plain = renderFrame(render::Lod::Sbt);
    render::DebugOverlay overlay;
    render::DebugPanel panel;
    panel.rows = {{"triangles", "12345"}, {"frame", "1.0 ms"}};
    panel.frameTimesMs = {1.0f, 2.0f, 1.5f};
    render::Camera camera =
        render::defaultCamera(terrain_->bounds(), float(kWidth) / float(kHeight));
    target_->begin(render::TerrainRenderer::clearColour({}));
    terrain_->draw(camera, kWidth, kHeight, {});
    target_->resolve();
    overlay.draw(panel, kWidth, kHeight);
    gpu::Image snapshot = gpu::readFramebuffer(kWidth, kHeight);
    render::writePng(std::string(SIERRA_TEST_OUTPUT_DIR) + "/debug_snapshot.png", snapshot);

    // The panel (top-left) changes many pixels; far from it nothing changes.
    int changedInPanel = 0, changedElsewhere = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            size_t p = (size_t(y) * kWidth + x) * 4;
            bool changed = std::abs(int(plain.rgba[p]) - int(snapshot.rgba[p])) +
                               std::abs(int(plain.rgba[p + 1]) - int(snapshot.rgba[p + 1])) >
                           30;
            if (x < 120 && y < 60) changedInPanel += changed;
            if (x > 420) changedElsewhere += changed;
        }
    EXPECT_GT(changedInPanel, 120 * 60 / 2) << "no panel drawn";
    EXPECT_EQ(changedElsewhere, 0);
}

}  // namespace

namespace {

class Padding : public test::GlTest {};

// A 65x33 field padded to 65x65: seen from straight above, the padded half of
// the square shows sky, the real half shows terrain.
TEST_F(Padding, PaddedSamplesAreNotDrawn) {
    terrain::Heightfield real(65, 33, 0.0f);
    for (int j = 0; j < 33; ++j)
        for (int i = 0; i < 65; ++i) real.at(i, j) = float(i % 7 + j % 5);
    terrain::Heightfield field = terrain::padToPowerOfTwoPlusOne(real);
    ASSERT_EQ(field.width(), 65);
    auto terrain = render::TerrainRenderer::create({.field = &field, .seaLevel = -100.0f});
    EXPECT_FLOAT_EQ(terrain.bounds().max.z, 32.0f);
    auto target = render::FrameTarget::create({.width = kWidth, .height = kHeight});
    render::Camera camera;
    camera.position = {32.0f, 120.0f, 32.001f};
    camera.target = {32.0f, 0.0f, 32.0f};
    // Looking straight down, north (-z) is up: +z (rows) runs down the image.
    camera.nearPlane = 1.0f;
    camera.farPlane = 1000.0f;
    target.begin(render::TerrainRenderer::clearColour({}));
    terrain.draw(camera, kWidth, kHeight,
                 {.lod = render::Lod::Full, .lighting = {.fogDensity = 0.0f}});
    gpu::Image image = target.read();
    render::writePng(std::string(SIERRA_TEST_OUTPUT_DIR) + "/padding.png", image);
    glm::vec3 sky = render::Lighting{}.sky * 255.0f;
    // Rows 0..32 (real) above the image centre, rows 33..64 (padding) below.
    int cx = kWidth / 2;
    glm::vec3 upper = meanColour(image, kHeight / 2 - 50, kHeight / 2 - 10, cx - 60, cx + 60);
    glm::vec3 lower = meanColour(image, kHeight / 2 + 10, kHeight / 2 + 50, cx - 60, cx + 60);
    EXPECT_GT(glm::length(upper - sky), 30.0f) << "real samples missing";
    EXPECT_LT(glm::length(lower - sky), 2.0f) << "padding drawn";
}

}  // namespace
