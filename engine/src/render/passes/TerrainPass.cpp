#include <sierra/render/passes/TerrainPass.h>

#include "render/passes/PassState.h"

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/TerrainGpu.h>

#include <glm/gtc/type_ptr.hpp>

namespace sierra::render {

namespace {

gpu::Program buildProgram(const std::string& surfaceFile, const std::string& baseFile,
                          const std::string& defines) {
    const gpu::IncludeAlias aliases[] = {{"surface.glsl", surfaceFile},
                                         {"surface_base.glsl", baseFile}};
    return gpu::Program::create(
        {.vertex = "terrain.vert",
         .fragment = "terrain.frag",
         .defines = defines,
         .aliases = std::span<const gpu::IncludeAlias>(aliases, baseFile.empty() ? 1 : 2)});
}

}  // namespace

std::unique_ptr<TerrainPass> TerrainPass::create(std::unique_ptr<Surface> surface) {
    SIERRA_CHECK(surface != nullptr, "the terrain pass needs a surface");
    auto pass = std::make_unique<TerrainPass>();
    pass->surfaceFile_ = surface->shaderFile();
    pass->baseFile_ = surface->baseShaderFile();
    pass->lit_ = surface->lit();
    pass->defines_ = surface->defines() + (pass->lit_ ? "" : "#define SIERRA_UNLIT 1\n");
    pass->program(false, false);  // the plain variant now: a bad surface fails at creation
    pass->surface_ = std::move(surface);
    return pass;
}

const gpu::Program& TerrainPass::program(bool contours, bool relief) {
    relief = relief && lit_;
    gpu::Program& program = programs_[size_t(contours ? 1 : 0) | size_t(relief ? 2 : 0)];
    if (program.id() == 0)
        program = buildProgram(surfaceFile_, baseFile_,
                               defines_ + (contours ? "#define SIERRA_CONTOURS 1\n" : "") +
                                   (relief ? "#define SIERRA_RELIEF_LIGHT 1\n" : ""));
    return program;
}

void TerrainPass::draw(const FrameContext& frame) {
    gpu::GlStateScope scope;
    setOpaqueMeshState();
    const bool contours = shading_.contourWidth > 0.0f;
    const bool relief = shading_.relief && lit_;
    const gpu::Program& program = this->program(contours, relief);
    glUseProgram(program.id());
    if (contours) {
        glUniform1f(program.uniform("uContourWidth"), shading_.contourWidth);
        glUniform4fv(program.uniform("uContourColour"), 1, glm::value_ptr(shading_.contourColour));
    }
    frame.terrain.bind();
    if (relief) frame.terrain.bindRelief();
    surface_->bind();
    frame.mesh.draw();
}

}  // namespace sierra::render
