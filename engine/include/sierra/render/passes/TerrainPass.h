#pragma once
// The shaded terrain: the mesh with its albedo from one surface (see
// Surface.h), Lambert light and fog. The surface's function is compiled into
// the program (terrain.frag's "surface.glsl" resolved to its file). Effects
// computed in the same fragment stage (TerrainShading) are switched on per
// frame (a second program built with their #define, and uniforms), so they
// cost a few operations per vertex and fragment, not a second rasterisation
// of the mesh.

#include <sierra/gpu/Program.h>
#include <sierra/render/Pass.h>
#include <sierra/render/Surface.h>

#include <glm/glm.hpp>

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
};

class TerrainPass final : public Pass {
  public:
    static std::unique_ptr<TerrainPass> create(std::unique_ptr<Surface> surface);
    const char* name() const override { return "terrain"; }
    void draw(const FrameContext& frame) override;
    // The effects of the next draws (none until set).
    void setShading(const TerrainShading& shading) { shading_ = shading; }

  private:
    gpu::Program program_;         // the surface alone
    gpu::Program contourProgram_;  // with contour edges (SIERRA_CONTOURS), built on first use
    std::string defines_;          // the surface's
    std::string surfaceFile_;      // what "surface.glsl" stands for
    TerrainShading shading_;
    std::unique_ptr<Surface> surface_;
};

}  // namespace sierra::render
