// Micro-benchmarks of the curvature analysis: the 4-direction field of a
// fractal grid by each method, and line tracing. items_per_second is grid
// samples per second. Target: 2049^2 in at most 150 ms with all threads.
// And the relief fields: horizons in 16 azimuths and the sun's visibility
// (target: both together for 4097^2 in at most 2 s with all threads,
// BM_ReliefFields).
#include <sierra/analysis/Curvature.h>
#include <sierra/analysis/Lines.h>
#include <sierra/analysis/Relief.h>
#include <sierra/core/Parallel.h>
#include <sierra/terrain/DiamondSquare.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <vector>

namespace {

namespace analysis = sierra::analysis;

// One fractal per size (roughness 1, seed 1, relief about a tenth of the extent).
const sierra::terrain::Heightfield& terrain(int size) {
    static std::map<int, std::unique_ptr<sierra::terrain::Heightfield>> cache;
    auto& slot = cache[size];
    if (!slot) {
        slot = std::make_unique<sierra::terrain::Heightfield>(
            sierra::terrain::generateDiamondSquare({.size = size, .seed = 1, .roughness = 1.0f}));
        auto [lo, hi] = slot->range();
        slot->setVerticalScale(0.1f * float(size - 1) / std::max(1e-6f, hi - lo));
    }
    return *slot;
}

// Args: size, method (0..3, CurvatureMethod order), reinforcement distance,
// threads (0 = all), fresh (1: a new field every time, paying the page
// faults of its 64 MiB at 2049^2; 0: the field's storage is reused).
void BM_Curvature(benchmark::State& state) {
    const auto& field = terrain(int(state.range(0)));
    analysis::CurvatureOptions o{.method = analysis::CurvatureMethod(state.range(1)),
                                 .distance = int(state.range(2)),
                                 .threads = int(state.range(3))};
    const bool fresh = state.range(4) != 0;
    analysis::CurvatureField c;
    analysis::computeCurvature(field, o, c);
    for (auto _ : state) {
        if (fresh) {
            auto f = analysis::computeCurvature(field, o);
            benchmark::DoNotOptimize(f.values.data());
        } else {
            analysis::computeCurvature(field, o, c);
            benchmark::DoNotOptimize(c.values.data());
        }
    }
    state.SetItemsProcessed(state.iterations() * field.sampleCount());
    state.SetLabel(analysis::curvatureMethodName(o.method));
    state.counters["threads"] = o.threads > 0 ? o.threads : sierra::defaultThreadCount();
}
BENCHMARK(BM_Curvature)
    ->ArgsProduct({{2049}, {0, 1, 2, 3}, {1}, {0, 1}, {0}})
    ->ArgsProduct({{2049}, {1, 2, 3}, {2}, {0}, {0}})
    ->Args({2049, 1, 1, 0, 1})
    ->Args({513, 1, 2, 0, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Line tracing (arg 1: 0 discrete, 1 blended) of a three-normal field
// (distance 2, scale 4) at a threshold that passes the top fifth of the vertices.
void BM_TraceLines(benchmark::State& state) {
    const auto& field = terrain(int(state.range(0)));
    auto c = analysis::computeCurvature(
        field, {.method = analysis::CurvatureMethod::ThreeNormal, .distance = 2, .scale = 4.0f});
    std::vector<float> strengths;
    for (int j = 0; j < c.height; ++j)
        for (int i = 0; i < c.width; ++i) strengths.push_back(c.maxMagnitude(i, j));
    std::nth_element(strengths.begin(), strengths.begin() + strengths.size() * 8 / 10,
                     strengths.end());
    analysis::LineOptions o{.threshold = strengths[strengths.size() * 8 / 10],
                            .minVertices = 5,
                            .blended = state.range(1) != 0};
    size_t vertices = 0;
    for (auto _ : state) {
        auto lines = analysis::traceLines(c, o);
        vertices = lines.vertices.size();
        benchmark::DoNotOptimize(lines.vertices.data());
    }
    state.SetItemsProcessed(state.iterations() * field.sampleCount());
    state.counters["line_vertices"] = double(vertices);
}
BENCHMARK(BM_TraceLines)
    ->ArgsProduct({{1025}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Horizons in 16 azimuths (args: size, threads, 0 = all; radius in world
// units, 0 = the whole grid). items_per_second is samples times azimuths.
void BM_Horizons(benchmark::State& state) {
    const auto& field = terrain(int(state.range(0)));
    analysis::HorizonOptions o{
        .directions = 16, .radius = float(state.range(2)), .threads = int(state.range(1))};
    for (auto _ : state) {
        auto h = analysis::computeHorizons(field, o);
        benchmark::DoNotOptimize(h.angle.data());
    }
    state.SetItemsProcessed(state.iterations() * field.sampleCount() * o.directions);
    state.counters["threads"] = o.threads > 0 ? o.threads : sierra::defaultThreadCount();
}
BENCHMARK(BM_Horizons)
    ->Args({4097, 0, 0})
    ->Args({4097, 1, 0})
    ->Args({1025, 0, 0})
    ->Args({1025, 0, 100})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The sun's visibility: one sweep in its azimuth, 300 degrees (a digital
// line, not a grid axis) at altitude 20 (args: size, threads).
void BM_SunVisibility(benchmark::State& state) {
    const auto& field = terrain(int(state.range(0)));
    analysis::SunDisc sun{.azimuth = 300.0f, .altitude = 20.0f};
    analysis::HorizonOptions o{.threads = int(state.range(1))};
    for (auto _ : state) {
        auto v = analysis::sunVisibility(field, sun, o);
        benchmark::DoNotOptimize(v.data());
    }
    state.SetItemsProcessed(state.iterations() * field.sampleCount());
    state.counters["threads"] = o.threads > 0 ? o.threads : sierra::defaultThreadCount();
}
BENCHMARK(BM_SunVisibility)
    ->Args({4097, 0})
    ->Args({4097, 1})
    ->Args({1025, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The target's work: horizons in 16 azimuths plus the sun's visibility (300
// degrees, altitude 20) in one iteration (args: size, threads, 0 = all;
// what is kept: 0 every angle (computeHorizons, 1 GiB at 4097^2), 1 only the
// sky light, the terrain pass's input, from one azimuth's angles at a time).
// items_per_second is samples times the 17 sweeps.
void BM_ReliefFields(benchmark::State& state) {
    const auto& field = terrain(int(state.range(0)));
    analysis::HorizonOptions o{.directions = 16, .threads = int(state.range(1))};
    const bool stored = state.range(2) == 0;
    analysis::SunDisc sun{.azimuth = 300.0f, .altitude = 20.0f};
    for (auto _ : state) {
        if (stored) {
            auto h = analysis::computeHorizons(field, o);
            benchmark::DoNotOptimize(h.angle.data());
        } else {
            auto light = analysis::skyLight(field, o);
            benchmark::DoNotOptimize(light.data());
        }
        auto v = analysis::sunVisibility(field, sun, o);
        benchmark::DoNotOptimize(v.data());
    }
    state.SetItemsProcessed(state.iterations() * field.sampleCount() * (o.directions + 1));
    state.SetLabel(stored ? "every angle" : "sky light");
    state.counters["threads"] = o.threads > 0 ? o.threads : sierra::defaultThreadCount();
}
BENCHMARK(BM_ReliefFields)
    ->Args({4097, 0, 0})
    ->Args({4097, 0, 1})
    ->Args({4097, 1, 1})
    ->Args({1025, 0, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
