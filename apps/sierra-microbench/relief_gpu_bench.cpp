// The relief fields on the GPU (render::ReliefGpu, shaders/horizon.comp):
// horizons in 16 azimuths and the sun's visibility of a fractal grid, from
// the upload of the heights to the results on the host, finished with the
// read-back (which waits for the GPU). Target: 4097^2 in at most 50 ms on an
// NVIDIA GPU. Run beside BM_Horizons/4097/... for the CPU time of the same
// fields.
#include <sierra/analysis/Relief.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/render/ReliefGpu.h>
#include <sierra/terrain/DiamondSquare.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <string>

namespace {

namespace analysis = sierra::analysis;

struct GpuSetup {
    sierra::gpu::EglContext context = sierra::gpu::EglContext::create({.width = 16, .height = 16});
    sierra::terrain::Heightfield field;
};

GpuSetup& setup(int size) {
    static std::unique_ptr<GpuSetup> s;
    if (!s || s->field.width() != size) {
        s.reset();
        s = std::make_unique<GpuSetup>();
        s->field =
            sierra::terrain::generateDiamondSquare({.size = size, .seed = 1, .roughness = 1.0f});
        auto [lo, hi] = s->field.range();
        s->field.setVerticalScale(0.1f * float(size - 1) / std::max(1e-6f, hi - lo));
    }
    return *s;
}

// Args: grid side (2^n + 1), what is read back: 0 the sun's visibility only
// (the horizons stay on the GPU as the terrain pass's textures), 1 also the
// sky light (computed from the horizons), 2 also all the horizons. Each
// iteration uploads the heights anew into the same textures.
void BM_HorizonsGpu(benchmark::State& state) {
    GpuSetup& s = setup(int(state.range(0)));
    const int read = int(state.range(1));
    const analysis::HorizonOptions options{.directions = 16};
    const analysis::SunDisc sun{.azimuth = 300.0f, .altitude = 20.0f};
    sierra::render::ReliefGpu gpu = sierra::render::ReliefGpu::create(s.field);
    auto run = [&] {
        gpu.upload(s.field);
        gpu.computeHorizonsAndSun(options, sun);
        auto v = gpu.readSunVisibility();
        benchmark::DoNotOptimize(v.data());
        if (read >= 1) {
            gpu.computeSky();
            auto l = gpu.readSkyLight();
            benchmark::DoNotOptimize(l.data());
        }
        if (read >= 2) {
            auto h = gpu.readHorizons();
            benchmark::DoNotOptimize(h.angle.data());
        }
    };
    run();  // builds the programs and allocates the textures and the scratch
    for (auto _ : state) run();
    state.SetItemsProcessed(state.iterations() * s.field.sampleCount() * (options.directions + 1));
    static const char* kRead[] = {"sun visibility", "sun visibility + sky light",
                                  "sun visibility + sky light + horizons"};
    state.SetLabel(std::string("16 azimuths + sun, upload and read-back of ") + kRead[read] +
                   " on " + s.context.renderer());
}
BENCHMARK(BM_HorizonsGpu)
    ->Args({129, 0})
    ->Args({1025, 0})
    ->Args({4097, 0})
    ->Args({4097, 1})
    ->Args({4097, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
