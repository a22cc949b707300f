#include <sierra/render/passes/WireframePass.h>

#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/TerrainGpu.h>

#include <glm/gtc/type_ptr.hpp>

namespace sierra::render {

std::unique_ptr<WireframePass> WireframePass::create(const WireframePassDesc& desc) {
    auto pass = std::make_unique<WireframePass>();
    pass->program_ = gpu::Program::create({.vertex = "terrain.vert", .fragment = "wire.frag"});
    pass->colourLocation_ = pass->program_.uniform("uColour");
    pass->colour_ = desc.colour;
    return pass;
}

void WireframePass::draw(const FrameContext& frame) {
    gpu::GlStateScope scope;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glEnable(GL_POLYGON_OFFSET_LINE);
    glPolygonOffset(-1.0f, -1.0f);
    glUseProgram(program_.id());
    glUniform4fv(colourLocation_, 1, glm::value_ptr(colour_));
    frame.terrain.bind();
    frame.mesh.draw();
}

}  // namespace sierra::render
