// sierra-bench frames: renders a camera path and times every stage of every
// frame (refine + strip, upload, draw to completion, read-back), optionally
// against the full-grid renderer from the same cameras (frame time ratio, PSNR).

#include "Commands.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Log.h>
#include <sierra/core/Parallel.h>
#include <sierra/core/Timer.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/render/Capture.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/Scene.h>
#include <sierra/render/TerrainRenderer.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>

namespace sierra::apps {
namespace {

struct FramesOptions {
    render::TerrainSource source;
    std::string size = "1920x1080";
    float tau = 1.0f;
    std::string path = "orbit";
    int frames = 60;
    std::string lod = "sbt";
    int threads = 0;
    int msaa = 0;
    bool compareFull = false;
    bool noGeomorph = false;
    std::string json;
    std::string saveFrames;  // prefix for PNGs of every frame, empty = none
};

// Times of one frame, milliseconds.
struct FrameRecord {
    double refine = 0, upload = 0, draw = 0, gpu = 0, readBack = 0, total = 0;
    uint64_t triangles = 0, indices = 0, bytes = 0;
    double psnr = 0, differing = 0;  // against the full grid (compare mode)
    double fullTotal = 0;            // full-grid frame time (compare mode)
};

struct Stats {
    double median, p95, p99;
};

Stats stats(const std::vector<FrameRecord>& records, double FrameRecord::*field) {
    std::vector<double> v;
    for (const FrameRecord& r : records) v.push_back(r.*field);
    return {median(v), quantile(v, 0.95), quantile(v, 0.99)};
}

// Draws one frame and reads it back; fills the timing fields of `record`.
gpu::Image timedFrame(render::TerrainRenderer& terrain, render::FrameTarget& target, const render::Camera& camera,
                      const render::DrawOptions& draw, FrameRecord& record) {
    Stopwatch frame;
    target.begin(terrain.skyColour());
    render::DrawStats s = terrain.draw(camera, target.width(), target.height(), draw);
    Stopwatch finish;
    target.resolve();
    glFinish();  // llvmpipe rasterises at flush: the draw is done only here
    double drawWall = s.submitMs + finish.ms();
    Stopwatch read;
    gpu::Image image = gpu::readFramebuffer(target.width(), target.height());
    record.readBack = read.ms();
    record.total = frame.ms();
    terrain.collectGpuTime(s);
    record.refine = s.refineMs;
    record.upload = s.uploadMs;
    record.draw = drawWall;
    record.gpu = s.drawMs;
    record.triangles = s.triangles;
    record.indices = s.indices;
    record.bytes = s.bytesUploaded;
    return image;
}

void runFrames(const FramesOptions& o) {
    auto [width, height] = render::parseFrameSize(o.size);
    render::Lod lod = render::parseLod(o.lod);
    SIERRA_CHECK(o.tau > 0.0f, "--tau must be positive pixels, got ", o.tau);
    SIERRA_CHECK(o.path == "orbit" || o.path == "flyover", "--path must be orbit or flyover, got ", o.path);

    std::string description;
    terrain::Heightfield field = render::loadTerrain(o.source, &description);
    std::fprintf(stderr, "terrain: %s\n", description.c_str());
    gpu::EglContext context = gpu::EglContext::create({.width = width, .height = height});
    std::fprintf(stderr, "renderer: %s (%s)\n", context.renderer().c_str(), context.platform().c_str());
    render::TerrainRenderer terrain =
        render::TerrainRenderer::create({.field = &field, .threads = o.threads});
    render::FrameTarget target = render::FrameTarget::create({.width = width, .height = height, .samples = o.msaa});
    std::vector<render::Camera> cameras = o.path == "orbit" ? render::orbitPath(terrain.bounds(), o.frames)
                                                            : render::flyoverPath(terrain.bounds(), o.frames);
    render::DrawOptions draw{.lod = lod, .tau = o.tau, .geomorph = !o.noGeomorph, .threads = o.threads};
    render::DrawOptions fullDraw{.lod = render::Lod::Full};

    // One warm-up frame: first-use costs (full-grid index build, shader
    // compilation in the driver) are not frame costs.
    {
        FrameRecord warm;
        timedFrame(terrain, target, cameras.front(), draw, warm);
        if (o.compareFull || lod == render::Lod::Full) timedFrame(terrain, target, cameras.front(), fullDraw, warm);
    }

    std::vector<FrameRecord> records;
    for (size_t k = 0; k < cameras.size(); ++k) {
        FrameRecord r;
        gpu::Image image = timedFrame(terrain, target, cameras[k], draw, r);
        if (!o.saveFrames.empty()) render::writePng(render::sequencePath(o.saveFrames, int(k)), image);
        if (o.compareFull) {
            FrameRecord full;
            gpu::Image reference = timedFrame(terrain, target, cameras[k], fullDraw, full);
            render::ImageDifference d = render::compareImages(image, reference, 8);
            r.psnr = d.psnr;
            r.differing = d.differingShare;
            r.fullTotal = full.total;
        }
        records.push_back(r);
        std::fprintf(stderr, "\rframe %zu/%zu: %.1f ms, %llu triangles", k + 1, cameras.size(), r.total,
                     (unsigned long long)r.triangles);
    }
    std::fprintf(stderr, "\n");

    Stats refine = stats(records, &FrameRecord::refine), upload = stats(records, &FrameRecord::upload),
          drawS = stats(records, &FrameRecord::draw), gpuS = stats(records, &FrameRecord::gpu),
          readS = stats(records, &FrameRecord::readBack), total = stats(records, &FrameRecord::total);
    auto medianOf = [&](auto field) {
        std::vector<double> v;
        for (const FrameRecord& r : records) v.push_back(double(r.*field));
        return median(v);
    };
    double triangles = medianOf(&FrameRecord::triangles);
    double bytes = medianOf(&FrameRecord::bytes);
    double indices = medianOf(&FrameRecord::indices);

    std::printf("sierra-bench frames: %s, %dx%d, %s path, %d frames, lod %s, tau %g px, msaa %d, threads %d\n",
                description.c_str(), width, height, o.path.c_str(), o.frames, o.lod.c_str(), o.tau, o.msaa,
                o.threads ? o.threads : defaultThreadCount());
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
    std::printf("indices per triangle: %.3f\n", triangles > 0 ? indices / triangles : 0.0);
    std::printf("bytes uploaded per frame (median): %.0f (%.2f per triangle)\n", bytes,
                triangles > 0 ? bytes / triangles : 0.0);
    double cpuShare = total.median > 0 ? (refine.median + upload.median) / total.median : 0.0;
    std::printf("refine + strip + upload share of the frame: %.1f%%\n", 100.0 * cpuShare);

    nlohmann::json j;
    j["terrain"] = description;
    j["renderer"] = context.renderer();
    j["size"] = {width, height};
    j["path"] = o.path;
    j["frames"] = o.frames;
    j["lod"] = o.lod;
    j["tau"] = o.tau;
    j["msaa"] = o.msaa;
    j["threads"] = o.threads ? o.threads : defaultThreadCount();
    auto toJson = [](Stats s) { return nlohmann::json{{"median", s.median}, {"p95", s.p95}, {"p99", s.p99}}; };
    j["ms"] = {{"refine_strip", toJson(refine)}, {"upload", toJson(upload)},   {"draw", toJson(drawS)},
               {"draw_gl_timer", toJson(gpuS)},  {"read_back", toJson(readS)}, {"frame", toJson(total)}};
    j["triangles_median"] = triangles;
    j["indices_per_triangle"] = triangles > 0 ? indices / triangles : 0.0;
    j["bytes_per_frame_median"] = bytes;
    j["bytes_per_triangle"] = triangles > 0 ? bytes / triangles : 0.0;
    j["cpu_share"] = cpuShare;

    if (o.compareFull) {
        Stats full = stats(records, &FrameRecord::fullTotal);
        Stats psnr = stats(records, &FrameRecord::psnr);
        Stats differing = stats(records, &FrameRecord::differing);
        double minPsnr = 1e9;
        for (const FrameRecord& r : records) minPsnr = std::min(minPsnr, r.psnr);
        std::printf("full-grid frame (ms): median %.3f, p95 %.3f\n", full.median, full.p95);
        std::printf("frame time ratio %s / full (medians): %.4f (1/%.1f)\n", o.lod.c_str(),
                    total.median / full.median, full.median / total.median);
        std::printf("PSNR against full grid: median %.2f dB, min %.2f dB; differing pixels: median %.3f%%\n",
                    psnr.median, minPsnr, 100.0 * differing.median);
        j["full_frame"] = toJson(full);
        j["frame_ratio"] = total.median / full.median;
        j["psnr"] = {{"median", psnr.median}, {"min", minPsnr}};
        j["differing_share_median"] = differing.median;
    }
    nlohmann::json perFrame = nlohmann::json::array();
    for (const FrameRecord& r : records)
        perFrame.push_back({{"refine", r.refine}, {"upload", r.upload}, {"draw", r.draw}, {"gpu", r.gpu},
                            {"read_back", r.readBack}, {"frame", r.total}, {"triangles", r.triangles},
                            {"bytes", r.bytes}, {"psnr", o.compareFull ? r.psnr : 0.0}});
    j["per_frame"] = perFrame;
    if (!o.json.empty()) {
        writeFileAtomic(o.json, j.dump(2) + "\n");
        std::printf("wrote %s\n", o.json.c_str());
    }
}

}  // namespace

void addFramesCommand(CLI::App& app) {
    auto o = std::make_shared<FramesOptions>();
    CLI::App* cmd = app.add_subcommand("frames", "Time view-dependent frames along a camera path (EGL)");
    cmd->option_defaults()->always_capture_default();
    auto* heightmap = cmd->add_option("--heightmap", o->source.heightmap, "Heightmap file (any Sierra loader)")
                          ->check(CLI::ExistingFile);
    cmd->add_option("--generate", o->source.generateSize, "Generate a diamond-square terrain of N = 2^k+1 samples")
        ->excludes(heightmap);
    cmd->add_option("--seed", o->source.seed, "Seed of the generated terrain");
    cmd->add_option("--roughness", o->source.roughness, "Roughness of the generated terrain");
    cmd->add_option("--size", o->size, "Frame size WIDTHxHEIGHT");
    cmd->add_option("--tau", o->tau, "Screen-space error threshold in pixels");
    cmd->add_option("--path", o->path, "Camera path")->check(CLI::IsMember({"orbit", "flyover"}));
    cmd->add_option("--frames", o->frames, "Frames to time")->check(CLI::Range(1, 100000));
    cmd->add_option("--lod", o->lod, "sbt or full")->check(CLI::IsMember({"sbt", "full"}));
    cmd->add_option("--threads", o->threads, "Refinement threads (0 = all cores)")->check(CLI::Range(0, 256));
    cmd->add_option("--msaa", o->msaa, "Multisample count (0 = off)")->check(CLI::IsMember({0, 2, 4, 8}));
    cmd->add_flag("--compare-full", o->compareFull,
                  "Also render the full grid from each camera: frame-time ratio, PSNR, differing pixels");
    cmd->add_flag("--no-geomorph", o->noGeomorph, "Draw SBT vertices at their heights at once");
    cmd->add_option("--json", o->json, "Write all figures and per-frame records as JSON");
    cmd->add_option("--save-frames", o->saveFrames, "Write every frame as PNG (NAME_0000.png, ...)");
    cmd->callback([o] { runFrames(*o); });
}

}  // namespace sierra::apps
