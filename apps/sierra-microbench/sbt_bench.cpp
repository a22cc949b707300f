// Micro-benchmarks of the SBT CPU stages: the error pass, fixed-error
// refinement + strip emission, view-dependent refinement. items_per_second is
// output triangles per second (grid samples per second for the error pass).
#include <sierra/core/Parallel.h>
#include <sierra/core/Timer.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/TileFile.h>
#include <sierra/sbt/TiledRefiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/terrain/GridReader.h>

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

namespace sbt = sierra::sbt;

struct Terrain {
    sierra::terrain::Heightfield field;
    sbt::VertexErrors errors;
};

// One fractal per size, built once (roughness 1, seed 1, heights scaled to a
// relief of about a tenth of the extent).
const Terrain& terrain(int size) {
    static std::map<int, std::unique_ptr<Terrain>> cache;
    auto& slot = cache[size];
    if (!slot) {
        slot = std::make_unique<Terrain>();
        slot->field =
            sierra::terrain::generateDiamondSquare({.size = size, .seed = 1, .roughness = 1.0f});
        auto [lo, hi] = slot->field.range();
        slot->field.setVerticalScale(0.1f * float(size - 1) / std::max(1e-6f, hi - lo));
        slot->errors = sbt::computeVertexErrors(slot->field);
    }
    return *slot;
}

void BM_ErrorPass(benchmark::State& state) {
    const int size = int(state.range(0));
    const int threads = int(state.range(1));
    const Terrain& t = terrain(size);
    for (auto _ : state) {
        auto ve = sbt::computeVertexErrors(t.field, threads);
        benchmark::DoNotOptimize(ve.error.data());
    }
    state.SetItemsProcessed(state.iterations() * t.field.sampleCount());
    state.counters["threads"] = threads;
}
BENCHMARK(BM_ErrorPass)
    ->ArgsProduct({{513, 1025, 2049}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// A refiner and its mesh, kept while Google Benchmark runs one benchmark, as a
// renderer keeps its refiner from frame to frame: Google Benchmark calls a
// benchmark's function several times (to find an iteration count, then once
// per repetition), and a refiner made anew each call would grow its buffers
// and fault their pages in inside the timed loop, where the adaptive default
// (threads 0) would count those refinements among what it learns. Keyed by
// the benchmark (`name` and its first `argCount` arguments) and `threads`;
// those of the benchmark before are freed.
struct Kept {
    sbt::Refiner refiner;
    sbt::StripMesh mesh;
    int threads;
    bool fresh = true;  // not refined yet
    size_t next = 0;    // the next of a benchmark's views
    Kept(const Terrain& t, int threads)
        : refiner(t.field, t.errors, {.threads = threads}), threads(threads) {}
    // Refines a fresh refiner untimed (`refine()` writes `mesh`) until it has
    // grown its buffers: once, or four times for the default, whose first
    // refinements go both ways.
    template <typename Refine>
    void warm(Refine refine) {
        for (int w = 0; fresh && w < (threads == 0 ? 4 : 1); ++w) refine();
        fresh = false;
    }
};

Kept& kept(const benchmark::State& state, const char* name, int argCount, const Terrain& t,
           int threads) {
    static std::string running;
    static std::map<int, std::unique_ptr<Kept>> live;
    std::string key = name;
    for (int k = 0; k < argCount; ++k) key.append("/").append(std::to_string(state.range(k)));
    if (key != running) {
        live.clear();
        running = key;
    }
    std::unique_ptr<Kept>& slot = live[threads];
    if (!slot) slot = std::make_unique<Kept>(t, threads);
    return *slot;
}

// Warms a fresh refiner (Kept::warm), then times `refine` (which writes k's
// mesh with k's refiner, in view mode or not) and reports triangles per second.
// Google Benchmark's time is the mean of a repetition's refinements, which a
// few slow ones (a helper thread preempted on a shared machine) pull up;
// `median_ms` is the median of the single refinements, timed one by one.
template <typename Refine>
void measureRefinement(benchmark::State& state, Kept& k, bool view, Refine refine) {
    sbt::StripMesh& mesh = k.mesh;
    k.warm([&] { refine(mesh); });
    const sbt::ThreadChoice& choice = k.refiner.threadChoice(view);
    const int64_t serialBefore = choice.samples[0], parallelBefore = choice.samples[1];
    std::vector<double> seconds;
    seconds.reserve(size_t(state.max_iterations));
    int64_t triangles = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        refine(mesh);
        benchmark::DoNotOptimize(mesh.indices.data());
        seconds.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        triangles += mesh.triangleCount;
    }
    if (seconds.empty()) return;
    state.counters["median_ms"] = 1e3 * sierra::median(seconds);
    if (k.threads == 0) {
        // the share of the timed refinements the default ran on one thread
        const int64_t serial = choice.samples[0] - serialBefore,
                      parallel = choice.samples[1] - parallelBefore;
        state.counters["one_thread"] =
            serial + parallel > 0 ? double(serial) / double(serial + parallel) : 0.0;
        state.SetLabel("default: adaptive, up to " + std::to_string(sierra::defaultThreadCount()) +
                       " threads");
    }
    // a moving view's triangles differ from refinement to refinement: the
    // mean of the timed ones
    state.SetItemsProcessed(triangles);
    state.counters["triangles"] = double(triangles) / double(seconds.size());
    state.counters["idx_per_tri"] = mesh.indicesPerTriangle();
    state.counters["threads"] = k.threads;
}

// Arg 1: epsilon as a fraction of the terrain's relief in ten-thousandths
// (5 = 0.05%, 100 = 1%; -1 = full grid). Arg 2: threads (0 = the adaptive
// default, sbt::ThreadChoice).
void BM_RefineFixed(benchmark::State& state) {
    const int size = int(state.range(0));
    const int threads = int(state.range(2));
    const Terrain& t = terrain(size);
    auto [lo, hi] = t.field.range();
    const float relief = (hi - lo) * t.field.verticalScale();
    const float eps = state.range(1) < 0 ? -1.0f : relief * float(state.range(1)) / 10000.0f;
    Kept& k = kept(state, "fixed", 3, t, threads);
    measureRefinement(state, k, false,
                      [&](sbt::StripMesh& mesh) { k.refiner.refineFixed(eps, mesh); });
}
BENCHMARK(BM_RefineFixed)
    ->ArgsProduct({{1025, 2049}, {-1, 0, 5, 10, 20, 50, 100}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// A camera 1/8 of the extent above the middle of the south edge, looking at the
// centre, 1920x1080, 60 degree vertical field of view, tau 1 px.
void BM_RefineView(benchmark::State& state) {
    const int size = int(state.range(0));
    const int threads = int(state.range(1));
    const bool cull = state.range(2) != 0;
    const Terrain& t = terrain(size);
    const float extent = float(size - 1);
    sbt::ViewParams vp;
    vp.eye = {0.5f * extent, 0.125f * extent + t.field.worldHeight(size / 2, 0), -0.05f * extent};
    vp.lambda = sbt::projectionLambda(1080.0f, 1.0471976f);
    vp.tau = 1.0f;
    vp.cull = cull;
    // frustum: looking towards +z and slightly down; planes through the eye
    const float aspect = 16.0f / 9.0f, tanY = std::tan(0.5f * 1.0471976f), tanX = tanY * aspect;
    const float pitch = -0.35f, cp = std::cos(pitch), sp = std::sin(pitch);
    auto rot = [&](float x, float y, float z) {  // camera (x right, y up, z forward) to world
        return std::array<float, 3>{x, y * cp + z * sp, -y * sp + z * cp};
    };
    auto plane = [&](std::array<float, 3> nrm) {
        float len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        for (float& c : nrm) c /= len;
        return sbt::Plane{nrm[0], nrm[1], nrm[2],
                          -(nrm[0] * vp.eye[0] + nrm[1] * vp.eye[1] + nrm[2] * vp.eye[2])};
    };
    vp.planes = {plane(rot(1, 0, tanX)),  plane(rot(-1, 0, tanX)), plane(rot(0, 1, tanY)),
                 plane(rot(0, -1, tanY)), plane(rot(0, 0, 1)),     plane(rot(0, 0, 1))};
    // far plane: inside while the distance along the view is below 4 extents
    vp.planes[5] = sbt::Plane{-vp.planes[4].a, -vp.planes[4].b, -vp.planes[4].c,
                              -vp.planes[4].d + 4.0f * extent};
    Kept& k = kept(state, "view", 3, t, threads);
    measureRefinement(state, k, true,
                      [&](sbt::StripMesh& mesh) { k.refiner.refineView(vp, mesh); });
}
BENCHMARK(BM_RefineView)
    ->ArgsProduct({{2049}, {0, 1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// A rough fractal (Hurst exponent H = range(1) / 10) for the renderer's view:
// heights scaled so the relief is 20% of the extent (the renderer's automatic
// vertical scale), built once per (size, H).
const Terrain& roughTerrain(int size, int hurstTenths) {
    static std::map<std::pair<int, int>, std::unique_ptr<Terrain>> cache;
    auto& slot = cache[{size, hurstTenths}];
    if (!slot) {
        slot = std::make_unique<Terrain>();
        slot->field = sierra::terrain::generateDiamondSquare(
            {.size = size, .seed = 1, .hurst = float(hurstTenths) / 10.0f});
        auto [lo, hi] = slot->field.range();
        slot->field.setVerticalScale(0.2f * float(size - 1) / std::max(1e-6f, hi - lo));
        slot->errors = sbt::computeVertexErrors(slot->field);
    }
    return *slot;
}

// The first camera of the renderer's orbit path (render/Camera.cpp orbitPath):
// 0.9 extents from the centre towards the south-west, 0.3 extents above the
// highest point, looking at the centre at a quarter of the height range;
// 45 degree vertical field of view, 1920x1080, near 1e-3 and far 4 extents.
// `degrees` moves the camera along the orbit.
sbt::ViewParams orbitView(const Terrain& t, float tau, bool cull, float degrees = 135.0f) {
    const float extent = float(t.field.width() - 1) * t.field.spacingX();
    auto [lo, hi] = t.field.range();
    const float vs = t.field.verticalScale();
    const glm::vec3 centre{0.5f * extent, 0.5f * (lo + hi) * vs, 0.5f * extent};
    const float a = glm::radians(degrees);
    const glm::vec3 eye{centre.x + 0.9f * extent * std::cos(a), hi * vs + 0.3f * extent,
                        centre.z + 0.9f * extent * std::sin(a)};
    const glm::vec3 target{centre.x, lo * vs + 0.25f * (hi - lo) * vs, centre.z};
    return sbt::lookAtView({eye.x, eye.y, eye.z}, {target.x, target.y, target.z},
                           glm::radians(45.0f), 1920.0f / 1080.0f, 1080.0f, extent * 1e-3f,
                           extent * 4.0f, tau, cull);
}

// View-dependent refinement + strip of a rough 2049^2 fractal from the orbit
// camera at tau = 1 px. Args: Hurst exponent in tenths, threads, culling.
void BM_RefineOrbit(benchmark::State& state) {
    const Terrain& t = roughTerrain(2049, int(state.range(0)));
    const int threads = int(state.range(1));
    const sbt::ViewParams view = orbitView(t, 1.0f, state.range(2) != 0);
    Kept& k = kept(state, "orbit", 3, t, threads);
    measureRefinement(state, k, true,
                      [&](sbt::StripMesh& mesh) { k.refiner.refineView(view, mesh); });
}
BENCHMARK(BM_RefineOrbit)
    ->ArgsProduct({{8}, {0, 1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The same camera moving along the orbit, over 48 views that repeat: no two
// consecutive refinements make the same decisions, so the branch predictor
// and the caches see a new view each time. Args: Hurst exponent in tenths,
// threads, the step between views in tenths of a degree: 5 (half a degree,
// as a renderer's camera moves from frame to frame) or 150 (15 degrees, as
// the 24 frames of `sierra-bench frames --path orbit --frames 24`, whose
// views share little: a refinement learns nothing from the one before).
void BM_RefineOrbitMoving(benchmark::State& state) {
    const Terrain& t = roughTerrain(2049, int(state.range(0)));
    const int threads = int(state.range(1));
    const float step = 0.1f * float(state.range(2));
    std::vector<sbt::ViewParams> views;
    for (int k = 0; k < 48; ++k)
        views.push_back(orbitView(t, 1.0f, true, 135.0f + step * float(k)));
    Kept& k = kept(state, "orbit moving", 3, t, threads);
    measureRefinement(state, k, true, [&](sbt::StripMesh& mesh) {
        k.refiner.refineView(views[k.next], mesh);
        k.next = (k.next + 1) % views.size();
    });
}
BENCHMARK(BM_RefineOrbitMoving)
    ->ArgsProduct({{8}, {0, 1, 2}, {5, 150}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The adaptive default against one thread, refinement by refinement: each
// iteration refines the same case with a default refiner and a one-thread
// refiner, in turn (which goes first alternates), so a slow spell of a shared
// machine, which lasts seconds to minutes, weighs on both alike. Reports
// default_ms and one_ms (medians of the single refinements), their ratio
// `default_per_one` (< 1: the default is faster), the ratio of the means
// (`default_per_one_mean`, which the default's probes of the other way and
// its preempted helpers raise), and the share of the default's refinements
// that ran on one thread. Google Benchmark's own time is that of a pair.
// Args: case (0: fixed 1025^2 full grid, 1: fixed 2049^2 full grid, 2: fixed
// 1025^2 at 0.05% of the relief, 3: fixed 2049^2 at 0.05%, 4: the rough
// orbit view, 5: the rough orbit moving 15 degrees per refinement).
void BM_RefineDefaultAgainstOne(benchmark::State& state) {
    const int which = int(state.range(0));
    const bool view = which >= 4;
    const Terrain& t = view ? roughTerrain(2049, 8) : terrain(which % 2 ? 2049 : 1025);
    Kept* pair[2] = {&kept(state, "default against one", 1, t, 0),
                     &kept(state, "default against one", 1, t, 1)};
    auto [lo, hi] = t.field.range();
    const float eps = which < 2 ? -1.0f : (hi - lo) * t.field.verticalScale() * 5.0f / 10000.0f;
    std::vector<sbt::ViewParams> views;
    for (int k = 0; k < (which == 5 ? 48 : 1); ++k)
        views.push_back(orbitView(t, 1.0f, true, 135.0f + 15.0f * float(k)));
    std::vector<double> seconds[2];
    auto refine = [&](int k) {
        Kept& one = *pair[k];
        const auto start = std::chrono::steady_clock::now();
        if (view) {  // both refine the same view in a pair
            one.refiner.refineView(views[one.next % views.size()], one.mesh);
        } else {
            one.refiner.refineFixed(eps, one.mesh);
        }
        benchmark::DoNotOptimize(one.mesh.indices.data());
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    for (int k = 0; k < 2; ++k) pair[k]->warm([&] { refine(k); });
    const sbt::ThreadChoice& learned = pair[0]->refiner.threadChoice(view);
    const int64_t serialBefore = learned.samples[0], parallelBefore = learned.samples[1];
    int64_t pairs = 0;
    for (auto _ : state) {
        const int first = int(pairs++ & 1);
        seconds[first].push_back(refine(first));
        seconds[1 - first].push_back(refine(1 - first));
        pair[0]->next = ++pair[1]->next;
    }
    if (pairs == 0) return;
    // the last pair refined the same case: the thread count never changes the mesh
    if (pair[0]->mesh.indices != pair[1]->mesh.indices) {
        state.SkipWithError("the default and one thread made different meshes");
        return;
    }
    double middle[2], mean[2];
    for (int k = 0; k < 2; ++k) {
        mean[k] = 0.0;
        for (double x : seconds[k]) mean[k] += x / double(seconds[k].size());
        middle[k] = sierra::median(seconds[k]);
    }
    state.counters["default_ms"] = 1e3 * middle[0];
    state.counters["one_ms"] = 1e3 * middle[1];
    state.counters["default_per_one"] = middle[0] / middle[1];
    state.counters["default_per_one_mean"] = mean[0] / mean[1];
    const int64_t serial = learned.samples[0] - serialBefore,
                  parallel = learned.samples[1] - parallelBefore;
    state.counters["one_thread"] =
        serial + parallel > 0 ? double(serial) / double(serial + parallel) : 0.0;
    state.counters["triangles"] = double(pair[1]->mesh.triangleCount);
    // what the default's choice rests on at the end: its medians of the
    // recent refinements each way, in ms per refinement of this size
    for (int way = 0; way < 2; ++way)
        if (learned.samples[way] > 1)
            state.counters[way ? "learned_several_ms" : "learned_one_ms"] =
                1e3 * learned.estimate(way) * double(pair[1]->mesh.triangleCount);
}
BENCHMARK(BM_RefineDefaultAgainstOne)
    ->DenseRange(0, 5)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The same through the double-precision baseline (Refiner::refineViewReference).
void BM_RefineOrbitReference(benchmark::State& state) {
    const Terrain& t = roughTerrain(2049, int(state.range(0)));
    const int threads = int(state.range(1));
    const sbt::ViewParams view = orbitView(t, 1.0f, state.range(2) != 0);
    Kept& k = kept(state, "orbit reference", 3, t, threads);
    measureRefinement(state, k, true,
                      [&](sbt::StripMesh& mesh) { k.refiner.refineViewReference(view, mesh); });
}
BENCHMARK(BM_RefineOrbitReference)
    ->ArgsProduct({{8}, {1}, {1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Refinement over tiles against the in-memory path, the same 48 views of the
// moving orbit (half a degree apart) over the rough 2049^2 fractal, every tile
// resident, one thread: Arg 0 the in-memory refineView, 1 the in-memory
// reference walk (double, the tiled walk's decisions), 2 the tiled walk over
// 257^2 tiles (k = 8), 3 the same over a tile file of the terrain read
// whole (sbt::FileTiles, packed tiles). The counters give the 99th percentile of the
// refinements' times; the target is tiled p99 at most 1.5x the in-memory p99.
void BM_TiledRefine(benchmark::State& state) {
    const Terrain& t = roughTerrain(2049, 8);
    const int way = int(state.range(0));
    std::vector<sbt::ViewParams> views;
    for (int k = 0; k < 48; ++k)
        views.push_back(orbitView(t, 1.0f, true, 135.0f + 0.5f * float(k)));
    static sbt::InMemoryTiles tiles(t.field, t.errors, 8);
    static sbt::TiledRefiner tiled(tiles);
    // The tile file: built once per run into the temporary directory.
    static std::unique_ptr<sbt::TileFile> file;
    static std::unique_ptr<sbt::FileTiles> fileTiles;
    static std::unique_ptr<sbt::TiledRefiner> fileTiled;
    if (way == 3 && !file) {
        const char* tmp = std::getenv("TMPDIR");
        const std::string path =
            std::string(tmp && *tmp ? tmp : "/tmp") + "/sierra_bench_tiled.sierra";
        sbt::buildTileFile(*sierra::terrain::memoryGridReader(t.field), path,
                           {.k = 8,
                            .heights = sbt::TileHeights::Float32,
                            .verticalScale = t.field.verticalScale()});
        file = std::make_unique<sbt::TileFile>(path);
        std::remove(path.c_str());  // the open descriptor keeps it readable
        fileTiles = std::make_unique<sbt::FileTiles>(*file);
        fileTiles->loadAll(16);
        fileTiled = std::make_unique<sbt::TiledRefiner>(*fileTiles);
    }
    sbt::Refiner refiner(t.field, t.errors, {.threads = 1});
    sbt::StripMesh mesh;
    sbt::TiledMesh tiledMesh;
    // Once before timing: the in-memory path builds its view keys on its first call.
    refiner.refineView(views[0], mesh);
    std::vector<double> seconds;
    size_t next = 0;
    int64_t triangles = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        if (way == 0) refiner.refineView(views[next], mesh);
        if (way == 1) refiner.refineViewReference(views[next], mesh);
        if (way == 2) tiled.refineView(views[next], tiledMesh);
        if (way == 3) fileTiled->refineView(views[next], tiledMesh);
        seconds.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        triangles += way >= 2 ? tiledMesh.triangleCount : mesh.triangleCount;
        next = (next + 1) % views.size();
    }
    std::sort(seconds.begin(), seconds.end());
    state.counters["p99_ms"] =
        1e3 * seconds[std::min(seconds.size() - 1, seconds.size() * 99 / 100)];
    state.counters["triangles"] = double(triangles) / double(seconds.size());
    static const char* kWays[] = {"in-memory refineView", "in-memory reference walk",
                                  "tiled walk, 257^2 tiles", "tiled walk over a tile file"};
    state.SetLabel(kWays[way]);
}
BENCHMARK(BM_TiledRefine)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
