#pragma once
// The shaded terrain: the mesh with its albedo from one surface (see
// Surface.h), lit by the sun and the sky (Lighting in TerrainRenderer.h:
// Lambert light, the relief fields' shadows and sky light when the terrain
// has them prepared) and fogged. The surface's function is compiled into the
// program (terrain.frag's "surface.glsl" resolved to its file). Effects
// computed in the same fragment stage (TerrainShading, the relief fields) are
// switched on per frame: a program variant built on first use with their
// #defines (llvmpipe runs every branch, so an effect that is off is compiled
// out, not skipped), and uniforms. They cost a few operations per vertex and
// fragment, not a second rasterisation of the mesh.

#include <sierra/gpu/Program.h>
#include <sierra/render/Pass.h>
#include <sierra/render/Surface.h>

#include <glm/glm.hpp>

#include <array>
#include <memory>
#include <string>

namespace sierra::render {

// What the terrain's fragment stage draws besides the surface, asked for by
// added passes (Pass::shadeTerrain) frame by frame.
struct TerrainShading {
    // Contour edges (ContourPass): where dot(normal, towards the eye) changes
    // sign, this many pixels wide, antialiased over one pixel; 0 = none.
    float contourWidth = 0.0f;
    glm::vec4 contourColour{0.0f, 0.0f, 0.0f, 1.0f};  // RGBA 0..1, blended over the fogged colour
    // The relief texture (TerrainGpu::prepareRelief) lights the terrain:
    // shadows and sky light (SIERRA_RELIEF_LIGHT). Set by the renderer.
    bool relief = false;
};

class TerrainPass final : public Pass {
  public:
    static std::unique_ptr<TerrainPass> create(std::unique_ptr<Surface> surface);
    const char* name() const override { return "terrain"; }
    void draw(const FrameContext& frame) override;
    // The effects of the next draws (none until set).
    void setShading(const TerrainShading& shading) { shading_ = shading; }

    // False for an unlit surface (Surface::lit): the relief fields do not show.
    bool lit() const { return lit_; }
    const Surface& surface() const { return *surface_; }

  private:
    const gpu::Program& program(bool contours, bool relief);
    // By variant (bit 0: SIERRA_CONTOURS, bit 1: SIERRA_RELIEF_LIGHT), each
    // built on first use.
    std::array<gpu::Program, 4> programs_;
    std::string defines_;      // the surface's
    std::string surfaceFile_;  // what "surface.glsl" stands for
    std::string baseFile_;     // what "surface_base.glsl" stands for; empty = nothing
    TerrainShading shading_;
    std::unique_ptr<Surface> surface_;
    bool lit_ = true;
};

}  // namespace sierra::render
