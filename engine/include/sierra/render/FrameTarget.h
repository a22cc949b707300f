#pragma once
// Where a frame is drawn: the context's pbuffer directly, or a multisampled
// framebuffer that is resolved into the pbuffer before read-back.

#include <sierra/gpu/Objects.h>
#include <sierra/gpu/ReadBack.h>

#include <glm/glm.hpp>

namespace sierra::render {

struct FrameTargetDesc {
    int width = 640;  // must match the pbuffer, unless offscreen
    int height = 360;
    int samples = 0;  // 0 = draw straight into the pbuffer; 2..16 = MSAA through an FBO
    // Resolve into a framebuffer of its own (RGBA8 colour and depth) instead
    // of the pbuffer: a target of any size up to the driver's limits, e.g. a
    // debug snapshot taller than the frame.
    bool offscreen = false;
};

class FrameTarget {
  public:
    static FrameTarget create(const FrameTargetDesc& desc);

    // Binds the target, sets the viewport, clears colour (RGBA) and depth.
    void begin(const glm::vec4& clearColour);
    // Resolves multisampling into the pbuffer (or the offscreen framebuffer)
    // and binds that framebuffer for drawing and reading.
    void resolve();
    // resolve() then a synchronous read-back.
    gpu::Image read();

    int width() const { return desc_.width; }
    int height() const { return desc_.height; }
    int samples() const { return desc_.samples; }

  private:
    FrameTargetDesc desc_;
    gpu::Framebuffer fbo_;  // multisampled
    gpu::Texture colour_;
    gpu::Texture depth_;
    gpu::Framebuffer resolved_;  // offscreen: what resolve() binds instead of the pbuffer
    gpu::Texture resolvedColour_;
    gpu::Texture resolvedDepth_;
};

}  // namespace sierra::render
