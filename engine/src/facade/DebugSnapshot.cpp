#include <sierra/facade/DebugSnapshot.h>

#include <sierra/core/Parallel.h>
#include <sierra/core/Progress.h>
#include <sierra/gpu/Gl.h>
#include <sierra/gpu/StreamRing.h>
#include <sierra/render/MeshInspector.h>
#include <sierra/render/TerrainGpu.h>
#include <sierra/scene/Terrain.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace sierra::facade {

using namespace sierra::render;
namespace {

// A world position in the panel's narrow value column: one decimal below 100,
// none from there (a coordinate of 1703.1 reads as 1703), so three of them
// fit one line.
std::string vec(const glm::vec3& v) {
    auto c = [](float x) { return fixed(x, std::fabs(x) < 100.0f ? 1 : 0); };
    return msg("(", c(v.x), ", ", c(v.y), ", ", c(v.z), ")");
}

std::string bytes(double b) {
    if (b >= 1024.0 * 1024.0) return msg(fixed(b / (1024.0 * 1024.0), 1), " MiB");
    if (b >= 1024.0) return msg(fixed(b / 1024.0, 1), " KiB");
    return msg(fixed(b, 0), " B");
}

DebugSection sourceSection(const SnapshotFacts& f) {
    const scene::Scene& s = *f.scene;
    const terrain::Heightfield& field = *f.field;
    TerrainGpu& gpu = f.renderer->terrain();

    // Source: the real size is the valid samples' box (padding is added to the
    // right and at the bottom); no-data = invalid samples inside it.
    int realW = field.width(), realH = field.height();
    int64_t noData = 0;
    if (field.hasMask()) {
        realW = realH = 0;
        for (int j = 0; j < field.height(); ++j)
            for (int i = 0; i < field.width(); ++i)
                if (field.valid(i, j))
                    realW = std::max(realW, i + 1), realH = std::max(realH, j + 1);
        for (int j = 0; j < realH; ++j)
            for (int i = 0; i < realW; ++i) noData += field.valid(i, j) ? 0 : 1;
    }
    const glm::vec2 range = gpu.worldRange();
    DebugSection source{.title = "Source"};
    source.rows = {
        {"file", s.terrain.heightmap.empty()
                     ? msg("generated ", s.terrain.generateSize, "^2, seed ", s.terrain.seed,
                           ", roughness ", s.terrain.roughness)
                     : s.terrain.heightmap},
        {"real size", msg(realW, " x ", realH, " samples")},
        {"padded size", msg(field.width(), " x ", field.height(), " samples")},
        {"spacing", msg(fixed(field.spacingX(), 2), " x ", fixed(field.spacingZ(), 2),
                        field.metres() ? " m" : "")},
        {"vertical scale", fixed(field.verticalScale(), 4)},
        {"height range", msg(fixed(range.x, 1), " .. ", fixed(range.y, 1))},
        {"sea level", gpu.hasWater() ? fixed(gpu.worldSeaLevel(), 1) : "no water"},
        {"no-data samples", msg(noData)},
    };
    // The units once, rather than in every value (each then took two lines,
    // and the panel's last rows fell off the frame).
    source.note = "in world units (vertical scale: per stored unit)";
    return source;
}

DebugSection rendererSection(const SnapshotFacts& f) {
    const scene::Scene& s = *f.scene;
    DebugSection renderer{.title = "Renderer"};
    // The default count (0) refines on one thread or on all, whichever it
    // measures faster (sbt::ThreadChoice).
    const std::string threads = f.draw.threads > 0
                                    ? msg(f.draw.threads, " (refinement)")
                                    : msg("1 or ", defaultThreadCount(), " (measured)");
    renderer.rows = {
        {"GL renderer", f.glRenderer},
        {"GL version", f.glVersion},
        {"EGL", f.eglPlatform},
        {"MSAA", s.output.msaa ? msg(s.output.msaa, " samples") : "off"},
        {"threads", threads},
        {"frame", msg(f.frameWidth, " x ", f.height, " pixels")},
    };
    return renderer;
}

DebugSection cameraSection(const SnapshotFacts& f) {
    DebugSection camera{.title = "Camera", .column = 1};
    camera.rows = {
        {"position", vec(f.camera.position)},
        {"target", vec(f.camera.target)},
        {"fov", msg(fixed(f.camera.fovYDegrees, 1), " deg")},
        {"level of detail",
         msg(lodName(f.draw.lod), f.draw.lod == Lod::Sbt
                                      ? msg(", geomorph ", f.draw.geomorph ? "on" : "off",
                                            ", culling ", f.draw.cull ? "on" : "off")
                                      : "")},
    };
    return camera;
}

DebugSection timesSection(const SnapshotFacts& f, bool deterministic) {
    TerrainGpu& gpu = f.renderer->terrain();
    DebugSection times{.title = "Frame time", .column = 1};
    StageSeries refine{.name = "refine + strip"}, upload{.name = "upload"},
        draw{.name = "draw (GL timer)"}, frame{.name = "frame (wall clock)"};
    for (const DrawStats& st : f.frames) {
        refine.values.push_back(float(st.refineMs));
        upload.values.push_back(float(st.uploadMs));
        draw.values.push_back(float(st.drawMs));
    }
    frame.values = f.frameMs;
    times.series = {refine, upload, draw, frame};
    times.rows = {{"SBT build",
                   deterministic ? std::string("-- ms") : msg(fixed(gpu.sbtBuildMs(), 1), " ms")},
                  {"read-back", "in the frame time"}};
    return times;
}

DebugSection meshSection(const SnapshotFacts& f) {
    TerrainGpu& gpu = f.renderer->terrain();
    const DrawStats& last = f.frames.back();
    DebugSection mesh{.title = "Mesh", .column = 1};
    if (f.draw.lod == Lod::Sbt) {
        MeshInspection m = inspectMesh(gpu, f.camera, f.frameWidth, f.height, f.draw.tau,
                                       f.draw.cull, f.draw.threads, f.draw.geomorph);
        mesh.rows = {
            {"triangles", msg(m.triangles)},
            {"distinct vertices", msg(m.distinctVertices)},
            {"indices/triangle",
             fixed(m.triangles ? double(m.indices) / double(m.triangles) : 0.0, 3)},
            {"bytes uploaded", msg(m.indices * 4, " (", bytes(double(m.indices) * 4.0), ")")},
            {"tau, lambda", msg(fixed(m.tau, 2), " px, ", fixed(m.lambda, 1), " px")},
            {"max screen error", msg(fixed(m.maxProjectedErrorPx, 3), " px")},
            {"culled subtrees",
             f.draw.cull ? msg(m.culledSubtrees, " (frustum)") : std::string("0 (culling off)")},
        };
        Histogram h{.name = "leaves per level", .binLabel = "level"};
        h.counts.assign(m.levelCounts.begin(), m.levelCounts.end());
        mesh.histograms.push_back(std::move(h));
    } else {
        mesh.rows = {{"triangles", msg(last.triangles)},
                     {"indices/triangle", fixed(last.indicesPerTriangle(), 3)},
                     {"level of detail", "full grid (no SBT)"}};
    }
    return mesh;
}

DebugSection memorySection(const SnapshotFacts& f) {
    const terrain::Heightfield& field = *f.field;
    TerrainGpu& gpu = f.renderer->terrain();
    const DrawStats& last = f.frames.back();
    // Memory from the structures' sizes (what each holds per sample).
    const double samples = double(field.width()) * double(field.height());
    DebugSection memory{.title = "Memory"};
    memory.rows = {
        {"CPU heightfield", bytes(samples * (4.0 + (field.hasMask() ? 1.0 : 0.0)))},
        {"CPU drawn surface", bytes(samples * 4.0)},
        {"CPU errors, radii", bytes(samples * 8.0)},
        {"CPU SBT keys", bytes(double(gpu.refinerKeyBytes()))},
        {"CPU strip", bytes(double(last.indices) * 4.0)},
        {"GPU data RGBA32F", bytes(samples * 16.0)},
        {"GPU heights R32F", bytes(samples * 4.0)},
        {"GPU index ring", msg(gpu::StreamRing::kRegions, " x >= ", bytes(4.0 * 1024 * 1024))},
        {"GPU colour ramp", bytes(1024.0 * 4.0)},
    };
    memory.note = "from the layouts; the ring grows to the largest frame";
    return memory;
}

// The colour key of a debug colouring (style.colour_by error or level).
void addColourKey(DebugSection& style, const SnapshotFacts& f) {
    const scene::Scene& s = *f.scene;
    const terrain::Heightfield& field = *f.field;
    if (s.style.colourBy == "error") {
        // The heat map of shaders/debug_colour_geom.glsl.
        const double tau = f.draw.tau;
        style.swatches = {{{0.1f, 0.2f, 0.9f}, "0 px"},
                          {{0.1f, 0.75f, 0.2f}, msg(fixed(tau / 2, 2), " px (tau / 2)")},
                          {{0.95f, 0.9f, 0.1f}, msg(fixed(tau, 2), " px (tau)")},
                          {{0.9f, 0.1f, 0.05f}, msg(">= ", fixed(2 * tau, 2), " px (2 tau)")}};
        style.note = "colour: screen-space error of each triangle's split vertex";
    } else if (s.style.colourBy == "level") {
        int levels = 0;
        while ((1 << (levels / 2)) < field.width() - 1 || levels % 2) ++levels;
        for (int l = 0; l <= levels; l += std::max(1, levels / 5)) {
            // hue(0.8 * l / levels) as in the shader
            const float h = 0.8f * float(l) / float(std::max(levels, 1));
            std::array<float, 3> rgb;
            const float offsets[3] = {0.0f, 2.0f / 3.0f, 1.0f / 3.0f};
            for (int c = 0; c < 3; ++c) {
                float x = h + offsets[c];
                x -= std::floor(x);
                rgb[size_t(c)] = std::clamp(std::abs(x * 6.0f - 3.0f) - 1.0f, 0.0f, 1.0f);
            }
            style.swatches.push_back({rgb, msg("SBT level ", l)});
        }
        style.note = "colour: each triangle's SBT level";
    }
}

// The overlay layers, and for lines and hatches the curvature drawn.
void addOverlayParams(DebugSection& style, const SnapshotFacts& f) {
    // With "scale": "auto", the scale addOverlayPasses chose.
    const analysis::StyleParams& overlay = f.scene->style.overlay;
    std::string layers;
    for (auto [on, name] :
         {std::pair{overlay.layers.lines, "lines"}, std::pair{overlay.layers.hatch, "hatch"},
          std::pair{overlay.layers.contours, "contours"}})
        if (on) layers += (layers.empty() ? "" : ", ") + std::string(name);
    style.params.push_back({.kind = StyleParam::Kind::Text,
                            .name = "overlays",
                            .text = layers.empty() ? "none" : layers});
    if (overlay.layers.lines || overlay.layers.hatch) {
        const analysis::CurvatureOptions& c = overlay.curvature;
        style.params.push_back({.kind = StyleParam::Kind::Text,
                                .name = "curvature",
                                .text = analysis::curvatureMethodName(c.method)});
        std::ostringstream scale;
        scale << std::setprecision(4) << f.overlays.scale << (overlay.autoScale ? " (auto)" : "");
        style.params.push_back({.kind = StyleParam::Kind::Text,
                                .name = "distance, scale",
                                .text = msg(c.distance, ", ", scale.str())});
    }
    if (overlay.layers.lines)
        style.params.push_back({.kind = StyleParam::Kind::Text,
                                .name = "lines traced",
                                .text = msg(f.overlays.lines)});
}

DebugSection styleSection(const SnapshotFacts& f) {
    const scene::Scene& s = *f.scene;
    const terrain::Heightfield& field = *f.field;
    DebugSection style{.title = "Style", .column = 1};
    style.params = {
        {.kind = StyleParam::Kind::Flag, .name = "wireframe", .flag = s.style.wireframe}};
    // The tree and snow lines are metres of the elevation ramp: heights without
    // units take the hypsometric ramp, and a colour table replaces both.
    if (!s.style.cpt.empty() || !scene::metricHeights(s.terrain, field)) {
        style.params.push_back({.kind = StyleParam::Kind::Text,
                                .name = "tree, snow line",
                                .text = s.style.cpt.empty() ? "n/a (no units)" : "n/a (table)"});
    } else {
        for (auto [name, value] :
             {std::pair{"tree line", s.style.treeLine}, std::pair{"snow line", s.style.snowLine}})
            style.params.push_back({.kind = StyleParam::Kind::Number,
                                    .name = name,
                                    .value = value,
                                    .min = 0.0f,
                                    .max = 9000.0f,
                                    .text = "m"});
    }
    style.params.push_back(
        {.kind = StyleParam::Kind::Text, .name = "colour table", .text = s.style.cpt});
    style.params.push_back({.kind = StyleParam::Kind::Number,
                            .name = "tau",
                            .value = f.draw.tau,
                            .min = 0.0f,
                            .max = 16.0f,
                            .text = "px"});
    addColourKey(style, f);
    style.params.push_back(
        {.kind = StyleParam::Kind::Text, .name = "colour by", .text = s.style.colourBy});
    addOverlayParams(style, f);
    return style;
}

}  // namespace

int debugColumnWidth(int width) {
    return std::min(std::clamp(int(std::lround(0.45 * width)), 480, 720), 2 * width / 3);
}

DebugPanel buildDebugPanel(const SnapshotFacts& f, bool deterministic) {
    SIERRA_CHECK(f.scene && f.field && f.renderer && !f.frames.empty(),
                 "debug panel: missing facts");
    DebugPanel panel;
    panel.title = "Sierra debug";
    panel.deterministic = deterministic;
    panel.sections = {
        sourceSection(f), rendererSection(f), cameraSection(f), timesSection(f, deterministic),
        meshSection(f),   memorySection(f),   styleSection(f)};
    return panel;
}

SnapshotRenderer::SnapshotRenderer(SceneRenderer& renderer) : renderer_(renderer) {}
SnapshotRenderer::~SnapshotRenderer() = default;

gpu::Image SnapshotRenderer::render(int k, bool uiOnly, const std::vector<DrawStats>& frames,
                                    const std::vector<float>& frameMs) {
    const scene::Scene& s = renderer_.scene();
    const int width = s.output.width, height = s.output.height;
    renderer_.context().makeCurrent();
    if (!overlay_) overlay_ = std::make_unique<DebugOverlay>();
    const int column = debugColumnWidth(width);
    const int frameWidth = snapshotFrameWidth(width, column);
    if (!cameras_) cameras_ = snapshotCameraPath(s, renderer_.terrain().bounds(), frameWidth);
    const Camera camera = cameras_->at(k);
    const DrawOptions draw = renderer_.drawOptions(k);
    SnapshotFacts facts{.scene = &s,
                        .field = &renderer_.field(),
                        .glRenderer = renderer_.context().renderer(),
                        .glVersion = renderer_.context().version(),
                        .eglPlatform = renderer_.context().platform(),
                        .renderer = &renderer_.terrain(),
                        .camera = camera,
                        .frameWidth = frameWidth,
                        .height = height,
                        .draw = draw,
                        .frames = frames,
                        .frameMs = frameMs,
                        .overlays = renderer_.overlays()};
    DebugPanel panel = buildDebugPanel(facts, s.output.snapshotDeterministic);
    panel.columnWidth = uiOnly ? column : width - frameWidth;
    const int shotWidth = uiOnly ? column : width;
    int shotHeight = std::max(height, overlay_->contentHeight(panel, shotWidth, height));
    // Measured again at that height: without the scroll bar the text wraps
    // less and the column is shorter.
    if (shotHeight > height)
        shotHeight = std::max(height, overlay_->contentHeight(panel, shotWidth, shotHeight));
    std::optional<FrameTarget> tall;
    if (shotHeight > height)
        tall.emplace(FrameTarget::create({.width = shotWidth,
                                          .height = shotHeight,
                                          // the UI alone draws no terrain
                                          .samples = uiOnly ? 0 : s.output.msaa,
                                          .offscreen = true}));
    const glm::vec4 uiBackground{0.2f, 0.2f, 0.22f, 1.0f};
    if (uiOnly) {
        if (tall) {
            tall->begin(uiBackground);
            tall->resolve();
        } else {
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glViewport(0, 0, column, height);
            glClearColor(uiBackground.r, uiBackground.g, uiBackground.b, uiBackground.a);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        }
    } else {
        FrameTarget& into = tall ? *tall : renderer_.target();
        into.begin(TerrainRenderer::clearColour(draw.lighting));
        if (tall) {  // below the frame: the UI's background (GL's rows run bottom-up)
            glEnable(GL_SCISSOR_TEST);
            glScissor(0, 0, frameWidth, shotHeight - height);
            glClearColor(uiBackground.r, uiBackground.g, uiBackground.b, uiBackground.a);
            glClear(GL_COLOR_BUFFER_BIT);
            glDisable(GL_SCISSOR_TEST);
        }
        glViewport(0, shotHeight - height, frameWidth, height);
        renderer_.terrain().draw(camera, frameWidth, height, draw);
        into.resolve();
    }
    overlay_->draw(panel, shotWidth, shotHeight);
    gpu::Image shot = gpu::readFramebuffer(shotWidth, shotHeight);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return shot;
}

}  // namespace sierra::facade
