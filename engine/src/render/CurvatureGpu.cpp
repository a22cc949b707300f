#include <sierra/render/CurvatureGpu.h>

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace sierra::render {

namespace {
constexpr int kGroupSize = 16;  // curvature.comp's local size, both axes
}

CurvatureGpu CurvatureGpu::create(const terrain::Heightfield& field) {
    SIERRA_CHECK(!field.empty(), "GPU curvature: the heightfield is empty");
    CurvatureGpu c;
    c.width_ = field.width();
    c.height_ = field.height();
    c.spacingX_ = field.spacingX();
    c.spacingZ_ = field.spacingZ();
    c.gradientProgram_ = gpu::Program::create({.compute = "curvature.comp", .defines = "#define CURVATURE_GRADIENT 1\n"});
    for (int m = 0; m < 4; ++m) {
        std::string defines = "#define CURVATURE_METHOD " + std::to_string(m) + "\n";
        c.fieldPrograms_[size_t(m)] = gpu::Program::create({.compute = "curvature.comp", .defines = defines});
    }

    std::vector<float> heights(field.samples().begin(), field.samples().end());
    const float scale = field.verticalScale();
    const bool masked = field.hasMask();
    auto mask = field.mask();
    for (size_t k = 0; k < heights.size(); ++k) heights[k] = masked && !mask[k] ? NAN : heights[k] * scale;

    gpu::GlStateScope scope;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    c.heights_ = gpu::Buffer::create({.size = heights.size() * sizeof(float), .data = heights.data()});
    c.gradient_ = gpu::Texture::create(
        {.format = GL_RG32F, .width = c.width_, .height = c.height_, .filter = GL_NEAREST});
    c.field_ = gpu::Texture::create(
        {.format = GL_RGBA32F, .width = c.width_, .height = c.height_, .filter = GL_NEAREST});
    return c;
}

void CurvatureGpu::compute(const analysis::CurvatureOptions& o, bool tangentPlanes) {
    analysis::validate(o);
    const int minSide = std::max(3, 2 * o.distance + 1);
    SIERRA_CHECK(width_ >= minSide && height_ >= minSide, "curvature: a ", width_, "x", height_,
                 " grid is too small for reinforcement distance ", o.distance, " (each side needs at least ",
                 minSide, " samples)");
    gpu::GlStateScope scope;
    const GLuint groupsX = GLuint((width_ + kGroupSize - 1) / kGroupSize);
    const GLuint groupsY = GLuint((height_ + kGroupSize - 1) / kGroupSize);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, heights_.id());
    const bool normalBased =
        o.method == analysis::CurvatureMethod::TwoNormal || o.method == analysis::CurvatureMethod::ThreeNormal;
    if (normalBased || tangentPlanes) {
        glUseProgram(gradientProgram_.id());
        glUniform2i(gradientProgram_.uniform("uSize"), width_, height_);
        glUniform2f(gradientProgram_.uniform("uSpacing"), spacingX_, spacingZ_);
        glUniform1i(gradientProgram_.uniform("uNormals"), int(o.normals));
        glBindImageTexture(0, gradient_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
        glDispatchCompute(groupsX, groupsY, 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    const gpu::Program& p = fieldPrograms_[size_t(o.method)];
    glUseProgram(p.id());
    glUniform2i(p.uniform("uSize"), width_, height_);
    glUniform2f(p.uniform("uSpacing"), spacingX_, spacingZ_);
    glUniform1i(p.uniform("uDistance"), o.distance);
    glUniform1f(p.uniform("uScale"), o.scale);
    glUniform4f(p.uniform("uLevels"), o.levels.enabled ? 1.0f : 0.0f, o.levels.black, o.levels.white,
                o.levels.gamma);
    glUniform1i(p.uniform("uSigned"), o.signedValues ? 1 : 0);
    glUniform1i(p.uniform("uSecond"), o.output == analysis::CurvatureOutput::SecondDerivative ? 1 : 0);
    glBindTextureUnit(1, gradient_.id());
    glBindImageTexture(0, field_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(groupsX, groupsY, 1);
    // Any later reader: the hatch pass's texel fetches, or a read-back.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);  // not part of GlState
}

analysis::CurvatureField CurvatureGpu::read() const {
    analysis::CurvatureField out;
    out.width = width_;
    out.height = height_;
    out.spacingX = spacingX_;
    out.spacingZ = spacingZ_;
    out.values.resize(size_t(width_) * size_t(height_) * analysis::kDirectionCount);
    gpu::GlStateScope scope;
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(field_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(out.values.size() * sizeof(float)),
                      out.values.data());
    return out;
}

}  // namespace sierra::render
