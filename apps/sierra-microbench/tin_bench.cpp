// Micro-benchmarks of greedy insertion (the TIN): items_per_second is points
// inserted per second, on the diamond-square fractal (seed 1) at 1, 4 and 16
// megapixels and at 1% and 0.1% relative vertical error.
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/tin/Tin.h>

#include <benchmark/benchmark.h>

#include <map>
#include <memory>

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

}  // namespace
