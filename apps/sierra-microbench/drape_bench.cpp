// What drapes, vector layers and map furniture add to a frame: one 1920x1080
// frame of a 2049^2 fractal terrain (SBT, tau 1, no MSAA, the default view),
// drawn and finished (glFinish), plain and with each of them, side by side
// in one run. Targets: a drape at most 1.15x the plain frame; vector layers
// of one million vertices at most 1.5x.
#include <sierra/gpu/EglContext.h>
#include <sierra/render/Annotations.h>
#include <sierra/render/DrapeSurface.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/render/VectorOverlay.h>
#include <sierra/terrain/DiamondSquare.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <string>

namespace {

namespace analysis = sierra::analysis;
namespace render = sierra::render;
namespace terrain = sierra::terrain;

constexpr int kWidth = 1920, kHeight = 1080, kSide = 2049;

// Args: 0 plain, 1 a 4096^2 drape, 2 vector layers of 1 M vertices (1000
// random walks of 1000 points, half a sample a step, never cut further),
// 3 map furniture (title, scale bar, north arrow and 50 labels).
enum Variant { kPlain, kDrape, kVectors, kFurniture };

struct Setup {
    sierra::gpu::EglContext context =
        sierra::gpu::EglContext::create({.width = kWidth, .height = kHeight});
    terrain::Heightfield field;
    std::unique_ptr<render::TerrainRenderer> renderer;
    render::FrameTarget target = render::FrameTarget::create({.width = kWidth, .height = kHeight});
    terrain::DrapeImage drape;
    terrain::VectorLayer vectors;
    int64_t vectorVertices = 0;
};

Setup& setup() {
    static std::unique_ptr<Setup> s;
    if (s) return *s;
    s = std::make_unique<Setup>();
    s->field = terrain::generateDiamondSquare({.size = kSide, .seed = 7, .roughness = 1.0f});
    auto [lo, hi] = s->field.range();
    s->field.setVerticalScale(0.15f * float(kSide - 1) / std::max(1e-6f, hi - lo));
    s->drape.width = s->drape.height = 4096;
    s->drape.rgba.resize(size_t(4096) * 4096 * 4);
    for (int y = 0; y < 4096; ++y)
        for (int x = 0; x < 4096; ++x) {
            uint8_t* p = &s->drape.rgba[(size_t(y) * 4096 + x) * 4];
            p[0] = uint8_t(x / 16 * 37), p[1] = uint8_t(y / 16 * 53), p[2] = uint8_t((x ^ y) & 255);
            p[3] = 255;
        }
    s->drape.coverage = 1.0;
    std::mt19937 random(11);
    std::uniform_real_distribution<double> start(0.0, kSide - 1.0), turn(-0.3, 0.3);
    for (int walk = 0; walk < 1000; ++walk) {
        terrain::VectorFeature f{terrain::VectorFeature::Kind::Line, {{}}, ""};
        double i = start(random), j = start(random), heading = start(random);
        for (int k = 0; k < 1000; ++k) {
            f.parts[0].push_back(
                {std::clamp(i, 0.0, kSide - 1.0), std::clamp(j, 0.0, kSide - 1.0)});
            heading += turn(random);
            i += 0.5 * std::cos(heading), j += 0.5 * std::sin(heading);
        }
        s->vectors.features.push_back(std::move(f));
    }
    s->vectorVertices = 1000 * 1000;
    return *s;
}

void BM_DrapeFrame(benchmark::State& state) {
    Setup& s = setup();
    const auto variant = Variant(state.range(0));
    // A fresh renderer per variant: the drape surface and the line pass stay
    // off the plain frame.
    s.renderer = std::make_unique<render::TerrainRenderer>(
        render::TerrainRenderer::create({.field = &s.field}));
    std::unique_ptr<render::AnnotationOverlay> overlay;
    render::AnnotationDesc furniture;
    if (variant == kDrape) {
        const render::DrapeLayer layer{&s.drape};
        s.renderer->setSurface(render::makeDrapeSurface(
            render::makeRampSurface(s.renderer->terrain()), std::span(&layer, 1)));
    }
    static analysis::LineSet lines;
    static std::optional<render::LinePyramid> pyramid;
    if (variant == kVectors) {
        // As facade::applyMapLayers draws them: the far field in a texture, the near as quads.
        if (!pyramid) {
            lines = render::vectorLines(s.vectors, true, 1.0f);
            const render::LineLayer layer{&lines, {.width = 2.0f}};
            pyramid = render::rasteriseLines(std::span(&layer, 1), kSide, kSide);
        }
        s.renderer->setSurface(render::makeDrapeSurface(
            render::makeRampSurface(s.renderer->terrain()), {}, &*pyramid));
        s.renderer->addPass(render::LinePass::create(
            lines,
            {.width = 2.0f, .thin = false, .nearTexelSize = 1.0f / pyramid->texelsPerSample}));
    }
    const render::Camera camera =
        render::defaultCamera(s.renderer->bounds(), float(kWidth) / kHeight);
    if (variant == kFurniture) {
        overlay = std::make_unique<render::AnnotationOverlay>(16.0f);
        furniture.title = "Benchmark range";
        furniture.scaleBar = furniture.northArrow = true;
        for (int k = 0; k < 50; ++k)
            furniture.labels.push_back(
                {"peak " + std::to_string(k),
                 {float(k * 40), float(s.field.worldHeight(k * 40, 1024)), 1024.0f}});
    }
    auto frame = [&] {
        s.target.begin(render::TerrainRenderer::clearColour({}));
        s.renderer->draw(camera, kWidth, kHeight, {.tau = 1.0f});
        if (overlay) {
            const auto layout = render::layoutAnnotations(furniture, camera, kWidth, kHeight,
                                                          nullptr, overlay->measurer());
            overlay->draw(furniture, layout);
        }
        glFinish();
    };
    frame();  // programs built, textures uploaded
    for (auto _ : state) frame();
    static const char* kNames[] = {"plain", "4096^2 drape", "1 M vector vertices", "map furniture"};
    state.SetLabel(std::string(kNames[variant]) + ", 1920x1080, " + s.context.renderer());
}
BENCHMARK(BM_DrapeFrame)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
