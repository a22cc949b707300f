#pragma once
// The triangulation's edges over the shaded terrain: the same mesh drawn as
// lines, pulled towards the camera by a polygon offset so they win the depth
// test against the faces they border.

#include <sierra/gpu/Program.h>
#include <sierra/render/Pass.h>

#include <glm/glm.hpp>

#include <memory>

namespace sierra::render {

struct WireframePassDesc {
    glm::vec4 colour{0.08f, 0.08f, 0.1f, 1.0f};  // RGBA, 0..1
};

class WireframePass final : public Pass {
  public:
    static std::unique_ptr<WireframePass> create(const WireframePassDesc& desc = {});
    const char* name() const override { return "wireframe"; }
    void draw(const FrameContext& frame) override;

  private:
    gpu::Program program_;
    GLint colourLocation_ = -1;
    glm::vec4 colour_{0.0f};
};

}  // namespace sierra::render
