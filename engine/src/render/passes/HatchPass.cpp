#include <sierra/render/passes/HatchPass.h>

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/TerrainGpu.h>

#include <glm/gtc/type_ptr.hpp>

#include <cmath>

namespace sierra::render {

std::unique_ptr<HatchPass> HatchPass::create(std::shared_ptr<const CurvatureGpu> curvature,
                                             const HatchPassDesc& desc) {
    SIERRA_CHECK(curvature != nullptr, "hatch pass: no curvature field");
    SIERRA_CHECK(std::isfinite(desc.length) && desc.length > 0.0f, "hatch pass: length must be > 0 grid units, got ",
                 desc.length);
    SIERRA_CHECK(std::isfinite(desc.width) && desc.width > 0.0f, "hatch pass: width must be > 0 pixels, got ",
                 desc.width);
    auto pass = std::make_unique<HatchPass>();
    pass->program_ = gpu::Program::create({.vertex = "hatch.vert", .fragment = "line.frag"});
    pass->vao_ = gpu::VertexArray::create();
    pass->curvature_ = std::move(curvature);
    pass->desc_ = desc;
    return pass;
}

void HatchPass::draw(const FrameContext& frame) {
    SIERRA_CHECK(curvature_->width() == frame.terrain.side() && curvature_->height() == frame.terrain.side(),
                 "hatch pass: the curvature field is ", curvature_->width(), "x", curvature_->height(),
                 " but the terrain has ", frame.terrain.side(), " samples a side");
    gpu::GlStateScope scope;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(program_.id());
    glUniform1f(program_.uniform("uLength"), desc_.length);
    glUniform1f(program_.uniform("uWidth"), desc_.width);
    glUniform1i(program_.uniform("uAcross"), desc_.direction == analysis::HatchDirection::Across ? 1 : 0);
    glUniform4fv(program_.uniform("uColour"), 1, glm::value_ptr(desc_.colour));
    frame.terrain.bind();
    glBindTextureUnit(3, curvature_->texture().id());
    glBindTextureUnit(4, curvature_->gradient().id());
    glBindVertexArray(vao_.id());
    const GLsizei vertices = GLsizei(curvature_->width()) * GLsizei(curvature_->height());
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, vertices);
}

}  // namespace sierra::render
