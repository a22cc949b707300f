#pragma once
// The mesh's vertices as GL points (the "points" display): every vertex of
// every emitted triangle, drawn with polygon mode GL_POINT so the strip needs
// no second index list; the size is fixed-function glPointSize (pixels).

#include <sierra/gpu/Program.h>
#include <sierra/render/Pass.h>

#include <glm/glm.hpp>

#include <memory>

namespace sierra::render {

struct PointsPassDesc {
    glm::vec4 colour{0.95f, 0.35f, 0.1f, 1.0f};  // RGBA, 0..1
    float size = 3.0f;                           // pixels
};

class PointsPass final : public Pass {
  public:
    static std::unique_ptr<PointsPass> create(const PointsPassDesc& desc = {});
    const char* name() const override { return "points"; }
    void draw(const FrameContext& frame) override;

  private:
    gpu::Program program_;
    GLint colourLocation_ = -1;
    PointsPassDesc desc_;
};

}  // namespace sierra::render
