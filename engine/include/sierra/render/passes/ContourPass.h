#pragma once
// Contour edges: the view-dependent silhouettes of the terrain, recomputed
// every frame in shaders (shaders/contour.vert, contour.frag): the frame's
// mesh drawn again, each fragment darkened where dot(normal, view) changes
// sign within uWidth pixels, the normal taken per vertex from the
// full-resolution heights. They complement line and hatch shading, which are
// view-independent.

#include <sierra/gpu/Program.h>
#include <sierra/render/Pass.h>

#include <glm/glm.hpp>

#include <memory>

namespace sierra::render {

struct ContourPassDesc {
    float width = 1.5f;                        // pixels, > 0
    glm::vec4 colour{0.0f, 0.0f, 0.0f, 1.0f};  // RGBA 0..1
};

class ContourPass final : public Pass {
public:
    // Throws sierra::Error for a width <= 0.
    static std::unique_ptr<ContourPass> create(const ContourPassDesc& desc = {});
    const char* name() const override { return "contours"; }
    void draw(const FrameContext& frame) override;

private:
    gpu::Program program_;
    ContourPassDesc desc_;
};

}  // namespace sierra::render
