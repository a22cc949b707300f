#pragma once
// Contour edges: the view-dependent silhouettes of the terrain, recomputed
// every frame in shaders, where dot(normal, towards the eye) changes sign,
// drawn `width` pixels wide and antialiased. They complement line and hatch
// shading, which are view-independent. The edges are drawn by the terrain
// pass's fragment stage (shaders/terrain.frag, from the normal it shades
// with), which this pass switches on through shadeTerrain(): a second
// rasterisation of the mesh cost about as much as the terrain itself on a
// software rasteriser. So contours show on the shaded or paper terrain, not
// on the debug colourings (--colour-by), and under the lines and hatches.

#include <sierra/render/Pass.h>

#include <glm/glm.hpp>

#include <memory>

namespace sierra::render {

struct ContourPassDesc {
    float width = 1.5f;                        // pixels, > 0
    glm::vec4 colour{0.0f, 0.0f, 0.0f, 1.0f};  // RGBA 0..1
};

class ContourPass final : public Pass {
  public:
    // Throws sierra::Error for a width <= 0.
    static std::unique_ptr<ContourPass> create(const ContourPassDesc& desc = {});
    const char* name() const override { return "contours"; }
    // Draws nothing: the terrain pass draws the edges.
    void draw(const FrameContext& frame) override;
    void shadeTerrain(TerrainShading& shading) const override;

  private:
    ContourPassDesc desc_;
};

}  // namespace sierra::render
