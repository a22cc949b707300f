// The GPU curvature field (render::CurvatureGpu, shaders/curvature.frag)
// beside the CPU reference on the same grid, in one run: compute alone
// (finished with glFinish) and compute plus the read-back the line tracer
// needs. Args: size, method (CurvatureMethod order). Run beside
// BM_Curvature/2049/... for the CPU time of the same field.
#include <sierra/analysis/Curvature.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/render/CurvatureGpu.h>
#include <sierra/terrain/DiamondSquare.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace {

namespace analysis = sierra::analysis;

struct GpuSetup {
    sierra::gpu::EglContext context = sierra::gpu::EglContext::create({.width = 16, .height = 16});
    sierra::terrain::Heightfield field;
    std::unique_ptr<sierra::render::CurvatureGpu> curvature;  // the driver's default path
    std::unique_ptr<sierra::render::CurvatureGpu> other;      // the other path
    // The same terrain with its lowest tenth no data (a coast), on the default path.
    sierra::terrain::Heightfield coast;
    std::unique_ptr<sierra::render::CurvatureGpu> coastCurvature;
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
        s->curvature = std::make_unique<sierra::render::CurvatureGpu>(
            sierra::render::CurvatureGpu::create(s->field));
        using Path = sierra::render::CurvatureGpu::Path;
        s->other =
            std::make_unique<sierra::render::CurvatureGpu>(sierra::render::CurvatureGpu::create(
                s->field, s->curvature->path() == Path::Fragment ? Path::Compute : Path::Fragment));
        s->coast = s->field;
        std::vector<float> heights(s->field.samples().begin(), s->field.samples().end());
        std::nth_element(heights.begin(), heights.begin() + heights.size() / 10, heights.end());
        const float sea = heights[heights.size() / 10];
        std::vector<uint8_t> mask(heights.size());
        for (size_t k = 0; k < mask.size(); ++k) mask[k] = s->field.samples()[k] > sea ? 1 : 0;
        s->coast.setMask(std::move(mask));
        s->coastCurvature = std::make_unique<sierra::render::CurvatureGpu>(
            sierra::render::CurvatureGpu::create(s->coast));
    }
    return *s;
}

const char* pathName(const sierra::render::CurvatureGpu& c) {
    return c.path() == sierra::render::CurvatureGpu::Path::Fragment ? "fragment runs" : "compute";
}

// Args: grid side, method, read back (1) or not, the driver's default path
// (0) or the other one (1), reinforcement distance.
void BM_CurvatureGpu(benchmark::State& state) {
    GpuSetup& s = setup(int(state.range(0)));
    analysis::CurvatureOptions o{.method = analysis::CurvatureMethod(state.range(1)),
                                 .distance = int(state.range(4))};
    const bool read = state.range(2) != 0;
    sierra::render::CurvatureGpu& gpu = state.range(3) != 0 ? *s.other : *s.curvature;
    // The field alone: the gradient pass only where the method needs it.
    gpu.compute(o, false);
    glFinish();
    for (auto _ : state) {
        gpu.compute(o, false);
        if (read) {
            auto f = gpu.read();
            benchmark::DoNotOptimize(f.values.data());
        } else {
            glFinish();
        }
    }
    state.SetItemsProcessed(state.iterations() * s.field.sampleCount());
    state.SetLabel(std::string(analysis::curvatureMethodName(o.method)) +
                   (o.distance > 1 ? ", distance " + std::to_string(o.distance) : "") +
                   (read ? " + read-back" : "") + ", " + pathName(gpu) + " on " +
                   s.context.renderer());
}
BENCHMARK(BM_CurvatureGpu)
    ->ArgsProduct({{2049}, {0, 1, 2, 3}, {0}, {0, 1}, {1}})
    ->Args({2049, 1, 1, 0, 1})
    ->ArgsProduct({{2049}, {1, 2, 3}, {0}, {0}, {2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// A field with no data (the lowest tenth of the terrain, a coast) on the CPU
// with all threads (device 0) and on the GPU's default path (device 1).
// Args: grid side, method, device, reinforcement distance.
void BM_CurvatureNoData(benchmark::State& state) {
    GpuSetup& s = setup(int(state.range(0)));
    analysis::CurvatureOptions o{.method = analysis::CurvatureMethod(state.range(1)),
                                 .distance = int(state.range(3))};
    const bool gpu = state.range(2) != 0;
    analysis::CurvatureField cpu;
    auto run = [&] {
        if (gpu) {
            s.coastCurvature->compute(o, false);
            glFinish();
        } else {
            analysis::computeCurvature(s.coast, o, cpu);
            benchmark::DoNotOptimize(cpu.values.data());
        }
    };
    run();
    for (auto _ : state) run();
    state.SetItemsProcessed(state.iterations() * s.coast.sampleCount());
    state.SetLabel(std::string(analysis::curvatureMethodName(o.method)) +
                   (o.distance > 1 ? ", distance " + std::to_string(o.distance) : "") +
                   ", 10% no data, " +
                   (gpu ? std::string(pathName(*s.coastCurvature)) + " on " + s.context.renderer()
                        : std::string("CPU")));
}
BENCHMARK(BM_CurvatureNoData)
    ->ArgsProduct({{2049}, {0, 1, 2, 3}, {0, 1}, {1}})
    ->Args({2049, 1, 0, 2})
    ->Args({2049, 1, 1, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
