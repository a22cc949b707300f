#pragma once
// Hatch shading over the terrain: one stroke per grid vertex, generated on
// the GPU from the curvature field (shaders/hatch_strokes.comp once, the
// view-independent direction and opacity; shaders/hatch.vert every frame:
// one point per stroke pulled from the field and expanded to its quad by a
// geometry stage, nothing rebuilt on the CPU), on the vertex's
// tangent plane, along or across the curvature-weighted axis
// (analysis::hatchStrokeDirection), with opacity = the largest curvature.
// Far away the strokes thin out by powers of two and fade with the screen
// size of a grid cell (see hatch.vert), so a far slope does not turn black;
// vertices outside the frustum are skipped in the vertex shader.

#include <sierra/analysis/Hatch.h>
#include <sierra/gpu/Objects.h>
#include <sierra/gpu/Program.h>
#include <sierra/render/CurvatureGpu.h>
#include <sierra/render/Pass.h>

#include <glm/glm.hpp>

#include <memory>

namespace sierra::render {

struct HatchPassDesc {
    float length = 0.75f;  // stroke length, grid units, > 0
    float width = 1.0f;    // pixels, > 0
    analysis::HatchDirection direction = analysis::HatchDirection::Along;
    glm::vec4 colour{0.0f, 0.0f, 0.0f, 1.0f};  // RGBA 0..1; alpha multiplies the opacity
    // Multiplies every stroke's opacity (the largest curvature) before it is
    // clamped to 1, > 0. An automatic curvature scale chosen for lines brings
    // the top 5% of the samples to the line threshold t; a gain of 1 / t
    // brings them to full opacity, as the scale chosen for hatches alone does.
    float opacityGain = 1.0f;
};

class HatchPass final : public Pass {
  public:
    // `curvature` (computed, same grid as the terrain drawn) is read once
    // into the pass's stroke field; compute() it again and the pass keeps
    // the strokes of the field it was created with. Throws
    // sierra::Error for a length or width <= 0.
    static std::unique_ptr<HatchPass> create(std::shared_ptr<const CurvatureGpu> curvature,
                                             const HatchPassDesc& desc = {});
    const char* name() const override { return "hatch"; }
    void draw(const FrameContext& frame) override;

    // Screen size of a grid cell below which strokes thin out (hatch.vert).
    static constexpr float kMinCellPixels = 6.0f;

  private:
    // The lattice stride of this frame's instances (a power of two).
    static int baseStride(const FrameContext& frame);

    gpu::Program program_;
    gpu::VertexArray vao_;
    std::shared_ptr<const CurvatureGpu> curvature_;
    gpu::Texture strokes_;  // RGBA32F: stroke direction and opacity per sample (hatch_strokes.comp)
    HatchPassDesc desc_;
};

}  // namespace sierra::render
