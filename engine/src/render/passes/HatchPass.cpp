#include <sierra/render/passes/HatchPass.h>

#include "render/passes/PassState.h"
#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/TerrainGpu.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>

namespace sierra::render {

std::unique_ptr<HatchPass> HatchPass::create(std::shared_ptr<const CurvatureGpu> curvature,
                                             const HatchPassDesc& desc) {
    SIERRA_CHECK(curvature != nullptr, "hatch pass: no curvature field");
    SIERRA_CHECK(std::isfinite(desc.length) && desc.length > 0.0f,
                 "hatch pass: length must be > 0 grid units, got ", desc.length);
    SIERRA_CHECK(std::isfinite(desc.width) && desc.width > 0.0f,
                 "hatch pass: width must be > 0 pixels, got ", desc.width);
    SIERRA_CHECK(std::isfinite(desc.opacityGain) && desc.opacityGain > 0.0f,
                 "hatch pass: opacity gain must be > 0, got ", desc.opacityGain);
    auto pass = std::make_unique<HatchPass>();
    pass->program_ = gpu::Program::create(
        {.vertex = "hatch.vert", .fragment = "line.frag", .geometry = "hatch_geom.glsl"});
    pass->vao_ = gpu::VertexArray::create();
    pass->curvature_ = std::move(curvature);
    pass->desc_ = desc;
    // The view-independent stroke field, once: direction and opacity per sample.
    static_assert(CurvatureGpu::kRun == 8,
                  "hatch_strokes.comp reads the curvature layout of runs of 8");
    const CurvatureGpu& c = *pass->curvature_;
    gpu::Program strokes = gpu::Program::create({.compute = "hatch_strokes.comp"});
    pass->strokes_ = gpu::Texture::create(
        {.format = GL_RGBA32F, .width = c.width(), .height = c.height(), .filter = GL_NEAREST});
    {
        gpu::GlStateScope scope;
        glUseProgram(strokes.id());
        glUniform2i(strokes.uniform("uSize"), c.width(), c.height());
        glUniform2f(strokes.uniform("uSpacing"), c.spacing().x, c.spacing().y);
        glUniform1i(strokes.uniform("uAcross"),
                    desc.direction == analysis::HatchDirection::Across ? 1 : 0);
        glBindTextureUnit(0, c.texture().id());
        glBindTextureUnit(1, c.gradient().id());
        glBindImageTexture(0, pass->strokes_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glDispatchCompute(GLuint((c.width() + 15) / 16), GLuint((c.height() + 15) / 16), 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    }
    return pass;
}

int HatchPass::baseStride(const FrameContext& frame) {
    const SceneBounds b = frame.terrain.bounds();
    const Camera& c = frame.camera;
    const glm::vec3 nearest = glm::clamp(c.position, b.min, b.max);
    const float distance = glm::length(nearest - c.position);
    const float spacing = std::min(frame.terrain.spacing().x, frame.terrain.spacing().y);
    float cellPx = 0.0f;
    if (c.projection == Projection::Orthographic) {
        cellPx = spacing * float(frame.height) / std::max(c.orthoHeight, 1e-6f);
    } else {
        if (distance <= 0.0f) return 1;  // the camera is inside the terrain's box
        cellPx = spacing * float(frame.height) /
                 (2.0f * std::tan(glm::radians(c.fovYDegrees) * 0.5f) * distance);
    }
    int stride = 1;
    // hatch.vert keeps a vertex when its stride s (the smallest power of two
    // with cellPx * s >= kMinCellPixels) divides its indices. Its cellPx is
    // measured along the view depth, up to about 1.25x this one off-axis, so
    // the smallest per-vertex stride is >= 0.8 kMinCellPixels / cellPx; the
    // power of two found here is below 0.7 kMinCellPixels / cellPx, hence
    // divides it, and the lattice holds every kept vertex.
    while (cellPx * float(stride) * 2.0f < kMinCellPixels * 0.7f && stride < 4096) stride *= 2;
    return stride;
}

void HatchPass::draw(const FrameContext& frame) {
    SIERRA_CHECK(
        curvature_->width() == frame.terrain.side() && curvature_->height() == frame.terrain.side(),
        "hatch pass: the curvature field is ", curvature_->width(), "x", curvature_->height(),
        " but the terrain has ", frame.terrain.side(), " samples a side");
    gpu::GlStateScope scope;
    setOverlayState();
    glUseProgram(program_.id());
    glUniform1f(program_.uniform("uLength"), desc_.length);
    glUniform1f(program_.uniform("uOpacityGain"), desc_.opacityGain);
    glUniform1f(program_.uniform("uWidth"), desc_.width);
    glUniform4fv(program_.uniform("uColour"), 1, glm::value_ptr(desc_.colour));
    frame.terrain.bind();
    glBindTextureUnit(3, strokes_.id());
    // The coarsest lattice every kept stroke is on: the thinning stride of the
    // largest grid cell on the screen (at the terrain's nearest point), so a
    // far or small view of a large grid runs the vertex shader for a
    // fraction of its vertices. hatch.vert thins further per vertex.
    const int base = baseStride(frame);
    const int perSide = (frame.terrain.side() - 1) / base + 1;
    glUniform1i(program_.uniform("uBaseStride"), base);
    glUniform1i(program_.uniform("uLatticeSide"), perSide);
    glBindVertexArray(vao_.id());
    // One point per stroke; hatch_geom.glsl makes the quads. (llvmpipe sets up
    // its vertex pipeline once per instance, so instanced quads cost more.)
    glDrawArrays(GL_POINTS, 0, GLsizei(perSide) * GLsizei(perSide));
}

}  // namespace sierra::render
