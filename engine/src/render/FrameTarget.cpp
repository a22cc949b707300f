#include <sierra/render/FrameTarget.h>

#include <sierra/core/Error.h>

namespace sierra::render {

FrameTarget FrameTarget::create(const FrameTargetDesc& desc) {
    SIERRA_CHECK(desc.samples == 0 || (desc.samples >= 2 && desc.samples <= 16),
                 "multisampling takes 0 (off) or 2..16 samples, got ", desc.samples);
    FrameTarget target;
    target.desc_ = desc;
    if (desc.offscreen) {
        GLint maxSide = 0;
        glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSide);
        SIERRA_CHECK(desc.width >= 1 && desc.height >= 1 && desc.width <= maxSide &&
                         desc.height <= maxSide,
                     "an offscreen frame target of ", desc.width, "x", desc.height,
                     " pixels; this GL draws at most ", maxSide, " pixels a side");
        gpu::TextureDesc t{.format = GL_RGBA8, .width = desc.width, .height = desc.height};
        target.resolvedColour_ = gpu::Texture::create(t);
        t.format = GL_DEPTH_COMPONENT32F;
        target.resolvedDepth_ = gpu::Texture::create(t);
        target.resolved_ = gpu::Framebuffer::create();
        target.resolved_.attach(GL_COLOR_ATTACHMENT0, target.resolvedColour_);
        target.resolved_.attach(GL_DEPTH_ATTACHMENT, target.resolvedDepth_);
        target.resolved_.checkComplete("offscreen frame target");
    }
    if (desc.samples > 0) {
        GLint maxSamples = 0;
        glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
        SIERRA_CHECK(desc.samples <= maxSamples, desc.samples,
                     "x multisampling requested; this GL offers at most ", maxSamples);
        gpu::TextureDesc t{.target = GL_TEXTURE_2D_MULTISAMPLE,
                           .format = GL_RGBA8,
                           .width = desc.width,
                           .height = desc.height,
                           .samples = desc.samples};
        target.colour_ = gpu::Texture::create(t);
        t.format = GL_DEPTH_COMPONENT32F;
        target.depth_ = gpu::Texture::create(t);
        target.fbo_ = gpu::Framebuffer::create();
        target.fbo_.attach(GL_COLOR_ATTACHMENT0, target.colour_);
        target.fbo_.attach(GL_DEPTH_ATTACHMENT, target.depth_);
        target.fbo_.checkComplete("multisampled frame target");
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
