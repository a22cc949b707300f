// sierra-render: renders terrain frames off-screen to PNG files or a video.
// With no arguments it renders the built-in default scene (a generated fractal
// terrain) to out/frame.png and its debug snapshot to out/debug.png. Every
// option is also a key of the scene file (--config, --print-config).

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Log.h>
#include <sierra/core/Npy.h>
#include <sierra/core/Progress.h>
#include <sierra/core/Timer.h>
#include <sierra/facade/Dataset.h>
#include <sierra/facade/DebugSnapshot.h>
#include <sierra/facade/SceneRenderer.h>

#include "Tiled.h"
#include <sierra/facade/SceneView.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/render/Capture.h>
#include <sierra/render/FrameQueue.h>
#include <sierra/render/Video.h>
#include <sierra/scene/Options.h>

#include "AppMain.h"

#include <CLI/CLI.hpp>

#include <signal.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>

using namespace sierra;

namespace {

// One line per EGL device: index, kind, vendor, renderer, CUDA ordinal (the
// physical one; cuda:N counts after CUDA_VISIBLE_DEVICES) and DRM node.
void listDevices() {
    auto devices = gpu::EglContext::listDevices(true);
    if (devices.empty())
        std::printf("no EGL devices enumerated (EGL_EXT_device_enumeration missing)\n");
    for (const auto& d : devices) {
        auto orNone = [](const std::string& s) { return s.empty() ? std::string("-") : s; };
        std::printf("%d: %s, vendor %s, renderer %s, CUDA device %s, DRM %s%s\n", d.index,
                    d.software ? "software" : "hardware", orNone(d.vendor).c_str(),
                    orNone(d.renderer).c_str(),
                    d.cudaDevice >= 0 ? std::to_string(d.cudaDevice).c_str() : "-",
                    orNone(d.drmFile).c_str(), d.uuid.empty() ? "" : (", " + d.uuid).c_str());
    }
}

std::string describe(const glm::vec3& v) {
    return msg("(", v.x, ", ", v.y, ", ", v.z, ")");
}

// The video of a scene whose output is one: a slice (--frames A:B) writes the
// segment NAME_AAAA.EXT, and the segments in name order join into the whole.
render::VideoDesc videoDesc(const scene::Scene& s, bool nvidia) {
    const scene::OutputDesc& o = s.output;
    return {.path = s.path.range ? render::sequencePath(o.frame, s.path.range->first) : o.frame,
            .width = o.width,
            .height = o.height,
            .fps = o.fps,
            .codec = o.videoCodec,
            .crf = o.crf,
            .bitrate = o.bitrate,
            .preset = o.videoPreset,
            .preferNvenc = nvidia};
}

// The signal that asked the run to stop (SIGINT, SIGTERM), 0 for none. The
// frame loop stops submitting, the frames in flight are written, and the
// program exits 128 + the signal. A second signal kills at once (the
// handler is reset), as a user pressing Ctrl-C twice expects.
volatile std::sig_atomic_t stopSignal = 0;

void requestStop(int signal) {
    stopSignal = signal;
}

void catchStopSignals() {
    struct sigaction action {};
    action.sa_handler = requestStop;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART | SA_RESETHAND;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

// "1:02:03" / "2:03" for a duration in seconds.
std::string clockTime(double seconds) {
    const int64_t total = std::isfinite(seconds) ? int64_t(std::max(seconds, 0.0) + 0.5) : 0;
    const int64_t h = total / 3600, m = total / 60 % 60, sec = total % 60;
    char text[48];
    if (h > 0)
        std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", (long long)h, (long long)m,
                      (long long)sec);
    else
        std::snprintf(text, sizeof text, "%lld:%02lld", (long long)m, (long long)sec);
    return text;
}

// The progress of a sequence on stderr: frames rendered, frames per second
// and the time left, at most kPerSecond times a second (and at the end).
class SequenceProgress {
  public:
    static constexpr double kPerSecond = 4.0;
    explicit SequenceProgress(int64_t total)
        : total_(total),
          progress_(log::level() <= log::Level::Info && total > 1
                        ? std::make_optional<Progress>("frames", total)
                        : std::nullopt) {}
    void update(int64_t done) {
        if (!progress_) return;
        const double seconds = clock_.ms() / 1000.0;
        if (done < total_ && seconds - shown_ < 1.0 / kPerSecond) return;
        shown_ = seconds;
        const double rate = seconds > 0.0 ? double(done) / seconds : 0.0;
        progress_->update(done,
                          msg(fixed(rate, 1), " frames/s, ",
                              rate > 0.0 ? clockTime(double(total_ - done) / rate) : "?", " left"));
    }
    void finish() {
        if (progress_) progress_->finish();
    }

  private:
    int64_t total_;
    std::optional<Progress> progress_;
    Stopwatch clock_;
    double shown_ = -1.0;
};

// The last kKept frames' statistics for the debug snapshot, in amortised
// O(1) per frame: a sequence of any length keeps bounded memory.
template <typename T>
void keepRecent(std::vector<T>& values, const T& value) {
    constexpr size_t kKept = 1000;
    values.push_back(value);
    if (values.size() >= 2 * kKept) values.erase(values.begin(), values.end() - long(kKept));
}

// The file of frame k for `base`: base itself for a single frame, its
// sequence name (base_0007.png) for a sequence.
std::string sequenceFile(const scene::Scene& s, const std::string& base, int k) {
    return s.path.frames > 1 ? render::sequencePath(base, k) : base;
}

// Where the frames go, in the order they are read back: to the video
// encoder on this thread, or to the encoder queue's threads as image files.
class FrameWriter {
  public:
    FrameWriter(const scene::Scene& s, render::VideoEncoder* encoder, int first, int last)
        : s_(s),
          encoder_(encoder),
          first_(first),
          last_(last),
          next_(first),
          encoding_(facade::frameEncoding(s.output)),
          queue_({.capacity = s.output.maxQueuedFrames > 0
                                  ? s.output.maxQueuedFrames
                                  : render::defaultQueuedFrames(size_t(s.output.width) *
                                                                size_t(s.output.height) * 4),
                  .threads = render::defaultEncoderThreads()}) {
        if (s.path.frames > 1 && !encoder)
            log::info("frames encoded on ", queue_.threads(), " thread(s), at most ",
                      queue_.capacity(), " queued");
    }
    // Takes the next frame (`image` is left empty).
    void write(gpu::Image& image) {
        if (encoder_) {  // a video takes its frames in order, on this thread
            encoder_->write(image);
        } else {
            std::string path = sequenceFile(s_, s_.output.frame, next_);
            if (s_.path.frames > 1)
                log::debug("frame ", next_, " (", next_ - first_ + 1, "/", last_ - first_ + 1,
                           ") queued -> ", path);
            queue_.submit(next_, std::move(image),
                          [path, encoding = encoding_](const gpu::Image& frame) {
                              render::writeImage(path, frame, encoding);
                          });
        }
        image = {};
        ++next_;
    }
    // Waits for the queued files.
    void finish() { queue_.finish(); }

  private:
    const scene::Scene& s_;
    render::VideoEncoder* encoder_;
    int first_, last_, next_;
    render::ImageEncoding encoding_;
    render::FrameQueue queue_;
};

int run(const scene::Scene& s) {
    const int width = s.output.width, height = s.output.height;
    const int frameCount = s.path.frames;
    const int first = s.path.range ? s.path.range->first : 0;
    const int last = s.path.range ? s.path.range->last : frameCount - 1;
    auto framePath = [&](const std::string& base, int k) { return sequenceFile(s, base, k); };
    const bool video = scene::isVideoOutput(s.output.frame);
    const std::string videoPath = video ? videoDesc(s, false).path : std::string();

    // Every output location is checked before any work, so a bad path fails
    // at once rather than after the frames.
    for (const std::string* path : {video ? &videoPath : &s.output.frame, &s.output.debug})
        if (!path->empty()) ensureWritableLocation(*path);
    // Depth, normals, zone ids, mask and cameras (docs/dataset.md).
    const facade::DatasetWriter dataset(s, frameCount > 1);
    dataset.checkLocations();

    Stopwatch total;
    // The context comes first: its texture limit bounds the grid the loader takes.
    auto context = std::make_shared<gpu::EglContext>(
        gpu::EglContext::create({.width = width, .height = height}));
    log::info("OpenGL ", context->version(), " on ", context->renderer(), " (", context->platform(),
              ")");
    // Opened before the terrain, so a codec or size it refuses fails at once.
    std::optional<render::VideoEncoder> encoder;
    if (video) {
        const bool nvidia = context->vendor().find("NVIDIA") != std::string::npos ||
                            context->renderer().find("NVIDIA") != std::string::npos;
        encoder.emplace(videoDesc(s, nvidia));
        log::info("video ", videoPath, ": ", encoder->encoderName(), ", ", s.output.fps, " fps");
    }
    // Before the terrain's GPU data: a sun time without a place fails at once.
    facade::SceneRenderer r = facade::SceneRenderer::create(
        s, context, nullptr,
        {.report = [](const std::string& line) { log::info(line); }, .describeSun = true});

    std::vector<float> frameMs;
    // Sequences read back through pixel-buffer objects (SceneRenderer::submitFrame):
    // each frame is handed to the encoder threads once it arrives; the render
    // thread waits only when the queue is full.
    gpu::Image image;
    FrameWriter writer(s, encoder ? &*encoder : nullptr, first, last);
    // Debug snapshots: the frame re-rendered narrower with the UI in a column
    // beside it, or the UI alone on a plain background.
    std::vector<render::DrawStats> history;
    facade::SnapshotRenderer snapshots(r);
    auto snapshot = [&](int k, const std::string& path, bool uiOnly = false) {
        render::writePng(path, snapshots.render(k, uiOnly, history, frameMs));
        log::info("wrote debug snapshot ", path);
    };
    catchStopSignals();
    SequenceProgress progress(int64_t(last) - first + 1);
    int rendered = first - 1;
    for (int k = first; k <= last && stopSignal == 0; ++k) {
        Stopwatch frame;
        const bool ready = r.submitFrame(k, image);
        const render::DrawStats& stats = r.lastStats();
        if (stats.triangles == 0) {
            const render::Camera camera = r.camera(k);
            log::warn("frame ", k, ": no terrain triangle is in view of the camera at ",
                      describe(camera.position), " looking at ", describe(camera.target),
                      " (the frame is sky only)");
        }
        keepRecent(frameMs, float(frame.ms()));
        keepRecent(history, stats);
        if (ready) writer.write(image);
        if (!s.output.debug.empty() && s.output.snapshotEvery > 0 &&
            (k - first) % s.output.snapshotEvery == 0)
            snapshot(k, framePath(s.output.debug, k));
        if (dataset.any()) r.writeDataset(k);
        rendered = k;
        progress.update(int64_t(k) - first + 1);
    }
    // The frames in flight (the last read back, those queued) are written
    // whether the sequence ended or was stopped.
    if (r.finishFrames(image)) writer.write(image);
    writer.finish();
    if (dataset.any()) r.finishDataset();
    progress.finish();
    // A stopped video is finished too: it plays with the frames so far.
    if (encoder && stopSignal != 0) encoder->finish();
    if (stopSignal != 0) {
        const std::string done = rendered >= first ? msg("frames ", first, "..", rendered, " of ",
                                                         first, "..", last, " written")
                                                   : std::string("no frame written");
        std::fprintf(stderr, "sierra-render: stopped by %s: %s\n",
                     stopSignal == SIGINT ? "SIGINT" : "SIGTERM", done.c_str());
        return 128 + int(stopSignal);
    }
    const render::DrawStats& stats = r.lastStats();
    log::info(render::lodName(r.drawOptions().lod), " frame: ", stats.triangles, " triangles, ",
              stats.indices, " indices (", fixed(stats.indicesPerTriangle()),
              " per triangle), refine + strip ", fixed(stats.refineMs), " ms, upload ",
              fixed(stats.uploadMs), " ms, draw (GL timer) ", fixed(stats.drawMs), " ms, frame ",
              fixed(frameMs.back(), 1), " ms");
    if (encoder) {
        encoder->finish();
        log::info("wrote ", videoPath, ": frames ", first, "..", last, " (",
                  encoder->framesWritten(), ") at ", s.output.fps, " fps, ",
                  encoder->encoderName());
    } else {
        log::info("wrote ", framePath(s.output.frame, first),
                  last > first ? " .. " + framePath(s.output.frame, last) : std::string());
    }

    if (!s.output.debug.empty() && s.output.snapshotEvery == 0) snapshot(last, s.output.debug);
    if (!s.output.snapshotOnly.empty()) snapshot(last, s.output.snapshotOnly, true);
    log::info("done in ", fixed(total.ms(), 1), " ms");
    return 0;
}

}  // namespace

std::string apps::sequenceFrame(const scene::Scene& s, int k) {
    return sequenceFile(s, s.output.frame, k);
}

int main(int argc, char** argv) {
    scene::Scene scene;
    CLI::App app{
        "Renders terrain off-screen (EGL) to PNG, JPEG or a video (.mp4, .mov, .mkv, .webm, "
        ".gif).\n"
        "With no arguments: a generated 1025x1025 fractal terrain to out/frame.png and an ImGui\n"
        "debug snapshot to out/debug.png. Every option is also a key of a scene file (--config).",
        "sierra-render"};
    scene::SceneOptions options(app, scene, scene::kAllOptions);
    bool devices = false;
    app.add_flag("--list-devices", devices, "List the EGL devices and exit");
    apps::TiledRenderOptions tiled;
    double budgetMiB = double(tiled.memoryBudget >> 20);
    app.add_option("--memory-budget", budgetMiB,
                   "A tiled terrain (.sierra): MiB for its tile caches, 3/4 CPU, 1/4 GPU textures")
        ->type_name("MIB")
        ->check(CLI::Range(16.0, 1048576.0))
        ->capture_default_str()
        ->group("Tiled terrain");
    app.add_option("--tile-wait", tiled.tileWaitSeconds,
                   "A tiled terrain's single frame: seconds to wait at most for its tiles (a "
                   "sequence never waits)")
        ->type_name("S")
        ->check(CLI::Range(0.0, 3600.0))
        ->capture_default_str()
        ->group("Tiled terrain");
    return apps::runMain(
        app, argc, argv,
        [&] {
            options.apply();
            // A codec, size or rate the encoder refuses is a command-line error.
            if (scene::isVideoOutput(scene.output.frame))
                render::checkVideo(videoDesc(scene, false));
        },
        [&] {
            if (options.printConfigRequested()) return 0;
            if (devices) {
                listDevices();
                return 0;
            }
            if (apps::isTiledTerrain(scene)) {
                tiled.memoryBudget = uint64_t(budgetMiB * 1048576.0);
                return apps::runTiled(scene, tiled);
            }
            return run(scene);
        });
}
