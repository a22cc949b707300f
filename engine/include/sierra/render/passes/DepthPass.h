#pragma once
// Linear eye-space depth of the terrain, per pixel: its own float target (not
// the frame's), cleared to NaN where no terrain is, read back in image order.

#include <sierra/gpu/Objects.h>
#include <sierra/gpu/Program.h>
#include <sierra/render/Pass.h>

#include <memory>
#include <vector>

namespace sierra::render {

struct DepthImage {
    int width = 0;
    int height = 0;
    std::vector<float> depth;  // width * height, top row first; NaN = no terrain
};

class DepthPass final : public Pass {
  public:
    static std::unique_ptr<DepthPass> create(int width, int height);
    const char* name() const override { return "depth"; }
    // Renders into the pass's own target (the bound framebuffer is untouched).
    void draw(const FrameContext& frame) override;
    // The depth of the last draw().
    DepthImage read() const;
    int width() const { return width_; }
    int height() const { return height_; }

  private:
    int width_ = 0, height_ = 0;
    gpu::Program program_;
    gpu::Framebuffer fbo_;
    gpu::Texture depthValue_;
    gpu::Texture depthBuffer_;
};

}  // namespace sierra::render
