// sierra-bench tiled T.sierra [--seconds S] [--fps F] [--size WxH] [--tau PX]
//                   [--memory-budget MIB] [--loaders N] [--altitude M] [--json FILE]
//
// A fly-through of a tiled terrain (a .sierra file from sierra-tile build),
// the refinement and the streaming only (no GL): a straight flight from one
// corner of the real samples to the other at --altitude above the ground,
// paced at --fps (each frame sleeps out its period, as a frame that draws
// would take it, so the loaders stream at a frame loop's pace). Each frame:
// TileCache::beginFrame (never waits for a read), TiledRefiner::refineView,
// TileCache::wantForView with the eye one second ahead as the prefetch.
// Reports the time from the program's start to the first frame, refinement
// times (median, p99), tiles drawn coarse, what was read and evicted, the
// longest beginFrame and the process's peak resident memory.
#include "Commands.h"

#include "AppMain.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Timer.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/TileCache.h>
#include <sierra/sbt/TileFile.h>
#include <sierra/sbt/TiledRefiner.h>

#include <nlohmann/json.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace sierra::apps {
namespace {

// The program's start, for the time to the first frame.
const Stopwatch kProgramStart;

struct TiledOptions {
    std::string file;
    double seconds = 60.0;
    double fps = 30.0;
    std::string size = "1920x1080";
    float tau = 1.0f;
    double budgetMiB = 1024.0;
    int loaders = 2;
    float altitude = -1.0f;  // world units above the ground; < 0 = 2% of the terrain's width
    std::string json;
};

double peakRssMiB() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;  // KiB on Linux
}

void runTiled(const TiledOptions& o) {
    int width = 0, height = 0;
    char x = 0;
    if (std::sscanf(o.size.c_str(), "%d%c%d", &width, &x, &height) != 3 || x != 'x' || width < 16 ||
        height < 16)
        throw UsageError(msg("tiled: --size must be WxH (at least 16x16), got '", o.size, "'"));
    const sbt::TileFile file(o.file);
    const sbt::TileFileInfo& info = file.info();
    sbt::TileCache cache(
        file, {.budgetBytes = uint64_t(o.budgetMiB * 1048576.0), .loaderThreads = o.loaders});
    sbt::TiledRefiner refiner(cache);

    // The flight: along the diagonal of the real samples, 5% in from each end.
    const double w = double(info.width - 1) * info.spacingX,
                 d = double(info.height - 1) * info.spacingZ;
    const float altitude = o.altitude >= 0.0f ? o.altitude : float(0.02 * std::max(w, d));
    const int frames = std::max(2, int(std::lround(o.seconds * o.fps)));
    const double period = 1.0 / o.fps;
    auto eyeAt = [&](double t) {
        const double s = 0.05 + 0.9 * std::clamp(t / o.seconds, 0.0, 1.0);
        return std::array<double, 2>{s * w, s * d};
    };
    // The ground under a point, from the coarse section's nearest corner (a
    // fly-through follows the relief, not the exact surface).
    const double tileX = double(1 << info.k) * info.spacingX,
                 tileZ = double(1 << info.k) * info.spacingZ;
    auto groundAt = [&](double px, double pz) {
        const int P = info.tilesPerSide();
        const int64_t ci = std::clamp<int64_t>(std::llround(px / tileX), 0, P);
        const int64_t cj = std::clamp<int64_t>(std::llround(pz / tileZ), 0, P);
        return double(file.corner(ci << info.k, cj << info.k).height) * info.verticalScale;
    };
    std::vector<double> refineMs, beginMs;
    std::vector<int> coarse;
    std::vector<int64_t> triangles;
    double firstFrameMs = 0.0;
    sbt::TiledMesh mesh;
    const auto start = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f) {
        const double t = f * period;
        const auto [ex, ez] = eyeAt(t);
        const auto [ax, az] = eyeAt(t + 1.0);
        const auto [lx, lz] = eyeAt(t + 2.0);
        const double ey = groundAt(ex, ez) + altitude;
        const std::array<float, 3> eye{float(ex), float(ey), float(ez)};
        const std::array<float, 3> ahead{float(ax), float(groundAt(ax, az) + altitude), float(az)};
        const std::array<float, 3> target{float(lx), float(groundAt(lx, lz)), float(lz)};
        const sbt::ViewParams view =
            sbt::lookAtView(eye, target, 0.8f, float(width) / float(height), float(height), 1.0f,
                            float(4.0 * std::max(w, d)), o.tau, true);
        Stopwatch frame;
        cache.beginFrame();
        beginMs.push_back(frame.ms());
        Stopwatch refine;
        refiner.refineView(view, mesh);
        refineMs.push_back(refine.ms());
        cache.wantForView(refiner, eye, ahead);
        coarse.push_back(mesh.coarseTiles);
        triangles.push_back(mesh.triangleCount);
        if (f == 0) firstFrameMs = kProgramStart.ms();
        std::this_thread::sleep_until(start + std::chrono::duration<double>((f + 1) * period));
    }
    const sbt::TileCacheStats st = cache.stats();
    auto q = [](std::vector<double> v, double p) { return quantile(std::move(v), p); };
    std::vector<double> coarseD(coarse.begin(), coarse.end());
    std::vector<double> trisD(triangles.begin(), triangles.end());
    const double rss = peakRssMiB();
    std::printf("tiled terrain          %lld x %lld samples, %d^2 tiles of %d^2 (%s)\n",
                (long long)info.width, (long long)info.height, info.tilesPerSide(), info.tileSide(),
                o.file.c_str());
    std::printf("flight                 %d frames at %g fps, %dx%d, tau %g px, %g above ground\n",
                frames, o.fps, width, height, o.tau, altitude);
    std::printf("first frame            %.0f ms after the program's start\n", firstFrameMs);
    std::printf("refine + strip         median %.2f ms, p99 %.2f ms\n", q(refineMs, 0.5),
                q(refineMs, 0.99));
    std::printf("triangles              median %.0f\n", q(trisD, 0.5));
    std::printf("tiles drawn coarse     median %.0f, p99 %.0f, last frame %d\n", q(coarseD, 0.5),
                q(coarseD, 0.99), coarse.back());
    std::printf("beginFrame             longest %.2f ms (never waits for a read)\n",
                *std::max_element(beginMs.begin(), beginMs.end()));
    std::printf("tiles read             %lld (%.1f MiB of the file), %lld evicted, %lld dropped\n",
                (long long)st.tilesRead, double(st.bytesRead) / 1048576.0, (long long)st.evicted,
                (long long)st.dropped);
    std::printf("cache                  peak %.1f MiB of %.0f MiB\n",
                double(st.peakBytes) / 1048576.0, o.budgetMiB);
    std::printf("peak RSS               %.1f MiB (whole process)\n", rss);
    if (!o.json.empty()) {
        nlohmann::json j = {
            {"file", o.file},
            {"width", info.width},
            {"height", info.height},
            {"tile_levels", info.k},
            {"frames", frames},
            {"fps", o.fps},
            {"size", {width, height}},
            {"tau", o.tau},
            {"altitude", altitude},
            {"first_frame_ms", firstFrameMs},
            {"refine_ms", {{"median", q(refineMs, 0.5)}, {"p99", q(refineMs, 0.99)}}},
            {"triangles_median", q(trisD, 0.5)},
            {"coarse_tiles",
             {{"median", q(coarseD, 0.5)}, {"p99", q(coarseD, 0.99)}, {"last", coarse.back()}}},
            {"begin_frame_ms_max", *std::max_element(beginMs.begin(), beginMs.end())},
            {"tiles_read", st.tilesRead},
            {"bytes_read", st.bytesRead},
            {"evicted", st.evicted},
            {"dropped", st.dropped},
            {"cache_peak_bytes", st.peakBytes},
            {"budget_bytes", uint64_t(o.budgetMiB * 1048576.0)},
            {"peak_rss_mib", rss},
        };
        writeFileAtomic(o.json, j.dump(2) + "\n");
    }
}

}  // namespace

void addTiledCommand(CLI::App& app) {
    auto o = std::make_shared<TiledOptions>();
    CLI::App* cmd = app.add_subcommand(
        "tiled", "Fly over a tiled terrain (.sierra): refinement and streaming, no GL");
    cmd->add_option("file", o->file, "The tile file (sierra-tile build)")
        ->type_name("T.sierra")
        ->required();
    cmd->add_option("--seconds", o->seconds, "Length of the flight")
        ->check(CLI::Range(0.1, 3600.0))
        ->capture_default_str();
    cmd->add_option("--fps", o->fps, "Frames a second the flight is paced at")
        ->check(CLI::Range(1.0, 1000.0))
        ->capture_default_str();
    cmd->add_option("--size", o->size, "Viewport")->type_name("WxH")->capture_default_str();
    cmd->add_option("--tau", o->tau, "Screen-space error threshold, pixels")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    cmd->add_option("--memory-budget", o->budgetMiB, "Tile cache, MiB")
        ->type_name("MIB")
        ->check(CLI::Range(1.0, 1048576.0))
        ->capture_default_str();
    cmd->add_option("--loaders", o->loaders, "Loader threads")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    cmd->add_option("--altitude", o->altitude,
                    "Height above the ground, world units (default: 2% of the terrain's width)")
        ->type_name("M");
    cmd->add_option("--json", o->json, "Write the figures as JSON")->type_name("FILE");
    cmd->callback([o] {
        if (!o->json.empty()) ensureWritableLocation(o->json);
        runTiled(*o);
    });
}

}  // namespace sierra::apps
