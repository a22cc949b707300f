#include <sierra/render/FrameTarget.h>

#include <sierra/core/Error.h>

namespace sierra::render {

namespace {
// A framebuffer with an RGBA8 colour and a 32-bit float depth texture of
// `desc`'s target, size and samples.
gpu::Framebuffer colourAndDepth(gpu::TextureDesc desc, gpu::Texture& colour, gpu::Texture& depth,
                                const char* what) {
    desc.format = GL_RGBA8;
    colour = gpu::Texture::create(desc);
    desc.format = GL_DEPTH_COMPONENT32F;
    depth = gpu::Texture::create(desc);
    gpu::Framebuffer fbo = gpu::Framebuffer::create();
    fbo.attach(GL_COLOR_ATTACHMENT0, colour);
    fbo.attach(GL_DEPTH_ATTACHMENT, depth);
    fbo.checkComplete(what);
    return fbo;
}
}  // namespace

FrameTarget FrameTarget::create(const FrameTargetDesc& desc) {
    SIERRA_CHECK(desc.samples == 0 || (desc.samples >= 2 && desc.samples <= 16),
                 "multisampling takes 0 (off) or 2..16 samples, got ", desc.samples);
    FrameTarget target;
    target.desc_ = desc;
    if (desc.offscreen) {
        GLint maxSide = 0;
        glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSide);
        SIERRA_CHECK(
            desc.width >= 1 && desc.height >= 1 && desc.width <= maxSide && desc.height <= maxSide,
            "an offscreen frame target of ", desc.width, "x", desc.height,
            " pixels; this GL draws at most ", maxSide, " pixels a side");
        target.resolved_ =
            colourAndDepth({.width = desc.width, .height = desc.height}, target.resolvedColour_,
                           target.resolvedDepth_, "offscreen frame target");
    }
    if (desc.samples > 0) {
        GLint maxSamples = 0;
        glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
        SIERRA_CHECK(desc.samples <= maxSamples, desc.samples,
                     "x multisampling requested; this GL offers at most ", maxSamples);
        target.fbo_ = colourAndDepth({.target = GL_TEXTURE_2D_MULTISAMPLE,
                                      .width = desc.width,
                                      .height = desc.height,
                                      .samples = desc.samples},
                                     target.colour_, target.depth_, "multisampled frame target");
    }
    return target;
}

void FrameTarget::begin(const glm::vec4& clearColour) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_ ? fbo_.id() : resolved_.id());
    glViewport(0, 0, desc_.width, desc_.height);
    glClearColor(clearColour.r, clearColour.g, clearColour.b, clearColour.a);
    glClearDepth(1.0);
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void FrameTarget::resolve() {
    // resolved_ is 0 (the pbuffer) unless offscreen.
    if (fbo_) {
        glBlitNamedFramebuffer(fbo_.id(), resolved_.id(), 0, 0, desc_.width, desc_.height, 0, 0,
                               desc_.width, desc_.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, resolved_.id());
}

gpu::Image FrameTarget::read() {
    resolve();
    return gpu::readFramebuffer(desc_.width, desc_.height);
}

}  // namespace sierra::render
