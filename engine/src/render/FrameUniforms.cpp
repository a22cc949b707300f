#include <sierra/render/FrameUniforms.h>

namespace sierra::render {

static_assert(sizeof(FrameUniformData) == 64 + 7 * 16,
              "FrameUniformData must match std140 `uniform Frame`");

FrameUniforms FrameUniforms::create() {
    FrameUniforms u;
    u.buffer_ =
        gpu::Buffer::create({.size = sizeof(FrameUniformData), .flags = GL_DYNAMIC_STORAGE_BIT});
    return u;
}

void FrameUniforms::update(const FrameUniformData& data) {
    glNamedBufferSubData(buffer_.id(), 0, sizeof(data), &data);
    glBindBufferBase(GL_UNIFORM_BUFFER, kFrameUniformBinding, buffer_.id());
}

}  // namespace sierra::render
