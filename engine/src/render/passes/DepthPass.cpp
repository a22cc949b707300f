#include <sierra/render/passes/DepthPass.h>

#include "render/passes/PassState.h"

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/TerrainGpu.h>

#include <cstring>
#include <limits>

namespace sierra::render {

std::unique_ptr<DepthPass> DepthPass::create(int width, int height) {
    SIERRA_CHECK(width > 0 && height > 0, "depth pass needs a frame size, got ", width, "x",
                 height);
    auto pass = std::make_unique<DepthPass>();
    pass->width_ = width;
    pass->height_ = height;
    pass->program_ = gpu::Program::create({.vertex = "terrain.vert", .fragment = "depth.frag"});
    pass->depthValue_ = gpu::Texture::create(
        {.format = GL_R32F, .width = width, .height = height, .filter = GL_NEAREST});
    pass->depthBuffer_ = gpu::Texture::create(
        {.format = GL_DEPTH_COMPONENT32F, .width = width, .height = height, .filter = GL_NEAREST});
    pass->fbo_ = gpu::Framebuffer::create();
    pass->fbo_.attach(GL_COLOR_ATTACHMENT0, pass->depthValue_);
    pass->fbo_.attach(GL_DEPTH_ATTACHMENT, pass->depthBuffer_);
    pass->fbo_.checkComplete("depth target");
    return pass;
}

void DepthPass::draw(const FrameContext& frame) {
    gpu::GlStateScope scope;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, width_, height_);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float far = 1.0f;
    glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, &nan);
    setOpaqueMeshState();  // depth writes on before the depth clear
    glClearNamedFramebufferfv(fbo_.id(), GL_DEPTH, 0, &far);
    glUseProgram(program_.id());
    frame.terrain.bind();
    frame.mesh.draw();
}

DepthImage DepthPass::read() const {
    gpu::GlStateScope scope;
    std::vector<float> raw(size_t(width_) * height_);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(depthValue_.id(), 0, GL_RED, GL_FLOAT, GLsizei(raw.size() * sizeof(float)),
                      raw.data());
    gpu::checkGlErrors("glGetTextureImage (depth)");
    DepthImage out{width_, height_, std::vector<float>(raw.size())};
    // GL's rows run bottom-up; images run top-down.
    for (int y = 0; y < height_; ++y)
        std::memcpy(out.depth.data() + size_t(y) * width_,
                    raw.data() + size_t(height_ - 1 - y) * width_, size_t(width_) * sizeof(float));
    return out;
}

}  // namespace sierra::render
