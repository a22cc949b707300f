#include <sierra/render/passes/TerrainPass.h>

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/TerrainGpu.h>

namespace sierra::render {

std::unique_ptr<TerrainPass> TerrainPass::create(std::unique_ptr<Surface> surface) {
    SIERRA_CHECK(surface != nullptr, "the terrain pass needs a surface");
    auto pass = std::make_unique<TerrainPass>();
    std::string file = surface->shaderFile();
    gpu::IncludeAlias alias{"surface.glsl", file};
    std::string defines = surface->defines();
    pass->program_ = gpu::Program::create({.vertex = "terrain.vert", .fragment = "terrain.frag", .defines = defines,
                                           .aliases = std::span<const gpu::IncludeAlias>(&alias, 1)});
    pass->surface_ = std::move(surface);
    return pass;
}

void TerrainPass::draw(const FrameContext& frame) {
    gpu::GlStateScope scope;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glUseProgram(program_.id());
    frame.terrain.bind();
    surface_->bind();
    frame.mesh.draw();
}

}  // namespace sierra::render
