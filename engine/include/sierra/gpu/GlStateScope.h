#pragma once
// Saving and restoring the GL state a pass changes, the way Dear ImGui's
// OpenGL3 backend backs up its state: capture on entry, restore on exit, so a
// pass leaves the context exactly as it found it.

#include <sierra/gpu/Gl.h>

#include <array>
#include <string>

namespace sierra::gpu {

// The state Sierra's passes touch (capabilities, depth, blend, raster, the
// bound objects, pixel-store alignment, viewport and clear values). Texture
// bindings cover units 0..kTextureUnits-1 and the 1D, 2D and 2D-array targets.
struct GlState {
    static constexpr int kTextureUnits = 8;
    static constexpr int kUniformBindings = 4;

    std::array<GLboolean, 14> enabled{};
    GLint depthFunc = 0;
    GLboolean depthMask = 0;
    std::array<GLboolean, 4> colourMask{};
    std::array<GLint, 6> blend{};  // src rgb, dst rgb, src alpha, dst alpha, eq rgb, eq alpha
    std::array<GLint, 2> polygonMode{};
    float polygonOffsetFactor = 0.0f, polygonOffsetUnits = 0.0f;
    GLint cullFace = 0, frontFace = 0;
    GLint program = 0, vertexArray = 0, arrayBuffer = 0, uniformBuffer = 0;
    std::array<GLint, kUniformBindings> uniformBindings{};
    GLint activeTexture = 0;
    std::array<std::array<GLint, 3>, kTextureUnits> textures{};
    GLint packAlignment = 0, unpackAlignment = 0;
    std::array<GLint, 4> viewport{};
    GLint drawFramebuffer = 0, readFramebuffer = 0;
    std::array<float, 4> clearColour{};
    double clearDepth = 0.0;

    // Reads the current context's state with glGet*.
    static GlState capture();
    // Makes the current context's state equal to this one.
    void restore() const;
    bool operator==(const GlState&) const = default;
    // The fields that differ from `other`, one per line; empty when equal.
    std::string differences(const GlState& other) const;
};

// Captures the state on construction and restores it on destruction.
class GlStateScope {
  public:
    GlStateScope() : saved_(GlState::capture()) {}
    ~GlStateScope() { saved_.restore(); }
    GlStateScope(const GlStateScope&) = delete;
    GlStateScope& operator=(const GlStateScope&) = delete;

  private:
    GlState saved_;
};

}  // namespace sierra::gpu
