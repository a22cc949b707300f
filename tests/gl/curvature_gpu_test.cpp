// The GPU curvature field (shaders/curvature.frag) against the CPU reference
// (analysis::computeCurvature): every method, normal scheme and option, on a
// fractal and on analytic surfaces, with no-data samples and the border rule.

#include "GlTest.h"

#include <sierra/analysis/Curvature.h>
#include <sierra/analysis/Normals.h>
#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/CurvatureGpu.h>
#include <sierra/terrain/DiamondSquare.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace sierra;
using analysis::CurvatureMethod;
using analysis::CurvatureOptions;
using analysis::NormalMethod;

namespace {

class CurvatureGpuTest : public test::GlTest {};

float withinTolerance(float value) {
    return std::max(1e-6f, 1e-4f * std::fabs(value));
}

float levelled(float magnitude, const analysis::Levels& l) {
    float t = std::clamp((magnitude - l.black) / (l.white - l.black), 0.0f, 1.0f);
    return t > 0.0f ? std::pow(t, 1.0f / l.gamma) : 0.0f;
}

// 1e-4 relative or 1e-6 absolute, NaN exactly where the CPU has NaN. Returns
// the number of mismatches and reports the first few. With level control,
// `raw` is the CPU field without it: the mapping is ill-conditioned just above
// the black point (a value 1e-7 above it moves by percents when the value
// moves by one float step, as a driver's fused multiply-add does), so a
// levelled GPU value must be the level of a value within the tolerance of the
// raw CPU value, with the sign of the CPU's.
int compareFields(const analysis::CurvatureField& gpu, const analysis::CurvatureField& cpu,
                  const std::string& what, const analysis::CurvatureField* raw = nullptr,
                  const analysis::Levels& levels = {}) {
    EXPECT_EQ(gpu.width, cpu.width);
    EXPECT_EQ(gpu.height, cpu.height);
    int bad = 0;
    for (size_t k = 0; k < cpu.values.size(); ++k) {
        float g = gpu.values[k], c = cpu.values[k];
        bool ok = std::isnan(c) ? std::isnan(g)
                                : !std::isnan(g) && std::fabs(g - c) <= withinTolerance(c);
        if (!ok && raw && !std::isnan(c) && !std::isnan(g)) {
            float r = std::fabs(raw->values[k]);
            float lo = levelled(r - withinTolerance(r), levels),
                  hi = levelled(r + withinTolerance(r), levels);
            float m = std::fabs(g);
            ok = m >= lo - withinTolerance(lo) && m <= hi + withinTolerance(hi) &&
                 (g == 0.0f || c == 0.0f || (g < 0.0f) == (c < 0.0f));
        }
        if (!ok && ++bad <= 3) {
            size_t s = k / 4;
            ADD_FAILURE() << what << ": sample (" << s % size_t(cpu.width) << ", "
                          << s / size_t(cpu.width) << ") direction " << k % 4 << ": GPU " << g
                          << ", CPU " << c;
        }
    }
    return bad;
}

terrain::Heightfield fractal(int size, unsigned seed) {
    terrain::Heightfield f = terrain::generateDiamondSquare({.size = size, .seed = seed});
    auto [lo, hi] = f.range();
    f.setSpacing(1.5f, 1.0f);  // unequal spacing: diagonals are not 45 degrees
    f.setVerticalScale(0.3f * float(size) / std::max(hi - lo, 1e-3f));
    return f;
}

std::vector<CurvatureOptions> allOptionSets() {
    std::vector<CurvatureOptions> sets;
    for (NormalMethod n : {NormalMethod::Edge, NormalMethod::Triangle, NormalMethod::Quad}) {
        sets.push_back({.method = CurvatureMethod::TwoNormal, .normals = n});
        sets.push_back({.method = CurvatureMethod::ThreeNormal, .normals = n});
        sets.push_back(
            {.method = CurvatureMethod::ThreeNormal, .normals = n, .distance = 3, .scale = 2.0f});
    }
    for (CurvatureMethod m : {CurvatureMethod::ThreeVertex, CurvatureMethod::EdgeAngle}) {
        sets.push_back({.method = m});
        sets.push_back({.method = m, .distance = 2, .scale = 0.5f});
    }
    // The largest distance the fragment runs compute (kMaxRunDistance) and
    // one past it (the per-sample program); grids smaller than the stencil skip
    // them (checkAllMethods).
    static_assert(render::CurvatureGpu::kMaxRunDistance == 4);
    sets.push_back({.method = CurvatureMethod::ThreeNormal, .distance = 4});
    sets.push_back({.method = CurvatureMethod::ThreeVertex, .distance = 4, .scale = 2.0f});
    sets.push_back({.method = CurvatureMethod::EdgeAngle, .distance = 5});
    CurvatureOptions levels{
        .method = CurvatureMethod::ThreeVertex, .scale = 4.0f, .signedValues = true};
    levels.levels = {.enabled = true, .black = 0.1f, .white = 0.9f, .gamma = 2.2f};
    sets.push_back(levels);
    sets.push_back({.method = CurvatureMethod::ThreeNormal, .signedValues = true});
    sets.push_back({.method = CurvatureMethod::EdgeAngle, .signedValues = true});
    sets.push_back({.method = CurvatureMethod::ThreeVertex,
                    .output = analysis::CurvatureOutput::SecondDerivative});
    sets.push_back({.method = CurvatureMethod::TwoNormal,
                    .output = analysis::CurvatureOutput::SecondDerivative});
    return sets;
}

std::string describe(const CurvatureOptions& o) {
    return std::string(analysis::curvatureMethodName(o.method)) + "/" +
           analysis::normalMethodName(o.normals) + " d=" + std::to_string(o.distance) +
           " scale=" + std::to_string(o.scale) + (o.signedValues ? " signed" : "") +
           (o.levels.enabled ? " levels" : "") +
           (o.output == analysis::CurvatureOutput::SecondDerivative ? " y''" : "");
}

constexpr render::CurvatureGpu::Path kPaths[] = {render::CurvatureGpu::Path::Fragment,
                                                 render::CurvatureGpu::Path::Compute};
const char* pathName(render::CurvatureGpu::Path p) {
    return p == render::CurvatureGpu::Path::Fragment ? "fragment runs" : "compute";
}

// Every option set on both paths against the CPU.
void checkAllMethods(const terrain::Heightfield& field, const std::string& name) {
    for (render::CurvatureGpu::Path path : kPaths) {
        render::CurvatureGpu gpu = render::CurvatureGpu::create(field, path);
        const std::string surface = name + " (" + pathName(path) + ")";
        for (const CurvatureOptions& o : allOptionSets()) {
            if (2 * o.distance + 1 > std::min(field.width(), field.height())) continue;
            gpu.compute(o);
            analysis::CurvatureField cpu = analysis::computeCurvature(field, o);
            analysis::CurvatureField raw;
            if (o.levels.enabled) {
                CurvatureOptions plain = o;
                plain.levels.enabled = false;
                raw = analysis::computeCurvature(field, plain);
            }
            EXPECT_EQ(compareFields(gpu.read(), cpu, surface + " " + describe(o),
                                    o.levels.enabled ? &raw : nullptr, o.levels),
                      0)
                << surface << " " << describe(o);
        }
    }
}

TEST_F(CurvatureGpuTest, FractalMatchesCpuForEveryMethod) {
    checkAllMethods(fractal(65, 7), "fractal");
}

TEST_F(CurvatureGpuTest, NonSquareGridMatchesCpu) {
    terrain::Heightfield f(37, 21);
    for (int j = 0; j < f.height(); ++j)
        for (int i = 0; i < f.width(); ++i)
            f.at(i, j) = std::sin(0.3f * float(i)) * std::cos(0.2f * float(j)) * 3.0f;
    checkAllMethods(f, "non-square waves");
}

// Fields without no-data are computed in runs of CurvatureGpu::kRun (8)
// samples of a row, the interior runs apart from the border's: widths of
// several residues modulo 8, the last run full, partly full or of one sample,
// and grids of one and two runs a row.
TEST_F(CurvatureGpuTest, RunsMatchCpuForWidthsAroundWholeRuns) {
    for (int width : {7, 9, 11, 17, 22, 24, 25, 31}) {
        // 11 rows and columns: distances up to 5, the runs' rows 4 ... 6 at 4
        const int height = width >= 11 ? 11 : 7;
        terrain::Heightfield f(width, height);
        for (int j = 0; j < f.height(); ++j)
            for (int i = 0; i < f.width(); ++i)
                f.at(i, j) =
                    std::sin(0.7f * float(i) + 0.2f * float(j)) * std::cos(0.5f * float(j)) * 2.0f;
        checkAllMethods(f, "waves " + std::to_string(width) + "x" + std::to_string(height));
    }
}

// The tangent planes the hatch strokes read (gradient(): sample (i, j) at
// texel (i / kRun, j), layer (i % kRun) / 2, .xy or .zw) are the CPU's normals
// as (dy/dx, dy/dz), from the runs and the border pass alike, for widths
// around whole runs.
TEST_F(CurvatureGpuTest, GradientTextureMatchesCpuNormals) {
    for (int width : {9, 10, 16, 17, 23, 24, 25}) {
        terrain::Heightfield f = fractal(33, 3);
        terrain::Heightfield g(width, 13);
        for (int j = 0; j < g.height(); ++j)
            for (int i = 0; i < g.width(); ++i) g.at(i, j) = f.at(i, j) * 3.0f;
        g.setSpacing(1.5f, 1.0f);
        for (render::CurvatureGpu::Path path : kPaths) {
            render::CurvatureGpu gpu = render::CurvatureGpu::create(g, path);
            const int run = render::CurvatureGpu::kRun, runs = gpu.runs();
            for (NormalMethod n :
                 {NormalMethod::Edge, NormalMethod::Triangle, NormalMethod::Quad}) {
                gpu.compute({.method = CurvatureMethod::ThreeVertex, .normals = n},
                            /*tangentPlanes=*/true);
                std::vector<float> layers(size_t(runs) * 13 * size_t(run / 2) * 4);
                glGetTextureImage(gpu.gradient().id(), 0, GL_RGBA, GL_FLOAT,
                                  GLsizei(layers.size() * sizeof(float)), layers.data());
                auto grad = [&](int i, int j, int c) {
                    return layers[((size_t(i % run / 2) * 13 + size_t(j)) * size_t(runs) +
                                   size_t(i / run)) *
                                      4 +
                                  size_t(i % 2) * 2 + size_t(c)];
                };
                analysis::NormalField cpu = analysis::computeNormals(g, n);
                int bad = 0;
                for (int j = 0; j < g.height(); ++j) {
                    for (int i = 0; i < g.width(); ++i) {
                        const analysis::Vec3& v = cpu.at(i, j);
                        const float ex = -v.x / v.y, ez = -v.z / v.y;
                        const float gx = grad(i, j, 0), gz = grad(i, j, 1);
                        auto near = [](float a, float b) {
                            return std::fabs(a - b) <= std::max(1e-5f, 1e-4f * std::fabs(b));
                        };
                        if ((!near(gx, ex) || !near(gz, ez)) && ++bad <= 3)
                            ADD_FAILURE() << width << "x13 " << pathName(path) << " "
                                          << analysis::normalMethodName(n) << " (" << i << ", " << j
                                          << "): GPU (" << gx << ", " << gz << "), CPU (" << ex
                                          << ", " << ez << ")";
                    }
                }
                EXPECT_EQ(bad, 0);
            }
        }
    }
}

TEST_F(CurvatureGpuTest, AnalyticSurfacesMatchCpu) {
    terrain::Heightfield quadric(33, 33), cylinder(33, 33), bump(33, 33), plane(33, 33);
    for (int j = 0; j < 33; ++j) {
        for (int i = 0; i < 33; ++i) {
            float x = float(i - 16), z = float(j - 16);
            quadric.at(i, j) = (0.05f * x * x + 0.02f * z * z) / 2.0f + 0.01f * x * z;
            cylinder.at(i, j) =
                std::sqrt(std::max(400.0f - z * z, 0.0f));  // axis along x, radius 20
            bump.at(i, j) = 8.0f * std::exp(-(x * x + z * z) / (2.0f * 36.0f));
            plane.at(i, j) = 0.3f * x - 0.2f * z + 5.0f;
        }
    }
    checkAllMethods(quadric, "quadric");
    checkAllMethods(cylinder, "cylinder");
    checkAllMethods(bump, "gaussian");
    checkAllMethods(plane, "plane");
}

TEST_F(CurvatureGpuTest, NoDataIsNanAndDoesNotSpread) {
    terrain::Heightfield f = fractal(33, 11);
    std::vector<uint8_t> mask(size_t(f.sampleCount()), 1);
    mask[size_t(10) * 33 + 12] = 0;  // an interior hole
    mask[size_t(0) * 33 + 5] = 0;    // on the border
    mask[size_t(20) * 33 + 20] = 0;  // a 2x2 hole
    mask[size_t(20) * 33 + 21] = 0;
    mask[size_t(21) * 33 + 20] = 0;
    mask[size_t(21) * 33 + 21] = 0;
    f.setMask(mask);
    checkAllMethods(f, "no-data");
    // The hole itself is NaN, a sample well away from it is not.
    render::CurvatureGpu gpu = render::CurvatureGpu::create(f);
    gpu.compute({});
    analysis::CurvatureField field = gpu.read();
    for (int d = 0; d < 4; ++d) {
        EXPECT_TRUE(std::isnan(field.at(12, 10, d)));
        EXPECT_FALSE(std::isnan(field.at(12, 14, d)));
    }
}

// Scattered no data on a grid of several runs a row: the fragment runs draw
// where their window (reach 1 for the gradients, the distance for the field)
// is clear of it, NaN where a run has no data at all, and the per-sample
// program elsewhere (a stencil), for every option set; the stencil itself
// against a brute-force search.
TEST_F(CurvatureGpuTest, ScatteredNoDataMatchesCpu) {
    terrain::Heightfield f = fractal(65, 13);
    std::vector<uint8_t> mask(size_t(f.sampleCount()), 1);
    uint32_t state = 99;
    for (auto& m : mask) {
        state = state * 1664525u + 1013904223u;
        if ((state >> 8) % 200 == 0) m = 0;
    }
    for (int j = 30; j < 34; ++j)
        for (int i = 16; i < 27; ++i) mask[size_t(j) * 65 + size_t(i)] = 0;
    f.setMask(mask);
    checkAllMethods(f, "scattered no-data");
    // Small grids: a last run of one sample that has no data (a run of no
    // data only), holes beside the borders and in the first run.
    for (int width : {9, 12, 17}) {
        terrain::Heightfield g(width, 11);
        std::vector<uint8_t> m(size_t(g.sampleCount()), 1);
        for (int j = 0; j < g.height(); ++j)
            for (int i = 0; i < g.width(); ++i) {
                // no symmetry: a sign of y'' near 0 would be a coin toss
                g.at(i, j) =
                    std::sin(0.7f * float(i) + 0.2f * float(j)) * std::cos(0.5f * float(j)) * 2.0f +
                    0.03f * float(i * i);
                if (i == width - 1 && j % 3 != 0) m[size_t(j) * width + i] = 0;
            }
        m[size_t(5) * width + 2] = m[size_t(1) * width + 1] = 0;
        g.setMask(m);
        checkAllMethods(g, "no-data " + std::to_string(width) + "x11");
    }

    const int w = f.width(), h = f.height(), pitch = 70, runs = (w + 7) / 8;
    std::vector<float> heights(size_t(pitch) * size_t(h + 2), 0.0f);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            heights[size_t(j + 1) * pitch + size_t(i) + 1] = mask[size_t(j) * w + i] ? 1.0f : NAN;
    const std::vector<uint8_t> clearance = render::CurvatureGpu::runClearance(heights, w, h, pitch);
    ASSERT_EQ(clearance.size(), size_t(runs) * size_t(h));
    const int far = render::CurvatureGpu::kMaxRunDistance + 1;
    const int kNoData = render::CurvatureGpu::kNoDataRun;
    int clear = 0, blocked = 0, empty = 0;
    for (int j = 0; j < h; ++j)
        for (int c = 0; c < runs; ++c) {
            int expect = far, missing = 0;
            for (int x = 8 * c; x < std::min(w, 8 * c + 8); ++x)
                missing += mask[size_t(j) * w + x] ? 0 : 1;
            if (missing == std::min(w, 8 * c + 8) - 8 * c) expect = kNoData;
            for (int y = 0; y < h && expect != kNoData; ++y)
                for (int x = 0; x < w; ++x) {
                    if (mask[size_t(y) * w + x]) continue;
                    const int dx = x < 8 * c ? 8 * c - x : x > 8 * c + 7 ? x - (8 * c + 7) : 0;
                    expect = std::min(expect, std::max(dx, std::abs(y - j)));
                }
            ASSERT_EQ(int(clearance[size_t(j) * runs + c]), expect) << "run " << c << " row " << j;
            (expect == far ? clear : expect == kNoData ? empty : blocked)++;
        }
    EXPECT_GT(clear, 0);
    EXPECT_GT(blocked, 0);
    EXPECT_GT(empty, 0);
}

TEST_F(CurvatureGpuTest, ComputeLeavesGlStateAlone) {
    terrain::Heightfield f = fractal(33, 5);
    for (render::CurvatureGpu::Path path : kPaths) {
        render::CurvatureGpu gpu = render::CurvatureGpu::create(f, path);
        gpu::GlState before = gpu::GlState::capture();
        gpu.compute({.method = CurvatureMethod::TwoNormal});
        (void)gpu.read();
        EXPECT_EQ(before.differences(gpu::GlState::capture()), "") << pathName(path);
    }
    // With no data the fragment runs test a stencil: its state (not part of
    // GlState) is the caller's again afterwards. Read with a stencil bound:
    // the reference reads back clamped to the bound stencil's bits.
    std::vector<uint8_t> mask(size_t(f.sampleCount()), 1);
    mask[40] = 0;
    f.setMask(mask);
    render::CurvatureGpu gpu =
        render::CurvatureGpu::create(f, render::CurvatureGpu::Path::Fragment);
    gpu::Framebuffer target = gpu::Framebuffer::create();
    gpu::Texture colour = gpu::Texture::create({.width = 4, .height = 4});
    gpu::Texture stencil =
        gpu::Texture::create({.format = GL_STENCIL_INDEX8, .width = 4, .height = 4});
    glNamedFramebufferTexture(target.id(), GL_COLOR_ATTACHMENT0, colour.id(), 0);
    glNamedFramebufferTexture(target.id(), GL_STENCIL_ATTACHMENT, stencil.id(), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, target.id());
    glStencilFuncSeparate(GL_FRONT, GL_NOTEQUAL, 3, 0x0f);
    glStencilFuncSeparate(GL_BACK, GL_GREATER, 5, 0xf0);
    glStencilMaskSeparate(GL_FRONT, 0x3c);
    glStencilMaskSeparate(GL_BACK, 0xc3);
    gpu::GlState before = gpu::GlState::capture();
    gpu.compute({.method = CurvatureMethod::ThreeVertex, .distance = 2});
    EXPECT_EQ(before.differences(gpu::GlState::capture()), "");
    const GLenum names[] = {GL_STENCIL_FUNC,
                            GL_STENCIL_REF,
                            GL_STENCIL_VALUE_MASK,
                            GL_STENCIL_WRITEMASK,
                            GL_STENCIL_BACK_FUNC,
                            GL_STENCIL_BACK_REF,
                            GL_STENCIL_BACK_VALUE_MASK,
                            GL_STENCIL_BACK_WRITEMASK};
    const GLint expected[] = {GL_NOTEQUAL, 3, 0x0f, 0x3c, GL_GREATER, 5, 0xf0, 0xc3};
    for (size_t k = 0; k < 8; ++k) {
        GLint v = 0;
        glGetIntegerv(names[k], &v);
        EXPECT_EQ(v, expected[k]) << "stencil state " << k;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glStencilFunc(GL_ALWAYS, 0, 0xff);
    glStencilMask(0xff);
    EXPECT_FALSE(glIsEnabled(GL_STENCIL_TEST));
}

// The two paths compute the same field on a fractal within 1e-5 relative
// (1e-6 absolute), tighter than against the CPU: the same per-sample code,
// or the runs' formulas in the same order. The default is the fragment runs
// on a software rasteriser and compute elsewhere.
TEST_F(CurvatureGpuTest, PathsAgreeAndTheDefaultSuitsTheDriver) {
    terrain::Heightfield f = fractal(65, 9);
    render::CurvatureGpu fragment = render::CurvatureGpu::create(f, kPaths[0]);
    render::CurvatureGpu compute = render::CurvatureGpu::create(f, kPaths[1]);
    for (CurvatureMethod m : {CurvatureMethod::TwoNormal, CurvatureMethod::ThreeNormal,
                              CurvatureMethod::ThreeVertex, CurvatureMethod::EdgeAngle}) {
        fragment.compute({.method = m});
        compute.compute({.method = m});
        analysis::CurvatureField a = fragment.read(), b = compute.read();
        ASSERT_EQ(a.values.size(), b.values.size());
        size_t differ = 0;
        for (size_t k = 0; k < a.values.size(); ++k)
            differ += std::fabs(a.values[k] - b.values[k]) >
                      std::max(1e-6f, 1e-5f * std::fabs(a.values[k]));
        EXPECT_EQ(differ, 0u) << analysis::curvatureMethodName(m);
    }
    const std::string renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const bool software = renderer.find("llvmpipe") != std::string::npos;
    EXPECT_EQ(render::CurvatureGpu::create(f).path(),
              software ? render::CurvatureGpu::Path::Fragment : render::CurvatureGpu::Path::Compute)
        << renderer;
}

TEST_F(CurvatureGpuTest, BadOptionsGiveTheCpuMessages) {
    render::CurvatureGpu gpu = render::CurvatureGpu::create(fractal(17, 1));
    auto message = [&](const CurvatureOptions& o) {
        try {
            gpu.compute(o);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(message({.distance = 0}).find("distance must be an integer >= 1"), std::string::npos);
    EXPECT_NE(message({.scale = -1.0f}).find("scale must be finite and >= 0"), std::string::npos);
    EXPECT_NE(message({.distance = 9}).find("too small for reinforcement distance 9"),
              std::string::npos);
}

}  // namespace
