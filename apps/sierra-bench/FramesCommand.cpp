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
#include <sierra/facade/SceneView.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/render/Capture.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainGpu.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/Options.h>
#include <sierra/scene/Terrain.h>

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
gpu::Image timedFrame(render::TerrainRenderer& terrain, render::FrameTarget& target,
                      const render::Camera& camera, const render::DrawOptions& draw,
                      FrameRecord& record) {
    const double cpuStart = processCpuMs();
    Stopwatch frame;
    target.begin(render::TerrainRenderer::clearColour(draw.lighting));
    render::DrawStats s = terrain.draw(camera, target.width(), target.height(), draw);
    Stopwatch finish;
    target.resolve();
    glFinish();  // llvmpipe rasterises at flush: the draw is done only here
    double drawWall = s.submitMs + finish.ms();
    Stopwatch read;
    gpu::Image image = gpu::readFramebuffer(target.width(), target.height());
    record.readBack = read.ms();
    record.total = frame.ms();
    record.processCpu = processCpuMs() - cpuStart;
    terrain.collectGpuTime(s);
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

void runFrames(const FramesOptions& o) {
    const scene::Scene& sc = o.scene;
    if (o.pinCpu >= 0) checkPinCpu(o.pinCpu);
    // Outputs are checked before the run, so a bad path fails at once.
    if (!o.saveFrames.empty() && lowerExtension(o.saveFrames) != ".png")
        throw UsageError(
            msg("frames: --save-frames must name a .png file (frames are written as "
                "PNG, NAME_0000.png, ...), got '",
                o.saveFrames, "'"));
    for (const std::string* path : {&o.json, &o.saveFrames})
        if (!path->empty()) ensureWritableLocation(*path);
    const int width = sc.output.width, height = sc.output.height;
    std::string description;
    // The context comes first: its texture limit bounds the grid the loader takes.
    gpu::EglContext context = gpu::EglContext::create({.width = width, .height = height});
    std::fprintf(stderr, "renderer: %s (%s)\n", context.renderer().c_str(),
                 context.platform().c_str());
    if (o.pinCpu >= 0) pinCallingThread(o.pinCpu);
    terrain::Heightfield field =
        scene::loadTerrain(sc.terrain, &description, scene::Padding::PowerOfTwoPlusOne,
                           render::TerrainGpu::maxGridSide());
    float seaLevel = scene::resolveSeaLevel(sc.terrain, field);
    std::fprintf(stderr, "terrain: %s\n", description.c_str());
    const std::vector<glm::vec3> allSuns = facade::sceneSunDirections(sc, field);
    render::TerrainRenderer terrain =
        render::TerrainRenderer::create(facade::sceneTerrainDesc(sc, field, seaLevel));
    if (std::string zones = facade::applySceneSurface(terrain, sc, field, seaLevel); !zones.empty())
        std::fprintf(stderr, "%s\n", zones.c_str());
    if (std::string mesh = facade::applySceneMesh(terrain, sc, field); !mesh.empty())
        std::fprintf(stderr, "%s\n", mesh.c_str());
    facade::addOverlayPasses(terrain, sc);
    const std::vector<std::string> passNames = terrain.addedPassNames();
    if (o.overlayCosts && passNames.empty())
        throw UsageError(
            "--overlay-costs needs overlays to time: --style with lines, hatch or contours, or "
            "--preset");
    render::FrameTarget target =
        render::FrameTarget::create({.width = width, .height = height, .samples = sc.output.msaa});
    std::vector<render::Camera> all = facade::sceneCameras(sc, terrain.bounds());
    const int first = sc.path.range ? sc.path.range->first : 0;
    const int last = sc.path.range ? sc.path.range->last : int(all.size()) - 1;
    std::vector<render::Camera> cameras(all.begin() + first, all.begin() + last + 1);
    const std::vector<glm::vec3> suns(allSuns.begin() + first, allSuns.begin() + last + 1);
    render::DrawOptions draw = facade::sceneDrawOptions(sc);
    draw.lighting.sunDirection = suns.front();
    if (o.lightingCosts && !draw.lighting.shadows && !draw.lighting.skyLight)
        throw UsageError(
            "--lighting-costs compares frames with shadows and sky light against frames "
            "without: leave --shadows or --sky-light on");
    if (o.surfaceCosts && (sc.zones.map.empty() || !sc.style.overlay.layers.shaded))
        throw UsageError(
            "--surface-costs compares frames drawn with the zone surface against the plain "
            "colouring: give --zones (with a shaded style)");
    render::Lod lod = draw.lod;
    render::DrawOptions fullDraw = draw;
    fullDraw.lod = render::Lod::Full;
    const std::string lodText = render::lodName(lod);
    const std::string pathText = scene::toString(sc.path.type);

    // One warm-up frame: first-use costs (full-grid index build, shader
    // compilation in the driver) are not frame costs.
    {
        FrameRecord warm;
        timedFrame(terrain, target, cameras.front(), draw, warm);
        if (o.compareFull || lod == render::Lod::Full)
            timedFrame(terrain, target, cameras.front(), fullDraw, warm);
        if (o.lightingCosts) {
            render::DrawOptions plainDraw = draw;
            plainDraw.lighting.shadows = plainDraw.lighting.skyLight = false;
            timedFrame(terrain, target, cameras.front(), plainDraw, warm);
        }
        if (o.surfaceCosts) {
            render::DrawOptions plainDraw = draw;
            plainDraw.plainSurface = true;
            timedFrame(terrain, target, cameras.front(), plainDraw, warm);
        }
    }

    std::vector<FrameRecord> records;
    Progress progress(o.compareFull ? "frames (and full-grid references)" : "frames",
                      int64_t(cameras.size()));
    // Saved frames carry their index in the whole sequence; full-grid
    // references go beside them as NAME_full_0000.png.
    std::string fullFrames;
    if (!o.saveFrames.empty()) {
        std::filesystem::path p(o.saveFrames);
        fullFrames =
            (p.parent_path() / (p.stem().string() + "_full" + p.extension().string())).string();
    }
    for (size_t k = 0; k < cameras.size(); ++k) {
        FrameRecord r;
        draw.lighting.sunDirection = suns[k];
        fullDraw.lighting.sunDirection = suns[k];
        // --surface-costs: the same camera with the plain colouring, before
        // the frame on odd frames and after it on even ones, so whatever a
        // camera's first or second draw pays weighs on both alike.
        render::DrawOptions plainSurfaceDraw = draw;
        plainSurfaceDraw.plainSurface = true;
        const bool plainSurfaceFirst = o.surfaceCosts && k % 2 == 1;
        FrameRecord plainSurface;
        if (plainSurfaceFirst)
            timedFrame(terrain, target, cameras[k], plainSurfaceDraw, plainSurface);
        gpu::Image image = timedFrame(terrain, target, cameras[k], draw, r);
        if (o.surfaceCosts && !plainSurfaceFirst)
            timedFrame(terrain, target, cameras[k], plainSurfaceDraw, plainSurface);
        r.plainSurface = plainSurface.total;
        r.plainSurfaceCpu = plainSurface.processCpu;
        if (!o.saveFrames.empty())
            render::writePng(render::sequencePath(o.saveFrames, first + int(k)), image);
        std::string detail = msg(fixed(r.total, 1), " ms, ", r.triangles, " triangles");
        if (o.surfaceCosts) detail += msg(", plain colouring ", fixed(r.plainSurface, 1), " ms");
        if (o.compareFull) {
            FrameRecord full;
            gpu::Image reference = timedFrame(terrain, target, cameras[k], fullDraw, full);
            if (!fullFrames.empty())
                render::writePng(render::sequencePath(fullFrames, first + int(k)), reference);
            render::ImageDifference d = render::compareImages(image, reference, 8);
            r.psnr = d.psnr;
            r.differing = d.differingShare;
            r.fullTotal = full.total;
            detail +=
                msg(", full grid ", fixed(full.total, 1), " ms, PSNR ",
                    std::isfinite(d.psnr) ? fixed(d.psnr, 2) + " dB" : std::string("identical"));
        }
        if (o.lightingCosts) {
            // The same camera without the relief fields, in turn with the frame above.
            render::DrawOptions plainDraw = draw;
            plainDraw.lighting.shadows = plainDraw.lighting.skyLight = false;
            FrameRecord other;
            timedFrame(terrain, target, cameras[k], plainDraw, other);
            r.plain = other.total;
            detail += msg(", plain lighting ", fixed(r.plain, 1), " ms");
        }
        if (o.overlayCosts) {
            // Interleaved with the frame above, so the machine's load weighs on all alike.
            render::DrawOptions bareDraw = draw;
            bareDraw.addedPasses = 0;
            FrameRecord other;
            timedFrame(terrain, target, cameras[k], bareDraw, other);
            r.bare = other.total;
            for (size_t p = 0; p < passNames.size() && p < 64; ++p) {
                bareDraw.addedPasses = uint64_t(1) << p;
                timedFrame(terrain, target, cameras[k], bareDraw, other);
                r.alone.push_back(other.total);
            }
            detail += msg(", no overlays ", fixed(r.bare, 1), " ms");
        }
        records.push_back(r);
        progress.update(int64_t(k + 1), detail);
    }
    progress.finish();

    Stats refine = stats(records, &FrameRecord::refine),
          upload = stats(records, &FrameRecord::upload), drawS = stats(records, &FrameRecord::draw),
          gpuS = stats(records, &FrameRecord::gpu), readS = stats(records, &FrameRecord::readBack),
          total = stats(records, &FrameRecord::total);
    auto medianOf = [&](auto field) {
        std::vector<double> v;
        for (const FrameRecord& r : records) v.push_back(double(r.*field));
        return median(v);
    };
    double triangles = medianOf(&FrameRecord::triangles);
    double bytes = medianOf(&FrameRecord::bytes);
    double indices = medianOf(&FrameRecord::indices);
    // Refinement throughput, frame by frame (triangles over that frame's
    // refine + strip time), then the median: the per-core rate when the
    // refinement ran on one thread.
    std::vector<double> rates;
    for (const FrameRecord& r : records)
        if (r.refine > 0) rates.push_back(double(r.triangles) / (r.refine * 1e-3));
    const double rate = rates.empty() ? 0.0 : median(rates);
    // Frames whose refinement ran on one thread, of those that refined: what
    // the default chose, frame by frame.
    int refined = 0, oneThread = 0;
    std::map<int, int> cpuFrames;  // CPU the refinement finished on: frames
    for (const FrameRecord& r : records) {
        refined += r.threads > 0;
        oneThread += r.threads == 1;
        if (r.cpu >= 0) ++cpuFrames[r.cpu];
    }
    const bool adaptive = sc.lod.threads == 0;
    const std::string threadsText =
        adaptive ? msg("default (1 or ", defaultThreadCount(), ", whichever measures faster)")
                 : msg(sc.lod.threads);

    std::printf(
        "sierra-bench frames: %s, %dx%d, %s path, %zu frames, lod %s, tau %g px, geomorph %s, msaa "
        "%d, threads %s\n",
        description.c_str(), width, height, pathText.c_str(), cameras.size(), lodText.c_str(),
        draw.tau, draw.geomorph ? "on" : "off", sc.output.msaa, threadsText.c_str());
    std::printf("renderer: %s\n", context.renderer().c_str());
    std::printf("%-22s %10s %10s %10s\n", "stage (ms)", "median", "p95", "p99");
    auto row = [](const char* name, Stats s) {
        std::printf("%-22s %10.3f %10.3f %10.3f\n", name, s.median, s.p95, s.p99);
    };
    row("refine + strip", refine);
    row("upload", upload);
    row("draw (to glFinish)", drawS);
    row("draw (GL timer)", gpuS);
    row("read-back", readS);
    row("frame", total);
    std::printf("triangles per frame (median): %.0f\n", triangles);
    std::printf("refine + strip rate (median over frames): %.1f M triangles/s\n", rate * 1e-6);
    if (refined > 0)
        std::printf("refinements on one thread: %d of %d frames\n", oneThread, refined);
    if (!cpuFrames.empty()) {
        std::string text;
        for (const auto& [cpu, frames] : cpuFrames)
            text += msg(text.empty() ? "" : ", ", "CPU ", cpu, " (", frames,
                        frames == 1 ? " frame)" : " frames)");
        std::printf("refinements finished on: %s%s\n", text.c_str(),
                    o.pinCpu >= 0 ? msg("; pinned to CPU ", o.pinCpu).c_str() : "");
    }
    std::printf("indices per triangle: %.3f\n", triangles > 0 ? indices / triangles : 0.0);
    std::printf("bytes uploaded per frame (median): %.0f (%.2f per triangle)\n", bytes,
                triangles > 0 ? bytes / triangles : 0.0);
    double cpuShare = total.median > 0 ? (refine.median + upload.median) / total.median : 0.0;
    std::printf("refine + strip + upload share of the frame: %.1f%%\n", 100.0 * cpuShare);

    nlohmann::json j;
    j["terrain"] = description;
    j["renderer"] = context.renderer();
    j["size"] = {width, height};
    j["path"] = pathText;
    j["frames"] = cameras.size();
    j["lod"] = lodText;
    j["tau"] = draw.tau;
    j["geomorph"] = draw.geomorph;
    j["msaa"] = sc.output.msaa;
    j["threads"] = sc.lod.threads ? sc.lod.threads : defaultThreadCount();
    j["threads_adaptive"] = adaptive;
    auto toJson = [](Stats s) {
        return nlohmann::json{{"median", s.median}, {"p95", s.p95}, {"p99", s.p99}};
    };
    j["ms"] = {{"refine_strip", toJson(refine)}, {"upload", toJson(upload)},
               {"draw", toJson(drawS)},          {"draw_gl_timer", toJson(gpuS)},
               {"read_back", toJson(readS)},     {"frame", toJson(total)}};
    j["triangles_median"] = triangles;
    j["refine_triangles_per_second_median"] = rate;
    j["one_thread_frames"] = oneThread;
    j["pinned_cpu"] = o.pinCpu >= 0 ? nlohmann::json(o.pinCpu) : nlohmann::json(nullptr);
    j["indices_per_triangle"] = triangles > 0 ? indices / triangles : 0.0;
    j["bytes_per_frame_median"] = bytes;
    j["bytes_per_triangle"] = triangles > 0 ? bytes / triangles : 0.0;
    j["cpu_share"] = cpuShare;

    if (o.compareFull) {
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
                    total.median / full.median, full.median / total.median);
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
        j["frame_ratio"] = total.median / full.median;
        j["psnr"] = {{"median", psnrJson(psnr.median)},
                     {"min", psnrJson(minPsnr)},
                     {"identical_frames", identical},
                     {"note", "dB against the full grid; null = identical frames"}};
        j["differing_share_median"] = differing.median;
    }
    if (o.lightingCosts) {
        // The ratio of medians of frames drawn in turn from the same cameras.
        Stats plain = stats(records, &FrameRecord::plain);
        std::printf(
            "lighting costs (frame medians, each camera drawn in turn with and without): plain "
            "lighting %.3f ms, %s%s%s %.3f ms: x%.3f (%+.1f%%); relief fields computed in %.1f "
            "ms\n",
            plain.median, draw.lighting.shadows ? "shadows" : "",
            draw.lighting.shadows && draw.lighting.skyLight ? " and " : "",
            draw.lighting.skyLight ? "sky light" : "", total.median, total.median / plain.median,
            100.0 * (total.median / plain.median - 1.0), terrain.terrain().reliefMs());
        j["lighting_costs"] = {{"plain_frame_median", plain.median},
                               {"ratio", total.median / plain.median},
                               {"shadows", draw.lighting.shadows},
                               {"sky_light", draw.lighting.skyLight},
                               {"relief_ms", terrain.terrain().reliefMs()}};
    }
    if (o.surfaceCosts) {
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
            plain.median, total.median, ratio, 100.0 * (ratio - 1.0), quantile(ratios, 0.95),
            total.median / plain.median);
        std::printf(
            "surface costs in process CPU time (every thread): plain colouring %.3f ms, zones "
            "%.3f ms (medians): x%.3f frame by frame (median; p95 x%.3f)\n",
            plainCpu.median, zonesCpu.median, cpuRatio, quantile(cpuRatios, 0.95));
        j["surface_costs"] = {
            {"surface", "zones"},
            {"zones", sc.zones.map},
            {"plain_frame", toJson(plain)},
            {"zones_frame", toJson(total)},
            {"ratio", ratio},
            {"ratio_p95", quantile(ratios, 0.95)},
            {"ratio_of_medians", total.median / plain.median},
            {"plain_cpu", toJson(plainCpu)},
            {"zones_cpu", toJson(zonesCpu)},
            {"cpu_ratio", cpuRatio},
            {"cpu_ratio_p95", quantile(cpuRatios, 0.95)},
            {"note",
             "ratio: the median over frames of zones / plain frame time, each camera drawn in "
             "turn with both; cpu_ratio: the same of the process's CPU time (all threads)"}};
    }
    if (o.overlayCosts) {
        // Ratios of medians of frames drawn in turn from the same cameras.
        Stats bare = stats(records, &FrameRecord::bare);
        std::printf(
            "overlay costs (frame medians, each camera drawn in turn with and without): no "
            "overlays %.3f ms, "
            "all overlays %.3f ms: x%.3f (%+.1f%%)\n",
            bare.median, total.median, total.median / bare.median,
            100.0 * (total.median / bare.median - 1.0));
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
                              {"all_ratio", total.median / bare.median},
                              {"alone", alone}};
    }
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
    j["per_frame"] = perFrame;
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
