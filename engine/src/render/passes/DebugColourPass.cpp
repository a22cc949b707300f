#include <sierra/render/passes/DebugColourPass.h>

#include "render/passes/PassState.h"

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/TerrainGpu.h>

namespace sierra::render {

ColourBy parseColourBy(const std::string& name) {
    if (name == "surface") return ColourBy::Surface;
    if (name == "level") return ColourBy::Level;
    if (name == "error") return ColourBy::Error;
    throw Error(msg("unknown colouring '", name, "'; expected surface, level or error"));
}

const char* colourByName(ColourBy mode) {
    switch (mode) {
        case ColourBy::Level:
            return "level";
        case ColourBy::Error:
            return "error";
        default:
            return "surface";
    }
}

std::unique_ptr<DebugColourPass> DebugColourPass::create() {
    auto pass = std::make_unique<DebugColourPass>();
    pass->program_ = gpu::Program::create({.vertex = "debug_colour.vert",
                                           .fragment = "debug_colour.frag",
                                           .geometry = "debug_colour_geom.glsl"});
    pass->modeLocation_ = pass->program_.uniform("uMode");
    return pass;
}

void DebugColourPass::draw(const FrameContext& frame) {
    gpu::GlStateScope scope;
    setOpaqueMeshState();
    glUseProgram(program_.id());
    glUniform1i(modeLocation_, mode_ == ColourBy::Error ? 1 : 0);
    frame.terrain.bind();
    frame.mesh.draw();
}

}  // namespace sierra::render
