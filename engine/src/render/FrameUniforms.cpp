#include <sierra/render/FrameUniforms.h>

#include <algorithm>
#include <cmath>

namespace sierra::render {

FogRange automaticFog(float eyeToCentre, float radius) {
    if (!(radius > 0.0f) || !std::isfinite(radius) || !std::isfinite(eyeToCentre)) return {};
    const float start = std::max(eyeToCentre - radius, 0.0f);
    const float far = std::max(eyeToCentre + radius, 0.0f);
    // fog(d) = 1 - exp(-density * (d - start)) is kAutoFogFarEdge at `far`.
    return {.density = -std::log(1.0f - kAutoFogFarEdge) / std::max(far - start, 1e-6f),
            .start = start};
}

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
