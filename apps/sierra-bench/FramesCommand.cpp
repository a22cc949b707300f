// sierra-bench frames: renders a camera path and times every stage of every
// frame (refine + strip, upload, draw to completion, read-back), optionally
// against the full-grid renderer from the same cameras (frame time ratio, PSNR).

#include "Commands.h"

#include "AppMain.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Log.h>
#include <sierra/core/Parallel.h>
#include <sierra/core/Progress.h>
#include <sierra/core/Timer.h>
#include <sierra/facade/SceneRenderer.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/gpu/Gl.h>
#include <sierra/render/Capture.h>
#include <sierra/render/TerrainGpu.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/Options.h>

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <pthread.h>
#include <sched.h>

namespace sierra::apps {
namespace {

struct FramesOptions {
    scene::Scene scene;
    std::unique_ptr<scene::SceneOptions> registrar;
    bool compareFull = false;
    bool overlayCosts = false;   // also time each frame without overlays and with each alone
    bool lightingCosts = false;  // also time each frame without shadows and sky light
    bool surfaceCosts = false;   // also time each frame with the plain colouring, not the zones
    std::string json;
    std::string saveFrames;  // prefix for PNGs of every frame, empty = none
    int pinCpu = -1;         // the CPU the refining (main) thread is kept on, -1 = any
};

// Times of one frame, milliseconds.
struct FrameRecord {
    double refine = 0, upload = 0, draw = 0, gpu = 0, readBack = 0, total = 0;
    uint64_t triangles = 0, indices = 0, bytes = 0;
    int threads = 0;                 // threads the refinement ran on (0: none ran)
    int cpu = -1;                    // the CPU the refinement finished on (-1: none ran)
    double psnr = 0, differing = 0;  // against the full grid (compare mode)
    double fullTotal = 0;            // full-grid frame time (compare mode)
    double bare = 0;                 // frame time without overlay passes (--overlay-costs)
    double plain = 0;                // frame time without shadows and sky light (--lighting-costs)
    double plainSurface = 0;         // frame time with the plain colouring (--surface-costs)
    // CPU time of the whole process over the frame (every thread: the
    // driver's rasteriser threads too), ms, and that of the plain-coloured
    // frame (--surface-costs): on a shared machine the work a frame costs,
    // whatever share of the cores it was given.
    double processCpu = 0, plainSurfaceCpu = 0;
    std::vector<double> alone;  // frame time with only added pass k (--overlay-costs)
};

struct Stats {
    double median, p95, p99;
};

Stats stats(const std::vector<FrameRecord>& records, double FrameRecord::*field) {
    std::vector<double> v;
    for (const FrameRecord& r : records) v.push_back(r.*field);
    return {median(v), quantile(v, 0.95), quantile(v, 0.99)};
}

// CPU time used by this process so far, every thread, ms.
double processCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

// Draws one frame and reads it back; fills the timing fields of `record`.
gpu::Image timedFrame(facade::SceneRenderer& r, const render::Camera& camera,
                      const render::DrawOptions& draw, FrameRecord& record) {
    const double cpuStart = processCpuMs();
    Stopwatch frame;
    render::DrawStats s = r.drawFrame(camera, draw);
    Stopwatch finish;
    r.target().resolve();
    glFinish();  // llvmpipe rasterises at flush: the draw is done only here
    double drawWall = s.submitMs + finish.ms();
    Stopwatch read;
    gpu::Image image = gpu::readFramebuffer(r.target().width(), r.target().height());
    record.readBack = read.ms();
    record.total = frame.ms();
    record.processCpu = processCpuMs() - cpuStart;
    r.terrain().collectGpuTime(s);
    record.refine = s.refineMs;
    record.upload = s.uploadMs;
    record.draw = drawWall;
    record.gpu = s.drawMs;
    record.triangles = s.triangles;
    record.threads = s.refineThreads;
    record.cpu = s.refineCpu;
    record.indices = s.indices;
    record.bytes = s.bytesUploaded;
    return image;
}

// The CPUs this process may run on, as "0-1,4".
std::string allowedCpus(const cpu_set_t& set) {
    std::string text;
    for (int c = 0; c < CPU_SETSIZE; ++c) {
        if (!CPU_ISSET(c, &set)) continue;
        int last = c;
        while (last + 1 < CPU_SETSIZE && CPU_ISSET(last + 1, &set)) ++last;
        text += msg(text.empty() ? "" : ",", c, last > c ? msg("-", last) : std::string());
        c = last;
    }
    return text;
}

// --pin-cpu: the CPU must be one this process may run on.
void checkPinCpu(int cpu) {
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    if (sched_getaffinity(0, sizeof allowed, &allowed) != 0)
        throw Error(msg("--pin-cpu: cannot read this process's CPUs: ", std::strerror(errno)));
    if (cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &allowed))
        throw UsageError(
            msg("--pin-cpu ", cpu, ": this process may run only on CPU ", allowedCpus(allowed)));
}

// Keeps the calling thread, which refines every frame, on `cpu`. Called after
// the EGL context starts: the driver's own threads (llvmpipe rasterises on
// every core) keep every CPU.
void pinCallingThread(int cpu) {
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu, &one);
    if (int err = pthread_setaffinity_np(pthread_self(), sizeof one, &one); err != 0)
        throw Error(msg("--pin-cpu ", cpu, ": ", std::strerror(err)));
}

// The options checked before any work, so a bad one fails at once.
void checkFramesOptions(const FramesOptions& o) {
    if (o.pinCpu >= 0) checkPinCpu(o.pinCpu);
    if (!o.saveFrames.empty() && lowerExtension(o.saveFrames) != ".png")
        throw UsageError(
            msg("frames: --save-frames must name a .png file (frames are written as "
                "PNG, NAME_0000.png, ...), got '",
                o.saveFrames, "'"));
    for (const std::string* path : {&o.json, &o.saveFrames})
        if (!path->empty()) ensureWritableLocation(*path);
}

// The scene's renderer, its set-up said on stderr; the refining thread is
// pinned once the context (and the driver's threads) exist.
facade::SceneRenderer setUpFrames(const FramesOptions& o) {
    const scene::Scene& sc = o.scene;
    auto context = std::make_shared<gpu::EglContext>(
        gpu::EglContext::create({.width = sc.output.width, .height = sc.output.height}));
    std::fprintf(stderr, "renderer: %s (%s)\n", context->renderer().c_str(),
                 context->platform().c_str());
    if (o.pinCpu >= 0) pinCallingThread(o.pinCpu);
    return facade::SceneRenderer::create(
        sc, context, nullptr,
        {.report = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); },
         .describeSun = true});
}

// What the frame loop shares: the renderer, the frames timed (first..last of
// the scene's sequence) and the draws compared.
struct FramesRun {
    const FramesOptions& o;
    facade::SceneRenderer& r;
    int first = 0, last = 0;
    std::vector<std::string> passNames;  // the overlay passes (--overlay-costs)
    std::string fullFrames;              // --save-frames: NAME_full.png for the references

    int frames() const { return last - first + 1; }
};

// The cost options need something to compare: each refuses a scene without it.
void checkCostOptions(const FramesRun& run, const render::DrawOptions& draw) {
    const FramesOptions& o = run.o;
    if (o.overlayCosts && run.passNames.empty())
        throw UsageError(
            "--overlay-costs needs overlays to time: --style with lines, hatch or contours, or "
            "--preset");
    if (o.lightingCosts && !draw.lighting.shadows && !draw.lighting.skyLight)
        throw UsageError(
            "--lighting-costs compares frames with shadows and sky light against frames "
            "without: leave --shadows or --sky-light on");
    if (o.surfaceCosts && (o.scene.zones.map.empty() || !o.scene.style.overlay.layers.shaded))
        throw UsageError(
            "--surface-costs compares frames drawn with the zone surface against the plain "
            "colouring: give --zones (with a shaded style)");
}

render::DrawOptions fullGrid(render::DrawOptions draw) {
    draw.lod = render::Lod::Full;
    return draw;
}
render::DrawOptions plainLighting(render::DrawOptions draw) {
    draw.lighting.shadows = draw.lighting.skyLight = false;
    return draw;
}
render::DrawOptions plainSurface(render::DrawOptions draw) {
    draw.plainSurface = true;
    return draw;
}

// One warm-up frame: first-use costs (full-grid index build, shader
// compilation in the driver) are not frame costs.
void warmUp(FramesRun& run) {
    const FramesOptions& o = run.o;
    const render::Camera camera = run.r.camera(run.first);
    const render::DrawOptions draw = run.r.drawOptions(run.first);
    FrameRecord warm;
    timedFrame(run.r, camera, draw, warm);
    if (o.compareFull || draw.lod == render::Lod::Full)
        timedFrame(run.r, camera, fullGrid(draw), warm);
    if (o.lightingCosts) timedFrame(run.r, camera, plainLighting(draw), warm);
    if (o.surfaceCosts) timedFrame(run.r, camera, plainSurface(draw), warm);
}

// Frame k of the sequence and the draws compared with it from its camera;
// `detail` gets the progress line's figures.
FrameRecord measureFrame(FramesRun& run, int k, std::string& detail) {
    const FramesOptions& o = run.o;
    facade::SceneRenderer& r = run.r;
    const render::Camera camera = r.camera(k);
    const render::DrawOptions draw = r.drawOptions(k);
    FrameRecord rec;
    // --surface-costs: the same camera with the plain colouring, before the
    // frame on odd frames and after it on even ones, so whatever a camera's
    // first or second draw pays weighs on both alike.
    const bool plainSurfaceFirst = o.surfaceCosts && (k - run.first) % 2 == 1;
    FrameRecord plain;
    if (plainSurfaceFirst) timedFrame(r, camera, plainSurface(draw), plain);
    gpu::Image image = timedFrame(r, camera, draw, rec);
    if (o.surfaceCosts && !plainSurfaceFirst) timedFrame(r, camera, plainSurface(draw), plain);
    rec.plainSurface = plain.total;
    rec.plainSurfaceCpu = plain.processCpu;
    if (!o.saveFrames.empty()) render::writePng(render::sequencePath(o.saveFrames, k), image);
    detail = msg(fixed(rec.total, 1), " ms, ", rec.triangles, " triangles");
    if (o.surfaceCosts) detail += msg(", plain colouring ", fixed(rec.plainSurface, 1), " ms");
    if (o.compareFull) {
        FrameRecord full;
        gpu::Image reference = timedFrame(r, camera, fullGrid(draw), full);
        if (!run.fullFrames.empty())
            render::writePng(render::sequencePath(run.fullFrames, k), reference);
        render::ImageDifference d = render::compareImages(image, reference, 8);
        rec.psnr = d.psnr;
        rec.differing = d.differingShare;
        rec.fullTotal = full.total;
        detail += msg(", full grid ", fixed(full.total, 1), " ms, PSNR ",
                      std::isfinite(d.psnr) ? fixed(d.psnr, 2) + " dB" : std::string("identical"));
    }
    if (o.lightingCosts) {
        // The same camera without the relief fields, in turn with the frame above.
        FrameRecord other;
        timedFrame(r, camera, plainLighting(draw), other);
        rec.plain = other.total;
        detail += msg(", plain lighting ", fixed(rec.plain, 1), " ms");
    }
    if (o.overlayCosts) {
        // Interleaved with the frame above, so the machine's load weighs on all alike.
        render::DrawOptions bareDraw = draw;
        bareDraw.addedPasses = 0;
        FrameRecord other;
        timedFrame(r, camera, bareDraw, other);
        rec.bare = other.total;
        for (size_t p = 0; p < run.passNames.size() && p < 64; ++p) {
            bareDraw.addedPasses = uint64_t(1) << p;
            timedFrame(r, camera, bareDraw, other);
            rec.alone.push_back(other.total);
        }
        detail += msg(", no overlays ", fixed(rec.bare, 1), " ms");
    }
    return rec;
}

// The figures over all frames.
struct FramesSummary {
    Stats refine, upload, draw, gpu, read, total;
    double triangles = 0, bytes = 0, indices = 0;
    double rate = 0;  // refine + strip, triangles per second (median over frames)
    int refined = 0, oneThread = 0;
    std::map<int, int> cpuFrames;  // CPU the refinement finished on: frames
    double cpuShare = 0;
};

FramesSummary summarise(const std::vector<FrameRecord>& records) {
    FramesSummary s{.refine = stats(records, &FrameRecord::refine),
                    .upload = stats(records, &FrameRecord::upload),
                    .draw = stats(records, &FrameRecord::draw),
                    .gpu = stats(records, &FrameRecord::gpu),
                    .read = stats(records, &FrameRecord::readBack),
                    .total = stats(records, &FrameRecord::total)};
    auto medianOf = [&](auto field) {
        std::vector<double> v;
        for (const FrameRecord& r : records) v.push_back(double(r.*field));
        return median(v);
    };
    s.triangles = medianOf(&FrameRecord::triangles);
    s.bytes = medianOf(&FrameRecord::bytes);
    s.indices = medianOf(&FrameRecord::indices);
    // Refinement throughput, frame by frame (triangles over that frame's
    // refine + strip time), then the median: the per-core rate when the
    // refinement ran on one thread.
    std::vector<double> rates;
    for (const FrameRecord& r : records)
        if (r.refine > 0) rates.push_back(double(r.triangles) / (r.refine * 1e-3));
    s.rate = rates.empty() ? 0.0 : median(rates);
    // Frames whose refinement ran on one thread, of those that refined: what
    // the default chose, frame by frame.
    for (const FrameRecord& r : records) {
        s.refined += r.threads > 0;
        s.oneThread += r.threads == 1;
        if (r.cpu >= 0) ++s.cpuFrames[r.cpu];
    }
    s.cpuShare = s.total.median > 0 ? (s.refine.median + s.upload.median) / s.total.median : 0.0;
    return s;
}

nlohmann::json toJson(Stats s) {
    return nlohmann::json{{"median", s.median}, {"p95", s.p95}, {"p99", s.p99}};
}

// The stage table and the mesh figures on stdout, and the same in `j`.
void reportSummary(const FramesRun& run, const FramesSummary& s, nlohmann::json& j) {
    const FramesOptions& o = run.o;
    const scene::Scene& sc = o.scene;
    const render::DrawOptions& draw = run.r.drawOptions();
    const std::string lodText = render::lodName(draw.lod);
    const std::string pathText = scene::toString(sc.path.type);
    const bool adaptive = sc.lod.threads == 0;
    const std::string threadsText =
        adaptive ? msg("default (1 or ", defaultThreadCount(), ", whichever measures faster)")
                 : msg(sc.lod.threads);
    const std::string& description = run.r.terrainDescription();
    const std::string& renderer = run.r.context().renderer();
    std::printf(
        "sierra-bench frames: %s, %dx%d, %s path, %d frames, lod %s, tau %g px, geomorph %s, msaa "
        "%d, threads %s\n",
        description.c_str(), sc.output.width, sc.output.height, pathText.c_str(), run.frames(),
        lodText.c_str(), draw.tau, draw.geomorph ? "on" : "off", sc.output.msaa,
        threadsText.c_str());
    std::printf("renderer: %s\n", renderer.c_str());
    std::printf("%-22s %10s %10s %10s\n", "stage (ms)", "median", "p95", "p99");
    auto row = [](const char* name, Stats st) {
        std::printf("%-22s %10.3f %10.3f %10.3f\n", name, st.median, st.p95, st.p99);
    };
    row("refine + strip", s.refine);
    row("upload", s.upload);
    row("draw (to glFinish)", s.draw);
    row("draw (GL timer)", s.gpu);
    row("read-back", s.read);
    row("frame", s.total);
    std::printf("triangles per frame (median): %.0f\n", s.triangles);
    std::printf("refine + strip rate (median over frames): %.1f M triangles/s\n", s.rate * 1e-6);
    if (s.refined > 0)
        std::printf("refinements on one thread: %d of %d frames\n", s.oneThread, s.refined);
    if (!s.cpuFrames.empty()) {
        std::string text;
        for (const auto& [cpu, frames] : s.cpuFrames)
            text += msg(text.empty() ? "" : ", ", "CPU ", cpu, " (", frames,
                        frames == 1 ? " frame)" : " frames)");
        std::printf("refinements finished on: %s%s\n", text.c_str(),
                    o.pinCpu >= 0 ? msg("; pinned to CPU ", o.pinCpu).c_str() : "");
    }
    const double perTriangle = s.triangles > 0 ? s.indices / s.triangles : 0.0;
    const double bytesPerTriangle = s.triangles > 0 ? s.bytes / s.triangles : 0.0;
    std::printf("indices per triangle: %.3f\n", perTriangle);
    std::printf("bytes uploaded per frame (median): %.0f (%.2f per triangle)\n", s.bytes,
                bytesPerTriangle);
    std::printf("refine + strip + upload share of the frame: %.1f%%\n", 100.0 * s.cpuShare);

    j["terrain"] = description;
    j["renderer"] = renderer;
    j["size"] = {sc.output.width, sc.output.height};
    j["path"] = pathText;
    j["frames"] = run.frames();
    j["lod"] = lodText;
    j["tau"] = draw.tau;
    j["geomorph"] = draw.geomorph;
    j["msaa"] = sc.output.msaa;
    j["threads"] = sc.lod.threads ? sc.lod.threads : defaultThreadCount();
    j["threads_adaptive"] = adaptive;
    j["ms"] = {{"refine_strip", toJson(s.refine)}, {"upload", toJson(s.upload)},
               {"draw", toJson(s.draw)},           {"draw_gl_timer", toJson(s.gpu)},
               {"read_back", toJson(s.read)},      {"frame", toJson(s.total)}};
    j["triangles_median"] = s.triangles;
    j["refine_triangles_per_second_median"] = s.rate;
    j["one_thread_frames"] = s.oneThread;
    j["pinned_cpu"] = o.pinCpu >= 0 ? nlohmann::json(o.pinCpu) : nlohmann::json(nullptr);
    j["indices_per_triangle"] = perTriangle;
    j["bytes_per_frame_median"] = s.bytes;
    j["bytes_per_triangle"] = bytesPerTriangle;
    j["cpu_share"] = s.cpuShare;
}
// --compare-full: the frames against the full grid's from the same cameras.
void reportCompareFull(const FramesRun& run, const std::vector<FrameRecord>& records,
                       const FramesSummary& s, nlohmann::json& j) {
    const std::string lodText = render::lodName(run.r.drawOptions().lod);
    Stats full = stats(records, &FrameRecord::fullTotal);
    Stats psnr = stats(records, &FrameRecord::psnr);
    Stats differing = stats(records, &FrameRecord::differing);
    // A frame identical to its reference has an infinite PSNR: say so in
    // words here and as null in the JSON (which has no infinity).
    double minPsnr = std::numeric_limits<double>::infinity();
    int identical = 0;
    for (const FrameRecord& r : records) {
        minPsnr = std::min(minPsnr, r.psnr);
        identical += std::isinf(r.psnr);
    }
    auto dB = [](double v) {
        return std::isfinite(v) ? fixed(v, 2) + " dB" : std::string("identical");
    };
    std::printf("full-grid frame (ms): median %.3f, p95 %.3f\n", full.median, full.p95);
    std::printf("frame time ratio %s / full (medians): %.4f (1/%.1f)\n", lodText.c_str(),
                s.total.median / full.median, full.median / s.total.median);
    std::printf(
        "PSNR against full grid: median %s, min %s; %d of %zu frames identical; differing "
        "pixels: "
        "median %.3f%%\n",
        dB(psnr.median).c_str(), dB(minPsnr).c_str(), identical, records.size(),
        100.0 * differing.median);
    auto psnrJson = [](double v) {
        return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
    };
    j["full_frame"] = toJson(full);
    j["frame_ratio"] = s.total.median / full.median;
    j["psnr"] = {{"median", psnrJson(psnr.median)},
                 {"min", psnrJson(minPsnr)},
                 {"identical_frames", identical},
                 {"note", "dB against the full grid; null = identical frames"}};
    j["differing_share_median"] = differing.median;
}

// --lighting-costs: frames with and without the relief fields.
void reportLightingCosts(const FramesRun& run, const std::vector<FrameRecord>& records,
                         const FramesSummary& s, nlohmann::json& j) {
    const render::DrawOptions& draw = run.r.drawOptions();
    // The ratio of medians of frames drawn in turn from the same cameras.
    Stats plain = stats(records, &FrameRecord::plain);
    std::printf(
        "lighting costs (frame medians, each camera drawn in turn with and without): plain "
        "lighting %.3f ms, %s%s%s %.3f ms: x%.3f (%+.1f%%); relief fields computed in %.1f "
        "ms\n",
        plain.median, draw.lighting.shadows ? "shadows" : "",
        draw.lighting.shadows && draw.lighting.skyLight ? " and " : "",
        draw.lighting.skyLight ? "sky light" : "", s.total.median, s.total.median / plain.median,
        100.0 * (s.total.median / plain.median - 1.0), run.r.terrain().terrain().reliefMs());
    j["lighting_costs"] = {{"plain_frame_median", plain.median},
                           {"ratio", s.total.median / plain.median},
                           {"shadows", draw.lighting.shadows},
                           {"sky_light", draw.lighting.skyLight},
                           {"relief_ms", run.r.terrain().terrain().reliefMs()}};
}

// --surface-costs: frames with the zone surface and the plain colouring.
void reportSurfaceCosts(const FramesRun& run, const std::vector<FrameRecord>& records,
                        const FramesSummary& s, nlohmann::json& j) {
    // Frame by frame (each camera drawn in turn with both surfaces), the
    // median of the ratios, beside the ratio of the two medians; the
    // same of the process's CPU time.
    Stats plain = stats(records, &FrameRecord::plainSurface);
    Stats zonesCpu = stats(records, &FrameRecord::processCpu);
    Stats plainCpu = stats(records, &FrameRecord::plainSurfaceCpu);
    std::vector<double> ratios, cpuRatios;
    for (const FrameRecord& r : records) {
        ratios.push_back(r.total / r.plainSurface);
        cpuRatios.push_back(r.processCpu / r.plainSurfaceCpu);
    }
    const double ratio = median(ratios), cpuRatio = median(cpuRatios);
    std::printf(
        "surface costs (each camera drawn in turn with and without the zone surface): plain "
        "colouring %.3f ms, zones %.3f ms (frame medians): x%.3f (%+.1f%%) frame by frame "
        "(median; p95 x%.3f), x%.3f of the medians\n",
        plain.median, s.total.median, ratio, 100.0 * (ratio - 1.0), quantile(ratios, 0.95),
        s.total.median / plain.median);
    std::printf(
        "surface costs in process CPU time (every thread): plain colouring %.3f ms, zones "
        "%.3f ms (medians): x%.3f frame by frame (median; p95 x%.3f)\n",
        plainCpu.median, zonesCpu.median, cpuRatio, quantile(cpuRatios, 0.95));
    j["surface_costs"] = {
        {"surface", "zones"},
        {"zones", run.o.scene.zones.map},
        {"plain_frame", toJson(plain)},
        {"zones_frame", toJson(s.total)},
        {"ratio", ratio},
        {"ratio_p95", quantile(ratios, 0.95)},
        {"ratio_of_medians", s.total.median / plain.median},
        {"plain_cpu", toJson(plainCpu)},
        {"zones_cpu", toJson(zonesCpu)},
        {"cpu_ratio", cpuRatio},
        {"cpu_ratio_p95", quantile(cpuRatios, 0.95)},
        {"note",
         "ratio: the median over frames of zones / plain frame time, each camera drawn in "
         "turn with both; cpu_ratio: the same of the process's CPU time (all threads)"}};
}

// --overlay-costs: frames without the overlay passes and with each alone.
void reportOverlayCosts(const FramesRun& run, const std::vector<FrameRecord>& records,
                        const FramesSummary& s, nlohmann::json& j) {
    const std::vector<std::string>& passNames = run.passNames;
    // Ratios of medians of frames drawn in turn from the same cameras.
    Stats bare = stats(records, &FrameRecord::bare);
    std::printf(
        "overlay costs (frame medians, each camera drawn in turn with and without): no "
        "overlays %.3f ms, "
        "all overlays %.3f ms: x%.3f (%+.1f%%)\n",
        bare.median, s.total.median, s.total.median / bare.median,
        100.0 * (s.total.median / bare.median - 1.0));
    nlohmann::json alone = nlohmann::json::object();
    for (size_t p = 0; p < passNames.size() && p < 64; ++p) {
        std::vector<double> v;
        for (const FrameRecord& r : records) v.push_back(r.alone[p]);
        const double m = median(v);
        std::printf("  %-10s alone %.3f ms: x%.3f (%+.1f%%)\n", passNames[p].c_str(), m,
                    m / bare.median, 100.0 * (m / bare.median - 1.0));
        alone[passNames[p]] = {{"frame_median", m}, {"ratio", m / bare.median}};
    }
    j["overlay_costs"] = {{"bare_frame_median", bare.median},
                          {"all_ratio", s.total.median / bare.median},
                          {"alone", alone}};
}

// Every frame's record.
nlohmann::json perFrameJson(const FramesOptions& o, const std::vector<FrameRecord>& records) {
    nlohmann::json perFrame = nlohmann::json::array();
    for (const FrameRecord& r : records)
        perFrame.push_back(
            {{"refine", r.refine},
             {"upload", r.upload},
             {"draw", r.draw},
             {"gpu", r.gpu},
             {"read_back", r.readBack},
             {"frame", r.total},
             {"triangles", r.triangles},
             {"threads", r.threads},
             {"cpu", r.cpu},
             {"bytes", r.bytes},
             {"psnr", o.compareFull && std::isfinite(r.psnr) ? nlohmann::json(r.psnr)
                                                             : nlohmann::json(nullptr)},
             {"process_cpu", r.processCpu},
             {"plain_surface",
              o.surfaceCosts ? nlohmann::json(r.plainSurface) : nlohmann::json(nullptr)},
             {"plain_surface_cpu",
              o.surfaceCosts ? nlohmann::json(r.plainSurfaceCpu) : nlohmann::json(nullptr)}});
    return perFrame;
}

void runFrames(const FramesOptions& o) {
    const scene::Scene& sc = o.scene;
    checkFramesOptions(o);
    facade::SceneRenderer r = setUpFrames(o);
    FramesRun run{.o = o,
                  .r = r,
                  .first = sc.path.range ? sc.path.range->first : 0,
                  .last = sc.path.range ? sc.path.range->last : r.frameCount() - 1,
                  .passNames = r.terrain().addedPassNames()};
    checkCostOptions(run, r.drawOptions(run.first));
    // Saved frames carry their index in the whole sequence; full-grid
    // references go beside them as NAME_full_0000.png.
    if (!o.saveFrames.empty()) {
        std::filesystem::path p(o.saveFrames);
        run.fullFrames =
            (p.parent_path() / (p.stem().string() + "_full" + p.extension().string())).string();
    }
    warmUp(run);

    std::vector<FrameRecord> records;
    Progress progress(o.compareFull ? "frames (and full-grid references)" : "frames",
                      int64_t(run.frames()));
    for (int k = run.first; k <= run.last; ++k) {
        std::string detail;
        records.push_back(measureFrame(run, k, detail));
        progress.update(int64_t(k - run.first + 1), detail);
    }
    progress.finish();

    const FramesSummary summary = summarise(records);
    nlohmann::json j;
    reportSummary(run, summary, j);
    if (o.compareFull) reportCompareFull(run, records, summary, j);
    if (o.lightingCosts) reportLightingCosts(run, records, summary, j);
    if (o.surfaceCosts) reportSurfaceCosts(run, records, summary, j);
    if (o.overlayCosts) reportOverlayCosts(run, records, summary, j);
    j["per_frame"] = perFrameJson(o, records);
    if (!o.json.empty()) {
        writeFileAtomic(o.json, j.dump(2) + "\n");
        std::printf("wrote %s\n", o.json.c_str());
    }
}

}  // namespace

void addFramesCommand(CLI::App& app) {
    auto o = std::make_shared<FramesOptions>();
    // The benchmark's own defaults: a 1080p orbit of 60 frames, no MSAA, no
    // debug snapshot (every other option as in sierra-render).
    o->scene.output.width = 1920;
    o->scene.output.height = 1080;
    o->scene.output.msaa = 0;
    o->scene.output.debug.clear();
    o->scene.path.type = scene::PathType::Orbit;
    o->scene.path.frames = 60;
    CLI::App* cmd =
        app.add_subcommand("frames", "Time view-dependent frames along a camera path (EGL)");
    o->registrar = std::make_unique<scene::SceneOptions>(
        *cmd, o->scene,
        scene::kTerrainOptions | scene::kCameraOptions | scene::kPathOptions |
            scene::kLightingOptions | scene::kLodOptions | scene::kStyleOptions |
            scene::kFrameOptions | scene::kZoneOptions | scene::kZoneShadingOptions);
    cmd->add_flag(
        "--compare-full", o->compareFull,
        "Also render the full grid from each camera: frame-time ratio, PSNR, differing pixels");
    cmd->add_flag("--overlay-costs", o->overlayCosts,
                  "Also draw each frame without the overlay passes and with each alone: their cost "
                  "as ratios");
    cmd->add_flag("--lighting-costs", o->lightingCosts,
                  "Also draw each frame without shadows and sky light: their cost as a ratio");
    cmd->add_flag("--surface-costs", o->surfaceCosts,
                  "Also draw each frame with the plain colouring instead of the zone surface "
                  "(--zones): its cost as a ratio, frame by frame");
    cmd->add_option("--json", o->json, "Write all figures and per-frame records as JSON");
    cmd->add_option("--save-frames", o->saveFrames,
                    "Write every frame as PNG (NAME_0000.png, ...)");
    cmd->add_option("--pin-cpu", o->pinCpu,
                    "Keep the thread that refines every frame on this CPU (the driver's threads "
                    "keep every CPU): steadier refinement rates where cores run at different "
                    "speeds")
        ->check(CLI::Range(0, CPU_SETSIZE - 1));
    cmd->callback([o] {
        asUsage([&] { o->registrar->apply(); });
        if (o->registrar->printConfigRequested()) return;
        runFrames(*o);
    });
}

}  // namespace sierra::apps
