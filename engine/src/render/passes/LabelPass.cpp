#include <sierra/render/passes/LabelPass.h>

#include "render/passes/PassState.h"

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/TerrainGpu.h>

#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstring>
#include <limits>

namespace sierra::render {

std::unique_ptr<LabelPass> LabelPass::create(int width, int height, const Surface* zoneSurface) {
    SIERRA_CHECK(width > 0 && height > 0, "label pass needs a frame size, got ", width, "x",
                 height);
    SIERRA_CHECK(!zoneSurface || zoneSurface->zoneIds(),
                 "the label pass's zone ids need a zone surface");
    auto pass = std::make_unique<LabelPass>();
    pass->width_ = width;
    pass->height_ = height;
    pass->zoneSurface_ = zoneSurface;
    pass->program_ =
        gpu::Program::create({.vertex = "terrain.vert",
                              .fragment = "labels.frag",
                              .defines = zoneSurface ? "#define SIERRA_ZONE_IDS 1\n" : ""});
    pass->normals_ = gpu::Texture::create(
        {.format = GL_RGBA32F, .width = width, .height = height, .filter = GL_NEAREST});
    pass->zones_ = gpu::Texture::create(
        {.format = GL_R8UI, .width = width, .height = height, .filter = GL_NEAREST});
    pass->depthBuffer_ = gpu::Texture::create(
        {.format = GL_DEPTH_COMPONENT32F, .width = width, .height = height, .filter = GL_NEAREST});
    pass->fbo_ = gpu::Framebuffer::create();
    pass->fbo_.attach(GL_COLOR_ATTACHMENT0, pass->normals_);
    pass->fbo_.attach(GL_COLOR_ATTACHMENT1, pass->zones_);
    pass->fbo_.attach(GL_DEPTH_ATTACHMENT, pass->depthBuffer_);
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(pass->fbo_.id(), 2, buffers);
    pass->fbo_.checkComplete("label target");
    return pass;
}

void LabelPass::draw(const FrameContext& frame) {
    gpu::GlStateScope scope;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, width_, height_);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float noNormal[] = {nan, nan, nan, 0.0f};
    const GLuint noZone[] = {kNoZone, 0, 0, 0};
    const float far = 1.0f;
    glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, noNormal);
    glClearNamedFramebufferuiv(fbo_.id(), GL_COLOR, 1, noZone);
    setOpaqueMeshState();  // depth writes on before the depth clear
    glClearNamedFramebufferfv(fbo_.id(), GL_DEPTH, 0, &far);
    glUseProgram(program_.id());
    glUniformMatrix3fv(program_.uniform("uNormalRotation"), 1, GL_FALSE, glm::value_ptr(rotation_));
    frame.terrain.bind();
    if (zoneSurface_) zoneSurface_->bind();
    frame.mesh.draw();
}

LabelImage LabelPass::read() const {
    gpu::GlStateScope scope;
    const size_t pixels = size_t(width_) * size_t(height_);
    std::vector<float> rgba(pixels * 4);
    std::vector<uint8_t> ids(pixels);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(normals_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)),
                      rgba.data());
    glGetTextureImage(zones_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, GLsizei(ids.size()),
                      ids.data());
    gpu::checkGlErrors("glGetTextureImage (labels)");
    LabelImage out{width_, height_, std::vector<float>(pixels * 3), std::vector<uint8_t>(pixels),
                   std::vector<uint8_t>(pixels)};
    // GL's rows run bottom-up; images run top-down.
    for (int y = 0; y < height_; ++y) {
        const size_t from = size_t(height_ - 1 - y) * size_t(width_),
                     to = size_t(y) * size_t(width_);
        for (int x = 0; x < width_; ++x) {
            const float* p = &rgba[(from + size_t(x)) * 4];
            const bool terrain = p[3] > 0.5f;
            std::memcpy(&out.normals[(to + size_t(x)) * 3], p, 3 * sizeof(float));
            out.mask[to + size_t(x)] = terrain ? 255 : 0;
            out.zones[to + size_t(x)] = terrain ? ids[from + size_t(x)] : kNoZone;
        }
    }
    return out;
}

}  // namespace sierra::render
