// The debug UI: a snapshot over the default scene keeps the terrain's centre
// uncovered and puts the panels in a column beside the narrowed frame; the UI
// alone with deterministic placeholders matches a golden image; the mesh
// inspection agrees with the frame's statistics.

#include "GlTest.h"
#include "GoldenCompare.h"

#include <sierra/core/Parallel.h>
#include <sierra/facade/DebugSnapshot.h>
#include <sierra/facade/SceneView.h>
#include <sierra/gpu/Gl.h>
#include <sierra/gpu/ReadBack.h>
#include <sierra/render/Capture.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/MeshInspector.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/Terrain.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

using namespace sierra;

namespace {

constexpr int kWidth = 1280;  // the default frame size
constexpr int kHeight = 720;

class DebugSnapshot : public test::GlTest {
  protected:
    void SetUp() override {
        createContext(kWidth, kHeight);
        scene_.terrain.generateSize = 257;  // small: the snapshot, not the terrain, is tested
        field_ = scene::loadTerrain(scene_.terrain);
        terrain_.emplace(render::TerrainRenderer::create(
            {.field = &field_, .seaLevel = scene::heightQuantile(field_, 0.3)}));
        target_.emplace(
            render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4}));
        std::filesystem::create_directories(SIERRA_TEST_OUTPUT_DIR);
    }

    // The frame drawn in the left `frameWidth` pixels (the rest sky).
    gpu::Image frame(int frameWidth, render::DrawStats* stats = nullptr) {
        camera_ = render::defaultCamera(terrain_->bounds(), float(frameWidth) / float(kHeight));
        target_->begin(render::TerrainRenderer::clearColour({}));
        glViewport(0, 0, frameWidth, kHeight);
        render::DrawStats s = terrain_->draw(camera_, frameWidth, kHeight, draw_);
        target_->resolve();
        if (stats) *stats = s;
        return gpu::readFramebuffer(kWidth, kHeight);
    }

    render::DebugPanel panel(int frameWidth, const render::DrawStats& stats, bool deterministic,
                             facade::OverlayInfo overlays = {}) {
        facade::SnapshotFacts facts{.scene = &scene_,
                                    .field = &field_,
                                    .glRenderer = "test renderer",
                                    .glVersion = "4.5 test",
                                    .eglPlatform = "test platform",
                                    .renderer = &*terrain_,
                                    .camera = camera_,
                                    .frameWidth = frameWidth,
                                    .height = kHeight,
                                    .draw = draw_,
                                    .frames = {stats, stats},
                                    .frameMs = {12.0f, 14.0f},
                                    .overlays = overlays};
        return facade::buildDebugPanel(facts, deterministic);
    }

    scene::Scene scene_;
    terrain::Heightfield field_;
    std::optional<render::TerrainRenderer> terrain_;
    std::optional<render::FrameTarget> target_;
    render::Camera camera_;
    render::DrawOptions draw_{.threads = 2};
};

const uint8_t* px(const gpu::Image& image, int x, int y) {
    return &image.rgba[(size_t(y) * image.width + x) * 4];
}

bool samePixel(const gpu::Image& a, const gpu::Image& b, int x, int y) {
    const uint8_t *p = px(a, x, y), *q = px(b, x, y);
    return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
}

TEST_F(DebugSnapshot, PanelsBesideTheFrameLeaveTheTerrainUncovered) {
    const int column = facade::debugColumnWidth(kWidth);
    const int frameWidth = render::snapshotFrameWidth(kWidth, column);
    ASSERT_LT(frameWidth, kWidth);
    ASSERT_GE(frameWidth, kWidth / 3);
    render::DrawStats stats;
    gpu::Image full = frame(kWidth);
    gpu::Image narrowed = frame(frameWidth, &stats);
    render::DebugPanel p = panel(frameWidth, stats, false);
    p.columnWidth = kWidth - frameWidth;
    render::DebugOverlay overlay;
    target_->begin(render::TerrainRenderer::clearColour({}));
    glViewport(0, 0, frameWidth, kHeight);
    terrain_->draw(camera_, frameWidth, kHeight, draw_);
    target_->resolve();
    overlay.draw(p, kWidth, kHeight);
    gpu::Image shot = gpu::readFramebuffer(kWidth, kHeight);
    render::writePng(std::string(SIERRA_TEST_OUTPUT_DIR) + "/debug_column.png", shot);

    // Not blank: many distinct colours.
    std::set<uint32_t> colours;
    for (size_t k = 0; k + 3 < shot.rgba.size(); k += 4 * 7)
        colours.insert(uint32_t(shot.rgba[k]) << 16 | uint32_t(shot.rgba[k + 1]) << 8 |
                       shot.rgba[k + 2]);
    EXPECT_GT(colours.size(), 50u);

    // The frame beside the column is untouched, its centre shows terrain.
    int changedInFrame = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < frameWidth; ++x)
            changedInFrame += samePixel(shot, narrowed, x, y) ? 0 : 1;
    EXPECT_EQ(changedInFrame, 0) << "the panel covers part of the frame";
    glm::vec3 sky = render::Lighting{}.sky * 255.0f;
    const uint8_t* centre = px(shot, frameWidth / 2, kHeight / 2);
    EXPECT_GT(glm::length(glm::vec3(centre[0], centre[1], centre[2]) - sky), 30.0f)
        << "no terrain at the centre";

    // The column differs from the frame that would be beneath it.
    int differing = 0, total = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = frameWidth; x < kWidth; ++x, ++total)
            differing += samePixel(shot, full, x, y) ? 0 : 1;
    EXPECT_GT(differing, total * 9 / 10);
}

// Pixels on the border of the left `frameWidth` columns that are not sky.
int terrainOnFrameBorder(const gpu::Image& image, int frameWidth) {
    const glm::vec3 sky = render::Lighting{}.sky * 255.0f;
    auto terrain = [&](int x, int y) {
        const uint8_t* p = px(image, x, y);
        return glm::length(glm::vec3(p[0], p[1], p[2]) - sky) > 3.0f;
    };
    int n = 0;
    for (int y = 0; y < kHeight; ++y) n += terrain(0, y) + terrain(frameWidth - 1, y);
    for (int x = 0; x < frameWidth; ++x) n += terrain(x, 0) + terrain(x, kHeight - 1);
    return n;
}

// The Style section's text rows, name -> text.
std::map<std::string, std::string> styleTexts(const render::DebugPanel& panel) {
    std::map<std::string, std::string> texts;
    for (const render::DebugSection& section : panel.sections)
        if (section.title == "Style")
            for (const render::StyleParam& p : section.params)
                if (p.kind == render::StyleParam::Kind::Text) texts[p.name] = p.text;
    return texts;
}

// The text of row `label` of section `title`; "" when there is none.
std::string rowText(const render::DebugPanel& panel, const std::string& title,
                    const std::string& label) {
    for (const render::DebugSection& section : panel.sections)
        if (section.title == title)
            for (const auto& [name, text] : section.rows)
                if (name == label) return text;
    return "";
}

TEST_F(DebugSnapshot, ThreadsRowSaysWhetherTheCountIsMeasured) {
    render::DrawStats stats;
    frame(640, &stats);
    EXPECT_EQ(rowText(panel(640, stats, false), "Renderer", "threads"), "2 (refinement)");
    draw_.threads = 0;  // the default: one thread or all, whichever measures faster
    EXPECT_EQ(rowText(panel(640, stats, false), "Renderer", "threads"),
              "1 or " + std::to_string(defaultThreadCount()) + " (measured)");
}

// Metres, when the file's georeferencing says so, are named beside the
// spacing; a unitless grid's spacing has no unit.
TEST_F(DebugSnapshot, SpacingNamesMetresOnlyForGeoreferencedFields) {
    render::DrawStats stats;
    frame(640, &stats);
    EXPECT_EQ(rowText(panel(640, stats, false), "Source", "spacing"), "1.00 x 1.00");
    field_.setSpacing(74.5732f, 92.4751f);
    field_.setMetres(true);
    EXPECT_EQ(rowText(panel(640, stats, false), "Source", "spacing"), "74.57 x 92.48 m");
}

TEST_F(DebugSnapshot, StyleShowsTheOverlaysAndTheCurvatureScaleDrawn) {
    render::DrawStats stats;
    frame(640, &stats);
    auto plain = styleTexts(panel(640, stats, false));
    EXPECT_EQ(plain["overlays"], "none");
    EXPECT_EQ(plain.count("curvature"), 0u);
    EXPECT_EQ(plain.count("lines traced"), 0u);

    analysis::StyleParams& overlay = scene_.style.overlay;
    overlay.layers = {.shaded = true, .lines = true, .contours = true};
    overlay.curvature.distance = 2;
    overlay.autoScale = true;
    auto lines =
        styleTexts(panel(640, stats, false, {.lines = 12, .segments = 40, .scale = 46.3407f}));
    EXPECT_EQ(lines["overlays"], "lines, contours");
    EXPECT_EQ(lines["curvature"], "three-normal");
    EXPECT_EQ(lines["distance, scale"], "2, 46.34 (auto)");
    EXPECT_EQ(lines["lines traced"], "12");

    overlay.layers = {.shaded = true, .hatch = true};
    overlay.curvature.method = analysis::CurvatureMethod::EdgeAngle;
    overlay.curvature.distance = 1;
    overlay.autoScale = false;
    auto hatches = styleTexts(panel(640, stats, false, {.scale = 4.0f}));
    EXPECT_EQ(hatches["overlays"], "hatch");
    EXPECT_EQ(hatches["curvature"], "edge-angle");
    EXPECT_EQ(hatches["distance, scale"], "1, 4");
    EXPECT_EQ(hatches.count("lines traced"), 0u);
}

TEST_F(DebugSnapshot, SnapshotCamerasKeepTheWholeTerrainInTheNarrowFrame) {
    const int frameWidth = render::snapshotFrameWidth(kWidth, facade::debugColumnWidth(kWidth));
    auto drawNarrow = [&](const render::Camera& camera) {
        target_->begin(render::TerrainRenderer::clearColour({}));
        glViewport(0, 0, frameWidth, kHeight);
        terrain_->draw(camera, frameWidth, kHeight, draw_);
        target_->resolve();
        return gpu::readFramebuffer(kWidth, kHeight);
    };
    const gpu::Image fitted =
        drawNarrow(facade::snapshotCameras(scene_, terrain_->bounds(), frameWidth).at(0));
    render::writePng(std::string(SIERRA_TEST_OUTPUT_DIR) + "/debug_narrow_frame.png", fitted);
    EXPECT_EQ(terrainOnFrameBorder(fitted, frameWidth), 0)
        << "the terrain touches the snapshot frame's border";
    const uint8_t* centre = px(fitted, frameWidth / 2, kHeight / 2);
    EXPECT_GT(
        glm::length(glm::vec3(centre[0], centre[1], centre[2]) - render::Lighting{}.sky * 255.0f),
        30.0f);
    // The full frame's camera, drawn narrower, cuts the terrain at the sides.
    const gpu::Image cut = drawNarrow(facade::sceneCameras(scene_, terrain_->bounds()).at(0));
    EXPECT_GT(terrainOnFrameBorder(cut, frameWidth), 0);
}

TEST_F(DebugSnapshot, UiAloneMatchesGoldenWithPlaceholders) {
    const int column = facade::debugColumnWidth(kWidth);
    render::DrawStats stats;
    frame(render::snapshotFrameWidth(kWidth, column), &stats);
    stats.refineMs = 3.25, stats.uploadMs = 0.5,
    stats.drawMs = 7.0;  // placeholders must hide these
    render::DebugPanel p = panel(render::snapshotFrameWidth(kWidth, column), stats, true);
    p.columnWidth = column;
    render::DebugOverlay overlay;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, column, kHeight);
    glClearColor(0.2f, 0.2f, 0.22f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    overlay.draw(p, column, kHeight);
    gpu::Image ui = gpu::readFramebuffer(column, kHeight);
    const std::string name = "debug_snapshot_only.png";
    const std::optional<gpu::Image> golden = test::goldenFor(ui, name);
    if (!golden) return;
    render::ImageDifference d = render::compareImages(ui, *golden, 24);
    std::printf("%s against golden: PSNR %.2f dB, %.4f%% pixels differ\n", name.c_str(), d.psnr,
                100.0 * d.differingShare);
    EXPECT_LE(d.differingShare, 0.01);

    // A second, deterministic snapshot with other measured times is identical.
    stats.refineMs = 99.0;
    render::DebugPanel q = panel(render::snapshotFrameWidth(kWidth, column), stats, true);
    q.columnWidth = column;
    glClear(GL_COLOR_BUFFER_BIT);
    overlay.draw(q, column, kHeight);
    gpu::Image again = gpu::readFramebuffer(column, kHeight);
    EXPECT_EQ(again.rgba, ui.rgba);
}

TEST_F(DebugSnapshot, AShortSnapshotGrowsToShowTheWholePanel) {
    const int column = facade::debugColumnWidth(kWidth);
    render::DrawStats stats;
    frame(render::snapshotFrameWidth(kWidth, column), &stats);
    render::DebugPanel p = panel(render::snapshotFrameWidth(kWidth, column), stats, true);
    p.columnWidth = column;
    render::DebugOverlay overlay;
    // The panel needs more than 200 pixels, and fits the default 720.
    const int needed = overlay.contentHeight(p, column, 200);
    EXPECT_GT(needed, 200);
    EXPECT_LT(needed, kHeight);
    // Drawn 200 pixels high, the window scrolls: its scroll bar's grab (grey,
    // against the near-black window) shows at the right edge; drawn as high
    // as measured, nothing does. Both into offscreen targets, the tall one
    // taller than the context's pbuffer would need to be for 200.
    auto ui = [&](int height) {
        auto target = render::FrameTarget::create(
            {.width = column, .height = height, .samples = 0, .offscreen = true});
        target.begin({0.2f, 0.2f, 0.22f, 1.0f});
        target.resolve();
        overlay.draw(p, column, height);
        gpu::Image image = gpu::readFramebuffer(column, height);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        return image;
    };
    auto greyAtRightEdge = [&](const gpu::Image& image) {
        int grey = 0;
        for (int y = 30; y < image.height - 8; ++y)
            for (int x = column - 14; x < column - 2; ++x) grey += px(image, x, y)[0] > 60;
        return grey;
    };
    const gpu::Image cut = ui(200), whole = ui(needed);
    render::writePng(std::string(SIERRA_TEST_OUTPUT_DIR) + "/debug_whole_panel.png", whole);
    ASSERT_EQ(whole.height, needed);
    EXPECT_GT(greyAtRightEdge(cut), 100) << "no scroll bar on the cut-off panel";
    EXPECT_EQ(greyAtRightEdge(whole), 0) << "the panel drawn as high as measured still scrolls";
}

TEST_F(DebugSnapshot, MeshInspectionMatchesTheFrame) {
    render::DrawStats stats;
    frame(kWidth, &stats);
    render::MeshInspection m =
        render::inspectMesh(terrain_->terrain(), camera_, kWidth, kHeight, 1.0f, true, 2);
    EXPECT_EQ(uint64_t(m.triangles), stats.triangles);
    EXPECT_EQ(uint64_t(m.indices), stats.indices);
    int64_t sum = 0;
    for (int64_t c : m.levelCounts) sum += c;
    EXPECT_EQ(sum, m.triangles) << "every drawn triangle has a level";
    EXPECT_GT(m.distinctVertices, 0);
    EXPECT_LT(m.distinctVertices, m.triangles * 3);
    // Leaves are below tau except on the finest level, which has no split vertex.
    EXPECT_GT(m.maxProjectedErrorPx, 0.0);
    EXPECT_LE(m.maxProjectedErrorPx, 1.0 + 1e-3);
    // A coarser tau leaves larger errors on screen.
    render::MeshInspection coarse =
        render::inspectMesh(terrain_->terrain(), camera_, kWidth, kHeight, 8.0f, true, 2);
    EXPECT_LT(coarse.triangles, m.triangles);
    EXPECT_GT(coarse.maxProjectedErrorPx, m.maxProjectedErrorPx);
    EXPECT_LE(coarse.maxProjectedErrorPx, 8.0 + 1e-3);
}

TEST_F(DebugSnapshot, MeshPanelCountsCulledSubtrees) {
    // Low over one corner, looking across it: much of the terrain is outside the frustum.
    const render::SceneBounds b = terrain_->bounds();
    const glm::vec3 size = b.max - b.min;
    camera_ = render::defaultCamera(b, float(kWidth) / float(kHeight));
    camera_.position = b.min + glm::vec3(0.15f * size.x, size.y + 0.05f * size.x, 0.15f * size.z);
    camera_.target = b.min + glm::vec3(0.8f * size.x, 0.0f, 0.5f * size.z);
    render::fitClipPlanes(camera_, b);
    render::MeshInspection culled =
        render::inspectMesh(terrain_->terrain(), camera_, kWidth, kHeight, 1.0f, true, 2);
    render::MeshInspection all =
        render::inspectMesh(terrain_->terrain(), camera_, kWidth, kHeight, 1.0f, false, 2);
    EXPECT_GT(culled.culledSubtrees, 0);
    EXPECT_LT(culled.triangles, all.triangles);
    EXPECT_EQ(all.culledSubtrees, 0);

    // The Mesh panel shows the count (no longer "n/a").
    auto meshRow = [&](const render::DebugPanel& p) {
        for (const render::DebugSection& s : p.sections)
            if (s.title == "Mesh")
                for (const auto& row : s.rows)
                    if (row.first == "culled subtrees") return row.second;
        return std::string("(no row)");
    };
    render::DrawStats stats;
    stats.triangles = uint64_t(culled.triangles);
    EXPECT_EQ(meshRow(panel(kWidth, stats, true)),
              std::to_string(culled.culledSubtrees) + " (frustum)");
    draw_.cull = false;
    EXPECT_EQ(meshRow(panel(kWidth, stats, true)), "0 (culling off)");
}

TEST(MeshInspector, TriangleLevelFromEdges) {
    // side 5 (n = 2, levels 0..4): the level-0 triangle (0,0)-(4,0)-(0,4).
    EXPECT_EQ(render::triangleLevel(0, 4, 20, 5), 0);
    // Level 2: legs of 2 samples; level 4: legs of 1 sample.
    EXPECT_EQ(render::triangleLevel(0, 2, 10, 5), 2);
    EXPECT_EQ(render::triangleLevel(0, 1, 5, 5), 4);
    // Level 1: legs of length 2 sqrt 2 (centre (2,2) to corners).
    EXPECT_EQ(render::triangleLevel(0, 12, 4, 5), 1);
    EXPECT_EQ(render::triangleLevel(0, 3, 20, 5), -1);  // not an SBT triangle
}

TEST(DebugOverlayMaths, MedianAndP95) {
    auto [m, p] = render::medianAndP95({5, 1, 4, 2, 3});
    EXPECT_EQ(m, 3.0f);
    EXPECT_EQ(p, 5.0f);
    std::vector<float> many(100);
    for (int k = 0; k < 100; ++k) many[size_t(k)] = float(k + 1);
    auto [m2, p2] = render::medianAndP95(many);
    EXPECT_EQ(m2, 50.0f);
    EXPECT_EQ(p2, 95.0f);
}

}  // namespace
