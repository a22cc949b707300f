#include <sierra/render/passes/PointsPass.h>

#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/TerrainGpu.h>

#include <glm/gtc/type_ptr.hpp>

namespace sierra::render {

std::unique_ptr<PointsPass> PointsPass::create(const PointsPassDesc& desc) {
    auto pass = std::make_unique<PointsPass>();
    pass->program_ = gpu::Program::create({.vertex = "terrain.vert", .fragment = "wire.frag"});
    pass->colourLocation_ = pass->program_.uniform("uColour");
    pass->desc_ = desc;
    return pass;
}

void PointsPass::draw(const FrameContext& frame) {
    gpu::GlStateScope scope;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    glDisable(GL_PROGRAM_POINT_SIZE);
    glPointSize(desc_.size);
    glPolygonMode(GL_FRONT_AND_BACK, GL_POINT);
    glEnable(GL_POLYGON_OFFSET_POINT);
    glPolygonOffset(-1.0f, -2.0f);
    glUseProgram(program_.id());
    glUniform4fv(colourLocation_, 1, glm::value_ptr(desc_.colour));
    frame.terrain.bind();
    frame.mesh.draw();
    // Not in GlStateScope's list: put back by hand.
    glPointSize(1.0f);
    glDisable(GL_POLYGON_OFFSET_POINT);
}

}  // namespace sierra::render
