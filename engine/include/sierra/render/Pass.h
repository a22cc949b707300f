#pragma once
// A pass draws one layer of a frame (the shaded terrain, the wireframe, the
// overlays to come) from what the frame shares: the terrain's GPU data, the
// mesh the SBT stream prepared, and the per-frame uniform block, already
// bound. A pass leaves the GL state exactly as it found it (gpu::GlStateScope).
// A new style is a new pass or a new surface function of the terrain pass,
// never a copy of the terrain shader. A layer that is a per-fragment effect of
// the terrain's own surface (contour edges) asks the terrain pass for it
// through shadeTerrain() instead of drawing the mesh again.

#include <sierra/render/Camera.h>
#include <sierra/render/FrameUniforms.h>
#include <sierra/render/SbtStream.h>

namespace sierra::render {

class TerrainGpu;
struct TerrainShading;  // passes/TerrainPass.h

struct FrameContext {
    TerrainGpu& terrain;
    const MeshDraw& mesh;
    const FrameUniformData& uniforms;
    const Camera& camera;
    int width = 0;  // frame size, pixels
    int height = 0;
};

class Pass {
  public:
    virtual ~Pass() = default;
    virtual const char* name() const = 0;
    // Draws into the bound framebuffer with the frame's uniforms bound.
    virtual void draw(const FrameContext& frame) = 0;
    // Called before the terrain pass of each frame the pass is drawn in: adds
    // the effects it wants from the terrain's fragment stage (none by default).
    virtual void shadeTerrain(TerrainShading& /*shading*/) const {}
};

}  // namespace sierra::render
