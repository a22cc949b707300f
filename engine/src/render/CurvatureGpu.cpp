#include <sierra/render/CurvatureGpu.h>

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace sierra::render {

namespace {

// curvature.comp's workgroup size (CURVATURE_GROUP_X, _Y).
// Other shapes (64x1, 128x1, 256x1, 8x8, 32x4) measured no different on
// llvmpipe within the noise of a loaded machine.
constexpr int kGroupX = 16;
constexpr int kGroupY = 16;

// A buffer texture over `buffer` (texelFetch by linear index in the shaders).
gpu::Texture bufferTexture(const gpu::Buffer& buffer, GLenum format) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    glTextureBuffer(id, format, buffer.id());
    return gpu::Texture(id, gpu::kAdopt);
}

// The gradient program for `normals`, or the field program of a method.
std::string gradientDefines(analysis::NormalMethod normals) {
    return "#define CURVATURE_GROUP_X " + std::to_string(kGroupX) + "\n#define CURVATURE_GROUP_Y " +
           std::to_string(kGroupY) + "\n#define CURVATURE_GRADIENT 1\n#define CURVATURE_NORMALS " +
           std::to_string(int(normals)) + "\n";
}

std::string fieldDefines(analysis::CurvatureMethod method, bool near, bool levels) {
    std::string d = "#define CURVATURE_GROUP_X " + std::to_string(kGroupX) + "\n#define CURVATURE_GROUP_Y " +
                    std::to_string(kGroupY) + "\n#define CURVATURE_METHOD " + std::to_string(int(method)) + "\n";
    if (levels) d += "#define CURVATURE_LEVELS 1\n";
    if (near) d += "#define CURVATURE_NEAR 1\n";
    return d;
}

}  // namespace

CurvatureGpu CurvatureGpu::create(const terrain::Heightfield& field) {
    SIERRA_CHECK(!field.empty(), "GPU curvature: the heightfield is empty");
    CurvatureGpu c;
    c.width_ = field.width();
    c.height_ = field.height();
    c.spacingX_ = field.spacingX();
    c.spacingZ_ = field.spacingZ();
    GLint maxTexels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
    SIERRA_CHECK(field.sampleCount() <= int64_t(maxTexels), "GPU curvature: a ", c.width_, "x", c.height_,
                 " grid has more samples than the driver's buffer textures hold (", maxTexels, ")");

    std::vector<float> heights(field.samples().begin(), field.samples().end());
    const float scale = field.verticalScale();
    const bool masked = field.hasMask();
    auto mask = field.mask();
    for (size_t k = 0; k < heights.size(); ++k) heights[k] = masked && !mask[k] ? NAN : heights[k] * scale;

    const size_t samples = heights.size();
    c.heights_ = gpu::Buffer::create({.size = samples * sizeof(float), .data = heights.data()});
    c.gradient_ = gpu::Buffer::create({.size = samples * 2 * sizeof(float)});
    c.field_ = gpu::Buffer::create({.size = samples * 4 * sizeof(float)});
    c.heightsTexture_ = bufferTexture(c.heights_, GL_R32F);
    c.gradientTexture_ = bufferTexture(c.gradient_, GL_RG32F);
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
    gpu::Program& p = fieldPrograms_[size_t(o.method)][near ? 1 : 0][o.levels.enabled ? 1 : 0];
    if (!p) {
        p = gpu::Program::create(
            {.compute = "curvature.comp", .defines = fieldDefines(o.method, near, o.levels.enabled)});
    }
    gpu::GlStateScope scope;
    const GLuint groupsX = GLuint((width_ + kGroupX - 1) / kGroupX);
    const GLuint groupsY = GLuint((height_ + kGroupY - 1) / kGroupY);
    glBindTextureUnit(2, heightsTexture_.id());
    const bool normalBased =
        o.method == analysis::CurvatureMethod::TwoNormal || o.method == analysis::CurvatureMethod::ThreeNormal;
    if (normalBased || tangentPlanes) {
        gpu::Program& g = gradientPrograms_[size_t(o.normals)];
        if (!g) g = gpu::Program::create({.compute = "curvature.comp", .defines = gradientDefines(o.normals)});
        glUseProgram(g.id());
        glUniform2i(g.uniform("uSize"), width_, height_);
        glUniform2f(g.uniform("uSpacing"), spacingX_, spacingZ_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, gradient_.id());
        glDispatchCompute(groupsX, groupsY, 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    glUseProgram(p.id());
    glUniform2i(p.uniform("uSize"), width_, height_);
    glUniform2f(p.uniform("uSpacing"), spacingX_, spacingZ_);
    glUniform1i(p.uniform("uDistance"), o.distance);
    glUniform1f(p.uniform("uScale"), o.scale);
    glUniform4f(p.uniform("uLevels"), o.levels.enabled ? 1.0f : 0.0f, o.levels.black, o.levels.white,
                o.levels.gamma);
    glUniform1i(p.uniform("uSigned"), o.signedValues ? 1 : 0);
    glUniform1i(p.uniform("uSecond"), o.output == analysis::CurvatureOutput::SecondDerivative ? 1 : 0);
    glBindTextureUnit(1, gradientTexture_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, field_.id());
    glDispatchCompute(groupsX, groupsY, 1);
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
