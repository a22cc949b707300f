#include <sierra/render/passes/ContourPass.h>

#include <sierra/core/Error.h>
#include <sierra/render/passes/TerrainPass.h>

#include <cmath>

namespace sierra::render {

std::unique_ptr<ContourPass> ContourPass::create(const ContourPassDesc& desc) {
    SIERRA_CHECK(std::isfinite(desc.width) && desc.width > 0.0f,
                 "contour pass: width must be > 0 pixels, got ", desc.width);
    auto pass = std::make_unique<ContourPass>();
    pass->desc_ = desc;
    return pass;
}

void ContourPass::shadeTerrain(TerrainShading& shading) const {
    shading.contourWidth = desc_.width;
    shading.contourColour = desc_.colour;
}

void ContourPass::draw(const FrameContext& /*frame*/) {
    // Nothing to draw: the terrain pass drew the edges (shadeTerrain).
}

}  // namespace sierra::render
