#pragma once
// Where a frame is drawn: the context's pbuffer directly, or a multisampled
// framebuffer that is resolved into the pbuffer before read-back.

#include <sierra/gpu/Objects.h>
#include <sierra/gpu/ReadBack.h>

#include <glm/glm.hpp>

namespace sierra::render {

struct FrameTargetDesc {
    int width = 640;  // must match the pbuffer
    int height = 360;
    int samples = 0;  // 0 = draw straight into the pbuffer; 2..16 = MSAA through an FBO
};

class FrameTarget {
  public:
    static FrameTarget create(const FrameTargetDesc& desc);

    // Binds the target, sets the viewport, clears colour (RGBA) and depth.
    void begin(const glm::vec4& clearColour);
    // Resolves multisampling into the pbuffer and binds the pbuffer for reading.
    void resolve();
    // resolve() then a synchronous read-back.
    gpu::Image read();

    int width() const { return desc_.width; }
    int height() const { return desc_.height; }
    int samples() const { return desc_.samples; }

  private:
    FrameTargetDesc desc_;
    gpu::Framebuffer fbo_;
    gpu::Texture colour_;
    gpu::Texture depth_;
};

}  // namespace sierra::render
