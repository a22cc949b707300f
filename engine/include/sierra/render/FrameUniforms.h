#pragma once
// The per-frame uniform block every pass reads (std140, binding 0; its GLSL
// side is shaders/frame.glsl): view-projection, eye, frame size, lambda and
// tau, sun, fog and sky. Written once per frame, bound once, read by all passes.

#include <sierra/gpu/Objects.h>

#include <glm/glm.hpp>

namespace sierra::render {

inline constexpr GLuint kFrameUniformBinding = 0;
inline constexpr GLuint kTerrainUniformBinding = 1;

// Automatic fog (Lighting::fogDensity < 0): aerial perspective over the framed
// terrain whatever the camera's distance. No haze up to the near edge of the
// terrain's bounding sphere seen from the eye; from there the haze grows
// exponentially, to kAutoFogFarEdge of the way to the sky colour at the
// sphere's far edge (a camera inside the sphere: from the eye to the far edge).
inline constexpr float kAutoFogFarEdge = 0.4f;
struct FogRange {
    float density = 0.0f;  // per world unit
    float start = 0.0f;    // world units from the eye where the haze begins
};
// eyeToCentre: distance from the eye to the sphere's centre; radius: the
// sphere's, both world units (> 0; a radius <= 0 gives no fog).
FogRange automaticFog(float eyeToCentre, float radius);

// Field for field the layout of `uniform Frame` in shaders/frame.glsl.
struct FrameUniformData {
    glm::mat4 viewProj{1.0f};
    glm::vec4 eye{0.0f};        // xyz: camera position (world units)
    glm::vec4 lodEye{0.0f};     // xyz: eye the SBT measures distance from (orthographic: a far
                                // virtual eye); w: lambda / tau for geomorphing, 0 = off
    glm::vec4 sun{0.0f};        // xyz: unit vector towards the sun, 0 when it is below the
                                // horizon; w: ambient light 0..1
    glm::vec4 sky{0.0f};        // rgb: sky colour; a: background alpha (0 = transparent)
    glm::vec4 frameSize{0.0f};  // x, y: frame width and height (px); z: lambda; w: tau (px)
    glm::vec4 fog{0.0f};        // x: fog density per world unit (0 = off); y: 1 orthographic;
                                // z: eye distance where the fog begins (world units)
    glm::vec4 viewDir{0.0f};    // xyz: camera forward, unit (linear depth = dot(p - eye, viewDir))
};

class FrameUniforms {
  public:
    static FrameUniforms create();
    // Writes the block and binds it at kFrameUniformBinding.
    void update(const FrameUniformData& data);
    GLuint buffer() const { return buffer_.id(); }

  private:
    gpu::Buffer buffer_;
};

}  // namespace sierra::render
