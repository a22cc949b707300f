#include <sierra/render/passes/ContourPass.h>

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include "render/passes/OverlayState.h"
#include <sierra/render/TerrainGpu.h>

#include <glm/gtc/type_ptr.hpp>

#include <cmath>

namespace sierra::render {

std::unique_ptr<ContourPass> ContourPass::create(const ContourPassDesc& desc) {
    SIERRA_CHECK(std::isfinite(desc.width) && desc.width > 0.0f, "contour pass: width must be > 0 pixels, got ",
                 desc.width);
    auto pass = std::make_unique<ContourPass>();
    pass->program_ = gpu::Program::create(
        {.vertex = "contour.vert", .fragment = "contour.frag", .geometry = "contour_geom.glsl"});
    pass->desc_ = desc;
    return pass;
}

void ContourPass::draw(const FrameContext& frame) {
    gpu::GlStateScope scope;
    // The same mesh as the terrain pass: equal depths pass LEQUAL. With the
    // geometry stage in the pipeline llvmpipe (Mesa 22.3) rounds the depths
    // of the same triangles differently from the terrain pass, so 0.3% of
    // the contour pixels failed the test; eight depth units towards the eye
    // make them pass again, and are far below any visible occlusion.
    setOverlayState();
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(0.0f, -8.0f);
    glUseProgram(program_.id());
    glUniform1f(program_.uniform("uWidth"), desc_.width);
    glUniform4fv(program_.uniform("uColour"), 1, glm::value_ptr(desc_.colour));
    frame.terrain.bind();
    frame.mesh.draw();
}

}  // namespace sierra::render
