// Micro-benchmarks of the zones stages on a 2048x2048 zone map: vectorising
// (rules 1-3), the distance-to-border field, and both together (the target:
// under 1 s on one core). The map is the auto-zoning of a 2049^2 diamond-square
// terrain (seed 1, relief 20% of the extent as the renderer shows it) cut to
// 2048^2; arg 0 = touching layout, 1 = Figure 1 borderlines drawn between the zones.
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/zones/BorderField.h>
#include <sierra/zones/Borderlines.h>
#include <sierra/zones/Tiles.h>

#include <benchmark/benchmark.h>

#include <map>
#include <memory>

namespace {

namespace zones = sierra::zones;

const zones::Palette& palette() {
    static zones::Palette p = [] {
        zones::Palette q;
        for (const std::string& name : zones::tileNames())
            q.surfaces.push_back(
                {name, zones::Colour(0x204060 + 0x101010 * q.surfaces.size()), "", 16.0f, 0.5f});
        return q;
    }();
    return p;
}

const zones::ZoneMap& zoneMap(int layout) {
    static std::map<int, std::unique_ptr<zones::ZoneMap>> cache;
    auto& slot = cache[layout];
    if (!slot) {
        auto field = sierra::terrain::generateDiamondSquare({.size = 2049, .seed = 1});
        auto [lo, hi] = field.range();
        field.setVerticalScale(0.2f * 2048.0f / (hi - lo));
        zones::ZoneMap full = zones::autoZones(field, palette());
        zones::ZoneMap map;
        map.width = map.height = 2048;
        map.ids.resize(size_t(2048) * 2048);
        for (int y = 0; y < 2048; ++y)
            for (int x = 0; x < 2048; ++x) map.ids[size_t(y) * 2048 + size_t(x)] = full.at(x, y);
        slot = std::make_unique<zones::ZoneMap>(layout ? zones::drawBorderlines(map) : map);
    }
    return *slot;
}

void BM_ZonesVectorise(benchmark::State& state) {
    const auto& map = zoneMap(int(state.range(0)));
    size_t edges = 0;
    for (auto _ : state) {
        auto lines = zones::buildBorderlines(map, palette(), {.epsilon = 0.5});
        edges = lines.edges.size();
        benchmark::DoNotOptimize(lines.vertices.data());
    }
    state.counters["edges"] = double(edges);
}
BENCHMARK(BM_ZonesVectorise)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_ZonesBorderField(benchmark::State& state) {
    auto lines = zones::buildBorderlines(zoneMap(int(state.range(0))), palette(), {.epsilon = 0.5});
    for (auto _ : state) {
        auto field = zones::buildBorderField(lines);
        benchmark::DoNotOptimize(field.signedDistance.data());
    }
    state.SetItemsProcessed(state.iterations() * 2048 * 2048);
}
BENCHMARK(BM_ZonesBorderField)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The target: vector borderlines and the distance field of a 2048^2 map.
void BM_ZonesBorderlinesAndField(benchmark::State& state) {
    const auto& map = zoneMap(int(state.range(0)));
    for (auto _ : state) {
        auto lines = zones::buildBorderlines(map, palette(), {.epsilon = 0.5});
        auto field = zones::buildBorderField(lines);
        benchmark::DoNotOptimize(field.signedDistance.data());
    }
}
BENCHMARK(BM_ZonesBorderlinesAndField)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
