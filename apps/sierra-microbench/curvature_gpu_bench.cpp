// The GPU curvature field (render::CurvatureGpu, shaders/curvature.frag)
// beside the CPU reference on the same grid, in one run: compute alone
// (finished with glFinish) and compute plus the read-back the line tracer
// needs. Args: size, method (CurvatureMethod order). Run beside
// BM_Curvature/2049/... for the CPU time of the same field.
#include <sierra/analysis/Curvature.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/gpu/Objects.h>
#include <sierra/gpu/Program.h>
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

// The floor of the fragment runs on this driver: a full-screen pass that
// writes a value computed from gl_FragCoord to the same 8 RGBA32F layers
// (ceil(size / 8) x size, sample i of a run in layer i % 8) and reads
// nothing, finished with glFinish. On llvmpipe a colour write loads the
// destination block before it stores it (its blend stage reads every colour
// buffer, blending on or off), so the field's 67 MB at 2049^2 cost a read
// and a write; the CPU reference only writes. Arg: grid side.
void BM_CurvatureGpuWriteFloor(benchmark::State& state) {
    const int size = int(state.range(0));
    GpuSetup& s = setup(size);
    // The benchmarks share one context: this one's bindings end with it.
    sierra::gpu::GlStateScope scope;
    constexpr int kRun = sierra::render::CurvatureGpu::kRun;
    const int runs = (size + kRun - 1) / kRun;
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &name);
    sierra::gpu::Texture layers(name, sierra::gpu::kAdopt);
    glTextureStorage3D(name, 1, GL_RGBA32F, runs, size, kRun);
    sierra::gpu::Framebuffer framebuffer = sierra::gpu::Framebuffer::create();
    GLenum buffers[kRun];
    for (int k = 0; k < kRun; ++k) {
        glNamedFramebufferTextureLayer(framebuffer.id(), GLenum(GL_COLOR_ATTACHMENT0 + k), name, 0,
                                       k);
        buffers[k] = GLenum(GL_COLOR_ATTACHMENT0 + k);
    }
    glNamedFramebufferDrawBuffers(framebuffer.id(), kRun, buffers);
    framebuffer.checkComplete("write floor");
    auto stage = [](GLenum type, const char* source) {
        const GLuint shader = glCreateShader(type);
        glShaderSource(shader, 1, &source, nullptr);
        glCompileShader(shader);
        return shader;
    };
    const GLuint vs = stage(GL_VERTEX_SHADER,
                            "#version 450 core\n"
                            "void main() {\n"
                            "    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
                            "    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
                            "}\n");
    const GLuint fs =
        stage(GL_FRAGMENT_SHADER,
              "#version 450 core\n"
              "layout(location = 0) out vec4 o[8];\n"
              "void main() {\n"
              "    vec2 f = gl_FragCoord.xy;\n"
              "    for (int k = 0; k < 8; ++k) o[k] = vec4(f.x + float(k), f.y, f.x * f.y, 1.0);\n"
              "}\n");
    GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    sierra::gpu::Program owned(program, sierra::gpu::kAdopt);
    GLint linked = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
        state.SkipWithError("write floor: the shader did not link");
        return;
    }
    sierra::gpu::VertexArray vertexArray = sierra::gpu::VertexArray::create();
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer.id());
    glViewport(0, 0, runs, size);
    glUseProgram(program);
    glBindVertexArray(vertexArray.id());
    for (GLenum cap : {GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_STENCIL_TEST, GL_SCISSOR_TEST})
        glDisable(cap);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    for (auto _ : state) {
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glFinish();
    }
    state.SetItemsProcessed(state.iterations() * int64_t(size) * size);
    state.SetLabel("8 RGBA32F layers written, nothing read, on " + s.context.renderer());
}
BENCHMARK(BM_CurvatureGpuWriteFloor)->Arg(2049)->Unit(benchmark::kMillisecond)->UseRealTime();

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
