// sierra-render: renders terrain frames off-screen to PNG files.
// With no arguments it renders the built-in default scene (a generated fractal
// terrain) to out/frame.png and its debug snapshot to out/debug.png.

#include <sierra/core/Error.h>
#include <sierra/core/Log.h>
#include <sierra/core/Timer.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/render/Capture.h>
#include <sierra/render/DebugOverlay.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/Scene.h>
#include <sierra/render/TerrainRenderer.h>

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

using namespace sierra;

namespace {

struct Options {
    render::TerrainSource source;
    std::string size = "1280x720";
    std::vector<float> cameraPosition, cameraTarget;
    float fov = 45.0f;
    float seaLevel = std::numeric_limits<float>::quiet_NaN();
    std::string out = "out/frame.png";
    std::string debugOut = "out/debug.png";
    bool noDebug = false;
    int frames = 1;
    bool orbit = false;
    std::string lod = "sbt";
    float tau = 1.0f;
    bool wireframe = false;
    int msaa = 4;
    int threads = 0;
    bool listDevices = false;
};

glm::vec3 toVec3(const std::vector<float>& v) { return {v[0], v[1], v[2]}; }

int run(const Options& o) {
    if (o.listDevices) {
        auto devices = gpu::EglContext::listDevices();
        if (devices.empty()) std::printf("no EGL devices enumerated (EGL_EXT_device_enumeration missing)\n");
        for (const auto& d : devices)
            std::printf("%d: %s%s\n   %s\n", d.index, d.software ? "software" : "hardware",
                        d.drmFile.empty() ? "" : (" " + d.drmFile).c_str(), d.extensions.c_str());
        return 0;
    }
    auto [width, height] = render::parseFrameSize(o.size);
    render::Lod lod = render::parseLod(o.lod);
    if (!(o.tau > 0.0f)) throw Error(msg("--tau must be positive pixels, got ", o.tau));

    Stopwatch total;
    std::string description;
    terrain::Heightfield field = render::loadTerrain(o.source, &description);
    log::info("terrain: ", description);

    gpu::EglContext context = gpu::EglContext::create({.width = width, .height = height});
    log::info("OpenGL ", context.version(), " on ", context.renderer(), " (", context.platform(), ")");
    render::TerrainRenderer terrain = render::TerrainRenderer::create(
        {.field = &field, .seaLevel = o.seaLevel, .threads = o.threads});
    render::FrameTarget target = render::FrameTarget::create({.width = width, .height = height, .samples = o.msaa});

    std::vector<render::Camera> cameras;
    if (o.orbit || o.frames > 1) {
        cameras = render::orbitPath(terrain.bounds(), o.frames);
    } else {
        cameras.push_back(render::defaultCamera(terrain.bounds()));
    }
    for (render::Camera& c : cameras) {
        if (!o.cameraPosition.empty()) c.position = toVec3(o.cameraPosition);
        if (!o.cameraTarget.empty()) c.target = toVec3(o.cameraTarget);
        c.fovYDegrees = o.fov;
    }
    if (cameras.front().position == cameras.front().target)
        throw Error("--camera-pos and --camera-target must differ");

    render::DrawOptions draw{.lod = lod, .tau = o.tau, .wireframe = o.wireframe, .threads = o.threads};
    bool sequence = cameras.size() > 1;
    std::vector<float> frameMs;
    render::DrawStats last;
    // Sequences read back through pixel-buffer objects: frame k is copied while
    // frame k + 1 is refined and drawn, and written once it arrives.
    gpu::PixelReader reader(width, height);
    gpu::Image image;
    int written = 0;
    auto writeNext = [&](const gpu::Image& frame) {
        std::string path = sequence ? render::sequencePath(o.out, written) : o.out;
        render::writePng(path, frame);
        if (sequence)
            log::info("frame ", written + 1, "/", cameras.size(), ": ", frameMs[size_t(written)], " ms -> ", path);
        ++written;
    };
    for (size_t k = 0; k < cameras.size(); ++k) {
        Stopwatch frame;
        target.begin(terrain.skyColour());
        last = terrain.draw(cameras[k], width, height, draw);
        target.resolve();
        bool ready = reader.start(image);
        terrain.collectGpuTime(last);
        frameMs.push_back(float(frame.ms()));
        if (ready) writeNext(image);
    }
    if (reader.finish(image)) writeNext(image);
    log::info(lodName(lod), " frame: ", last.triangles, " triangles, ", last.indices, " indices (",
              last.indicesPerTriangle(), " per triangle), refine ", last.refineMs, " ms, upload ", last.uploadMs,
              " ms, GPU draw ", last.drawMs, " ms, frame ", frameMs.back(), " ms");
    log::info("wrote ", sequence ? render::sequencePath(o.out, 0) + " .. " : "",
              sequence ? render::sequencePath(o.out, int(cameras.size()) - 1) : o.out);

    if (!o.noDebug) {
        render::DebugOverlay overlay;
        render::DebugPanel panel;
        panel.title = "Sierra debug";
        const render::Camera& cam = cameras.back();
        panel.rows = {
            {"renderer", context.renderer()},
            {"terrain", msg(terrain.side(), "^2 samples")},
            {"level of detail", msg(lodName(lod), lod == render::Lod::Sbt ? msg(", tau ", o.tau, " px") : "")},
            {"triangles", msg(last.triangles)},
            {"indices / triangle", msg(last.indicesPerTriangle())},
            {"error pass", msg(terrain.errorPassMs(), " ms")},
            {"refine + strip", msg(last.refineMs, " ms")},
            {"upload", msg(last.uploadMs, " ms, ", last.bytesUploaded, " bytes")},
            {"draw (GL timer)", msg(last.drawMs, " ms")},
            {"frame", msg(frameMs.back(), " ms")},
            {"camera", msg(cam.position.x, ", ", cam.position.y, ", ", cam.position.z)},
        };
        panel.frameTimesMs = frameMs;
        // The pbuffer still holds the last frame (its read-back was queued
        // before): the panel is drawn over it, with no second render.
        overlay.draw(panel, width, height);
        render::writePng(o.debugOut, gpu::readFramebuffer(width, height));
        log::info("wrote debug snapshot ", o.debugOut);
    }
    log::info("done in ", total.ms(), " ms");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"sierra-render: renders terrain off-screen (EGL) to PNG.\n"
                 "With no arguments: a generated 1025x1025 fractal terrain to out/frame.png and an ImGui\n"
                 "debug snapshot to out/debug.png."};
    app.option_defaults()->always_capture_default();
    auto* heightmap = app.add_option("--heightmap", o.source.heightmap,
                                     "Heightmap to load: .png (8/16-bit), .pgm, .r16/.r32 (with --raw-size), .hgt, .npy")
                          ->check(CLI::ExistingFile);
    app.add_option("--generate", o.source.generateSize, "Generate a diamond-square terrain of SIZE = 2^n+1 samples")
        ->excludes(heightmap);
    app.add_option("--seed", o.source.seed, "Seed of the generated terrain");
    app.add_option("--roughness", o.source.roughness, "Amplitude factor of the generator's offsets (> 0)");
    std::string rawSize;
    app.add_option("--raw-size", rawSize, "WIDTHxHEIGHT of a .r16/.r32 heightmap");
    app.add_option("--spacing", o.source.spacing, "World units between samples (0 = automatic)");
    app.add_option("--vertical-scale", o.source.verticalScale,
                   "Stored height to world height (0 = automatic: relief 20% of the extent; SRTM: 1)");
    app.add_option("--size", o.size, "Frame size WIDTHxHEIGHT");
    app.add_option("--camera-pos", o.cameraPosition, "Camera position X Y Z (world units)")->expected(3);
    app.add_option("--camera-target", o.cameraTarget, "Point the camera looks at, X Y Z")->expected(3);
    app.add_option("--fov", o.fov, "Vertical field of view in degrees")->check(CLI::Range(1.0f, 170.0f));
    app.add_option("--sea-level", o.seaLevel, "Sea level in stored height units (default: 30% of the samples below it)");
    app.add_option("--out", o.out, "Output PNG (sequences: NAME_0000.png, ...)");
    app.add_option("--debug-out", o.debugOut, "ImGui debug snapshot PNG");
    app.add_flag("--no-debug", o.noDebug, "Do not write the debug snapshot");
    app.add_option("--frames", o.frames, "Number of frames (more than 1 renders an orbit)")->check(CLI::Range(1, 100000));
    app.add_flag("--orbit", o.orbit, "Move the camera around the terrain over the frames");
    app.add_option("--lod", o.lod, "Level of detail: sbt (view-dependent) or full (every grid cell)")
        ->check(CLI::IsMember({"sbt", "full"}));
    app.add_option("--tau", o.tau, "SBT screen-space error threshold in pixels");
    app.add_flag("--wireframe", o.wireframe, "Overlay the triangulation");
    app.add_option("--msaa", o.msaa, "Multisample count (0 = off)")->check(CLI::IsMember({0, 2, 4, 8}));
    app.add_option("--threads", o.threads, "CPU threads (0 = all cores)")->check(CLI::Range(0, 256));
    app.add_flag("--list-devices", o.listDevices, "List EGL devices and exit");
    try {
        app.parse(argc, argv);
        if (!rawSize.empty()) {
            auto [w, h] = render::parseFrameSize(rawSize, "--raw-size");
            o.source.rawWidth = w;
            o.source.rawHeight = h;
        }
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const Error& e) {
        std::fprintf(stderr, "sierra-render: %s\n", e.what());
        return 2;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "sierra-render: error: %s\n", e.what());
        return 1;
    }
}
