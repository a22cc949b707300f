// Micro-benchmarks of greedy insertion (the TIN): items_per_second is points
// inserted per second, on the diamond-square fractal (seed 1) at 1, 4 and 16
// megapixels and at 1% and 0.1% relative vertical error.
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/tin/Tin.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <random>

namespace {

const sierra::terrain::Heightfield& fractal(int size) {
    static std::map<int, std::unique_ptr<sierra::terrain::Heightfield>> cache;
    auto& slot = cache[size];
    if (!slot)
        slot = std::make_unique<sierra::terrain::Heightfield>(
            sierra::terrain::generateDiamondSquare({.size = size, .seed = 1}));
    return *slot;
}

// Arguments: grid size, relative error in units of 0.1%.
void BM_GreedyInsertion(benchmark::State& state) {
    const auto& field = fractal(int(state.range(0)));
    const double rel = double(state.range(1)) * 0.001;
    int64_t inserted = 0, triangles = 0;
    for (auto _ : state) {
        auto result = sierra::tin::buildTin(field, {}, {.maxErrorRel = rel});
        inserted += result.stats.inserted;
        triangles = int64_t(result.mesh.triangles.size());
        benchmark::DoNotOptimize(result.mesh.triangles.data());
    }
    state.SetItemsProcessed(inserted);
    state.counters["triangles"] = double(triangles);
    state.counters["rel_error"] = rel;
}
BENCHMARK(BM_GreedyInsertion)
    ->ArgsProduct({{1025, 2049, 4097}, {10, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// The cost of zone borderlines: six wavy polylines across the 1025² fractal (a
// vertex every 8 samples, 768 segments) against no borderlines, at the same
// triangle budget. Counters: max and RMS error of each and their ratios
// (zones / plain); the time is of the constrained run.
void BM_ZoneCost(benchmark::State& state) {
    const auto& field = fractal(1025);
    const int64_t budget = state.range(0);
    sierra::tin::Constraints c;
    std::mt19937 rng(1);
    for (int k = 0; k < 6; ++k) {
        const int first = int(c.vertices.size());
        for (int x = 0; x <= 1024; x += 8)
            c.vertices.push_back(
                {double(x), 80.0 + k * 150 + 30 * std::sin(x / 60.0 + k) +
                                std::uniform_real_distribution<double>(-2, 2)(rng)});
        for (int i = first; i + 1 < int(c.vertices.size()); ++i)
            c.segments.push_back({i, i + 1, k + 1, k});
    }
    const auto plain = sierra::tin::measureError(
        sierra::tin::buildTin(field, {}, {.maxTriangles = budget}).mesh, field);
    sierra::tin::ErrorStats zoned;
    for (auto _ : state) {
        auto result = sierra::tin::buildTin(field, c, {.maxTriangles = budget});
        state.PauseTiming();
        zoned = sierra::tin::measureError(result.mesh, field);
        state.ResumeTiming();
    }
    state.counters["plain_max"] = plain.maxError;
    state.counters["plain_rms"] = plain.rmsError;
    state.counters["zones_max"] = zoned.maxError;
    state.counters["zones_rms"] = zoned.rmsError;
    state.counters["ratio_max"] = zoned.maxError / plain.maxError;
    state.counters["ratio_rms"] = zoned.rmsError / plain.rmsError;
}
BENCHMARK(BM_ZoneCost)
    ->Arg(20000)
    ->Arg(100000)
    ->Arg(300000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
