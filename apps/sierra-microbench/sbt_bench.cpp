// Micro-benchmarks of the SBT CPU stages: the error pass, fixed-error
// refinement + strip emission, view-dependent refinement. items_per_second is
// output triangles per second (grid samples per second for the error pass).
#include <sierra/core/Parallel.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/DiamondSquare.h>

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
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

// Times `refine` (which writes one mesh with `refiner`, in view mode or not)
// after a first call that grows the buffers, and reports triangles per second.
// Google Benchmark's time is the mean of a repetition's refinements, which a
// few slow ones (a helper thread preempted on a shared machine) pull up;
// `median_ms` is the median of the single refinements, timed one by one.
// What the adaptive default (threads 0) has learned is carried from one run of
// the benchmark to the next (its repetitions build a refiner each), as a
// renderer's refiner keeps it from frame to frame.
// `name` and the benchmark's `argCount` arguments name the benchmark.
template <typename Refine>
void measureRefinement(benchmark::State& state, int threads, sbt::Refiner& refiner, bool view,
                       const char* name, int argCount, Refine refine) {
    static std::map<std::string, sbt::ThreadChoice> learned;
    sbt::StripMesh mesh;
    refine(mesh);
    std::string key = name;
    for (int k = 0; k < argCount; ++k) key.append("/").append(std::to_string(state.range(k)));
    sbt::ThreadChoice& kept = learned[key];
    refiner.threadChoice(view) = kept;
    const int64_t serialBefore = kept.samples[0], parallelBefore = kept.samples[1];
    std::vector<double> seconds;
    seconds.reserve(size_t(state.max_iterations));
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        refine(mesh);
        benchmark::DoNotOptimize(mesh.indices.data());
        seconds.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    if (!seconds.empty()) {
        auto mid = seconds.begin() + ptrdiff_t(seconds.size() / 2);
        std::nth_element(seconds.begin(), mid, seconds.end());
        double median = *mid;
        if (seconds.size() % 2 == 0)
            median = 0.5 * (median + *std::max_element(seconds.begin(), mid));
        state.counters["median_ms"] = 1e3 * median;
    }
    kept = refiner.threadChoice(view);
    if (threads == 0) {
        // the share of the timed refinements the default ran on one thread
        const int64_t serial = kept.samples[0] - serialBefore,
                      parallel = kept.samples[1] - parallelBefore;
        state.counters["one_thread"] =
            serial + parallel > 0 ? double(serial) / double(serial + parallel) : 0.0;
    }
    state.SetItemsProcessed(state.iterations() * mesh.triangleCount);
    state.counters["triangles"] = double(mesh.triangleCount);
    state.counters["idx_per_tri"] = mesh.indicesPerTriangle();
    state.counters["threads"] = threads;
    if (threads == 0)
        state.SetLabel("default: adaptive, up to " + std::to_string(sierra::defaultThreadCount()) +
                       " threads");
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
    sbt::Refiner refiner(t.field, t.errors, {.threads = threads});
    measureRefinement(state, threads, refiner, false, "fixed", 3,
                      [&](sbt::StripMesh& mesh) { refiner.refineFixed(eps, mesh); });
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
    sbt::Refiner refiner(t.field, t.errors, {.threads = threads});
    measureRefinement(state, threads, refiner, true, "view", 3,
                      [&](sbt::StripMesh& mesh) { refiner.refineView(vp, mesh); });
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
    sbt::Refiner refiner(t.field, t.errors, {.threads = threads});
    measureRefinement(state, threads, refiner, true, "orbit", 3,
                      [&](sbt::StripMesh& mesh) { refiner.refineView(view, mesh); });
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
    sbt::Refiner refiner(t.field, t.errors, {.threads = threads});
    size_t next = 0;
    int64_t triangles = 0;
    measureRefinement(state, threads, refiner, true, "orbit moving", 3, [&](sbt::StripMesh& mesh) {
        refiner.refineView(views[next], mesh);
        next = (next + 1) % views.size();
        triangles += mesh.triangleCount;
    });
    // measureRefinement counts the last view's triangles per refinement; the
    // views differ, so the rate is the mean over those made.
    const int64_t refinements = int64_t(state.iterations()) + 1;
    state.SetItemsProcessed(triangles * state.iterations() / refinements);
    state.counters["triangles"] = double(triangles) / double(refinements);
}
BENCHMARK(BM_RefineOrbitMoving)
    ->ArgsProduct({{8}, {0, 1, 2}, {5, 150}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The same through the double-precision baseline (Refiner::refineViewReference).
void BM_RefineOrbitReference(benchmark::State& state) {
    const Terrain& t = roughTerrain(2049, int(state.range(0)));
    const int threads = int(state.range(1));
    const sbt::ViewParams view = orbitView(t, 1.0f, state.range(2) != 0);
    sbt::Refiner refiner(t.field, t.errors, {.threads = threads});
    measureRefinement(state, threads, refiner, true, "orbit reference", 3,
                      [&](sbt::StripMesh& mesh) { refiner.refineViewReference(view, mesh); });
}
BENCHMARK(BM_RefineOrbitReference)
    ->ArgsProduct({{8}, {1}, {1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
