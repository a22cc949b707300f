#include <sierra/render/CurvatureGpu.h>

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace sierra::render {

namespace {

// curvature.comp's workgroup size (CURVATURE_GROUP_X, _Y) of the per-sample
// programs. Other shapes (64x1, 128x1, 256x1, 8x8, 32x4) measured no
// different on llvmpipe within the noise of a loaded machine.
constexpr int kGroupX = 16;
constexpr int kGroupY = 16;
// The runs and the border: 1D workgroups.
constexpr int kLineGroup = 64;
// Samples per run (CURVATURE_RUN, a multiple of 4). 8 measured fastest on
// llvmpipe (docs/curvature.md).
constexpr int kRun = 8;

// A buffer texture over `buffer` from byte `offset` on (texelFetch by linear index in the shaders).
gpu::Texture bufferTexture(const gpu::Buffer& buffer, GLenum format, size_t offset = 0) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    glTextureBufferRange(id, format, buffer.id(), GLintptr(offset), GLsizeiptr(buffer.size() - offset));
    return gpu::Texture(id, gpu::kAdopt);
}

std::string define(const char* name, int value) { return std::string("#define ") + name + " " + std::to_string(value) + "\n"; }

std::string groupDefines(int x, int y) { return define("CURVATURE_GROUP_X", x) + define("CURVATURE_GROUP_Y", y); }

int roundUp(int v, int m) { return (v + m - 1) / m * m; }

// v / d rounded down (d > 0).
int floorDiv(int v, int d) { return v >= 0 ? v / d : -((-v + d - 1) / d); }

}  // namespace

std::string CurvatureGpu::layoutDefines(bool gradients) const {
    std::string d = define("CURVATURE_LEAD", heightsLead_) + define("CURVATURE_GRADIENT_LEAD", gradientLead_);
    // Window row rho (-1, 0, +1) of run r starts at value r * kRun - 1 + rho * width: in floats
    // of the vec4 view, lead + that (heights) or 2 (lead + that) (gradients).
    for (int row = 0; row < 3; ++row) {
        const int start = gradients ? 2 * (gradientLead_ - 1 + (row - 1) * width_) : heightsLead_ - 1 + (row - 1) * width_;
        const int texel = floorDiv(start, 4);
        d += define(("CURVATURE_T" + std::to_string(row)).c_str(), texel) +
             define(("CURVATURE_A" + std::to_string(row)).c_str(), start - 4 * texel);
    }
    return d + define("CURVATURE_RUN", kRun);
}

void CurvatureGpu::dispatchRuns(gpu::Program& program) {
    const int64_t runs = (int64_t(width_) * height_ + kRun - 1) / kRun;
    const int64_t groups = (runs + kLineGroup - 1) / kLineGroup;
    const int64_t x = std::min<int64_t>(groups, 65535);
    glUseProgram(program.id());
    glUniform2i(program.uniform("uSize"), width_, height_);
    glUniform2f(program.uniform("uSpacing"), spacingX_, spacingZ_);
    glDispatchCompute(GLuint(x), GLuint((groups + x - 1) / x), 1);
}

void CurvatureGpu::dispatchBorder(gpu::Program& program) {
    const int border = 2 * width_ + 2 * (height_ - 2);
    glUseProgram(program.id());
    glUniform2i(program.uniform("uSize"), width_, height_);
    glUniform2f(program.uniform("uSpacing"), spacingX_, spacingZ_);
    glDispatchCompute(GLuint((border + kLineGroup - 1) / kLineGroup), 1, 1);
}

CurvatureGpu CurvatureGpu::create(const terrain::Heightfield& field) {
    SIERRA_CHECK(!field.empty(), "GPU curvature: the heightfield is empty");
    CurvatureGpu c;
    c.width_ = field.width();
    c.height_ = field.height();
    c.spacingX_ = field.spacingX();
    c.spacingZ_ = field.spacingZ();
    // Leads and tails of a row and more, so that every window of a run
    // (rows -1 ... +1) lies inside the buffers. The heights' lead puts the
    // start of a run's middle window row (sample r * kRun - 1) at float 1 of
    // a texel for odd widths, 0 for even ones: then the 10 floats of each of
    // the 3 rows start at float 0, 1 or 2 of a texel and take 3 texels (a
    // start at float 3 would take 4). The gradients' lead keeps their RG32F
    // view (the hatch strokes') at an offset the driver accepts.
    const int w = c.width_;
    c.heightsLead_ = w + 4;
    while ((c.heightsLead_ - 1) % 4 != w % 2) ++c.heightsLead_;
    GLint align = 16;
    glGetIntegerv(GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT, &align);
    c.gradientLead_ = roundUp(w + 4, std::max(4, int(align) / 8));
    const size_t samples = size_t(field.sampleCount());
    const size_t padded = size_t(roundUp(int(samples), kRun)) + size_t(w) + 2 * kRun;
    GLint maxTexels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
    SIERRA_CHECK(int64_t(c.heightsLead_) + int64_t(padded) <= int64_t(maxTexels), "GPU curvature: a ", c.width_,
                 "x", c.height_, " grid has more samples than the driver's buffer textures hold (", maxTexels,
                 ")");

    std::vector<float> heights(size_t(c.heightsLead_) + padded, 0.0f);
    const float scale = field.verticalScale();
    const bool masked = field.hasMask();
    auto mask = field.mask();
    auto raw = field.samples();
    for (size_t k = 0; k < samples; ++k) {
        const float y = masked && !mask[k] ? NAN : raw[k] * scale;
        c.noData_ = c.noData_ || std::isnan(y);
        heights[size_t(c.heightsLead_) + k] = y;
    }

    c.heights_ = gpu::Buffer::create({.size = heights.size() * sizeof(float), .data = heights.data()});
    c.gradient_ = gpu::Buffer::create({.size = (size_t(c.gradientLead_) + padded) * 2 * sizeof(float)});
    c.field_ = gpu::Buffer::create({.size = size_t(roundUp(int(samples), kRun)) * 4 * sizeof(float)});
    c.heightsTexture_ = bufferTexture(c.heights_, GL_R32F);
    c.heights4Texture_ = bufferTexture(c.heights_, GL_RGBA32F);
    c.gradientTexture_ = bufferTexture(c.gradient_, GL_RG32F, size_t(c.gradientLead_) * 2 * sizeof(float));
    c.gradient4Texture_ = bufferTexture(c.gradient_, GL_RGBA32F);
    c.fieldTexture_ = bufferTexture(c.field_, GL_RGBA32F);
    return c;
}

void CurvatureGpu::compute(const analysis::CurvatureOptions& o, bool tangentPlanes) {
    analysis::validate(o);
    const int minSide = std::max(3, 2 * o.distance + 1);
    SIERRA_CHECK(width_ >= minSide && height_ >= minSide, "curvature: a ", width_, "x", height_,
                 " grid is too small for reinforcement distance ", o.distance, " (each side needs at least ",
                 minSide, " samples)");
    const bool near = o.distance == 1;
    const bool runs = near && !noData_;
    const int levels = o.levels.enabled ? 1 : 0;
    const std::string method = define("CURVATURE_METHOD", int(o.method)) + (levels ? "#define CURVATURE_LEVELS 1\n" : "");
    const std::string normals = define("CURVATURE_NORMALS", int(o.normals)) + "#define CURVATURE_GRADIENT 1\n";
    auto build = [&](gpu::Program& p, const std::string& defines) {
        if (!p) p = gpu::Program::create({.compute = "curvature.comp", .defines = defines});
        return std::ref(p);
    };
    gpu::GlStateScope scope;
    glBindTextureUnit(2, heightsTexture_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, gradient_.id());
    const bool normalBased =
        o.method == analysis::CurvatureMethod::TwoNormal || o.method == analysis::CurvatureMethod::ThreeNormal;
    if ((normalBased || tangentPlanes) && runs) {
        // Runs, then the border's one-sided normals over them.
        glBindTextureUnit(3, heights4Texture_.id());
        dispatchRuns(build(gradientRunPrograms_[size_t(o.normals)],
                           groupDefines(kLineGroup, 1) + normals + layoutDefines(false) + "#define CURVATURE_RUNS 1\n"));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        dispatchBorder(build(gradientBorderPrograms_[size_t(o.normals)],
                             groupDefines(kLineGroup, 1) + normals + layoutDefines(false) + "#define CURVATURE_BORDER 1\n"));
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    } else if (normalBased || tangentPlanes) {
        gpu::Program& g = build(gradientPrograms_[size_t(o.normals)], groupDefines(kGroupX, kGroupY) + normals + layoutDefines(false));
        glUseProgram(g.id());
        glUniform2i(g.uniform("uSize"), width_, height_);
        glUniform2f(g.uniform("uSpacing"), spacingX_, spacingZ_);
        glDispatchCompute(GLuint((width_ + kGroupX - 1) / kGroupX), GLuint((height_ + kGroupY - 1) / kGroupY), 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    auto setFieldUniforms = [&](gpu::Program& p) {
        glUseProgram(p.id());
        glUniform1i(p.uniform("uDistance"), o.distance);
        glUniform1f(p.uniform("uScale"), o.scale);
        glUniform4f(p.uniform("uLevels"), o.levels.enabled ? 1.0f : 0.0f, o.levels.black, o.levels.white,
                    o.levels.gamma);
        glUniform1i(p.uniform("uSigned"), o.signedValues ? 1 : 0);
        glUniform1i(p.uniform("uSecond"), o.output == analysis::CurvatureOutput::SecondDerivative ? 1 : 0);
    };
    glBindTextureUnit(1, gradientTexture_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, field_.id());
    if (runs) {
        gpu::Program& r = build(fieldRunPrograms_[size_t(o.method)][size_t(levels)],
                                groupDefines(kLineGroup, 1) + method + layoutDefines(normalBased) + "#define CURVATURE_RUNS 1\n");
        setFieldUniforms(r);
        glBindTextureUnit(3, normalBased ? gradient4Texture_.id() : heights4Texture_.id());
        dispatchRuns(r);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        gpu::Program& b = build(fieldBorderPrograms_[size_t(o.method)][size_t(levels)],
                                groupDefines(kLineGroup, 1) + method + layoutDefines(false) + "#define CURVATURE_BORDER 1\n");
        setFieldUniforms(b);
        dispatchBorder(b);
    } else {
        gpu::Program& p = build(fieldPrograms_[size_t(o.method)][near ? 1 : 0][size_t(levels)],
                                groupDefines(kGroupX, kGroupY) + method + layoutDefines(false) +
                                    (near ? "#define CURVATURE_NEAR 1\n" : ""));
        setFieldUniforms(p);
        glUniform2i(p.uniform("uSize"), width_, height_);
        glUniform2f(p.uniform("uSpacing"), spacingX_, spacingZ_);
        glDispatchCompute(GLuint((width_ + kGroupX - 1) / kGroupX), GLuint((height_ + kGroupY - 1) / kGroupY), 1);
    }
    // Any later reader: the hatch strokes' texel fetches, or a read-back.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);  // not part of GlState
}

analysis::CurvatureField CurvatureGpu::read() const {
    analysis::CurvatureField out;
    out.width = width_;
    out.height = height_;
    out.spacingX = spacingX_;
    out.spacingZ = spacingZ_;
    out.values.resize(size_t(width_) * size_t(height_) * analysis::kDirectionCount);
    glGetNamedBufferSubData(field_.id(), 0, GLsizeiptr(out.values.size() * sizeof(float)), out.values.data());
    return out;
}

}  // namespace sierra::render
