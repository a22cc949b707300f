#include <sierra/render/passes/TerrainPass.h>

#include "render/passes/PassState.h"

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/TerrainGpu.h>

#include <glm/gtc/type_ptr.hpp>

namespace sierra::render {

namespace {

gpu::Program buildProgram(const std::string& surfaceFile, const std::string& defines) {
    gpu::IncludeAlias alias{"surface.glsl", surfaceFile};
    return gpu::Program::create({.vertex = "terrain.vert",
                                 .fragment = "terrain.frag",
                                 .defines = defines,
                                 .aliases = std::span<const gpu::IncludeAlias>(&alias, 1)});
}

}  // namespace

std::unique_ptr<TerrainPass> TerrainPass::create(std::unique_ptr<Surface> surface) {
    SIERRA_CHECK(surface != nullptr, "the terrain pass needs a surface");
    auto pass = std::make_unique<TerrainPass>();
    pass->surfaceFile_ = surface->shaderFile();
    pass->defines_ = surface->defines();
    pass->program_ = buildProgram(pass->surfaceFile_, pass->defines_);
    pass->surface_ = std::move(surface);
    return pass;
}

void TerrainPass::draw(const FrameContext& frame) {
    gpu::GlStateScope scope;
    setOpaqueMeshState();
    const bool contours = shading_.contourWidth > 0.0f;
    if (contours && contourProgram_.id() == 0)
        contourProgram_ = buildProgram(surfaceFile_, defines_ + "#define SIERRA_CONTOURS 1\n");
    const gpu::Program& program = contours ? contourProgram_ : program_;
    glUseProgram(program.id());
    if (contours) {
        glUniform1f(program.uniform("uContourWidth"), shading_.contourWidth);
        glUniform4fv(program.uniform("uContourColour"), 1, glm::value_ptr(shading_.contourColour));
    }
    frame.terrain.bind();
    surface_->bind();
    frame.mesh.draw();
}

}  // namespace sierra::render
