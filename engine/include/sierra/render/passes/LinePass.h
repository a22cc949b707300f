#pragma once
// Line shading over the terrain: the polylines of analysis::traceLines
// (traced once per terrain and style, a static framework), drawn every frame
// as antialiased quads expanded in the vertex shader (shaders/line.vert),
// uWidth pixels wide, alpha = the curvature at each end, black unless a
// colour is set. Each point is lifted towards the camera along its view ray
// by the SBT's saturated error at the nearest vertex (overlay_common.glsl),
// so the lines neither sink into nor float over the mesh at any tau. Where a
// grid cell covers c < kFullCellPixels * w on the screen (w = max(1, width))
// the polylines thin out (line.vert): a fraction (c / (kFullCellPixels *
// w))^2 of them is drawn, so a far slope keeps the density of lines per
// screen area of a near one, and wide lines, which cover w^2 times the
// pixels, thin out sooner.

#include <sierra/analysis/Lines.h>
#include <sierra/gpu/Objects.h>
#include <sierra/gpu/Program.h>
#include <sierra/render/Pass.h>

#include <glm/glm.hpp>

#include <memory>
#include <vector>

namespace sierra::render {

struct LinePassDesc {
    float width = 1.0f;                        // pixels, > 0
    glm::vec4 colour{0.0f, 0.0f, 0.0f, 1.0f};  // RGBA 0..1; alpha multiplies the curvature
    // Distance thinning (the curvature lines' density per screen area);
    // false keeps every polyline at any distance (vector layers).
    bool thin = true;
    // > 0: the lines are also in a texture whose finest texel is this many
    // world units (vector layers' far field, render/VectorOverlay.h); only
    // the segments where such a texel may cover more than a pixel are drawn,
    // chosen per frame on the CPU by runs of kChunkSegments. 0: all of them.
    float nearTexelSize = 0.0f;
};

class LinePass final : public Pass {
  public:
    // Uploads the segments of `lines` (grid coordinates of the terrain the
    // pass draws over). Throws sierra::Error for a width <= 0.
    static std::unique_ptr<LinePass> create(const analysis::LineSet& lines,
                                            const LinePassDesc& desc = {});
    const char* name() const override { return "lines"; }
    void draw(const FrameContext& frame) override;
    size_t segmentCount() const { return segments_; }

    // Below this screen size of a grid cell (pixels, times the line width
    // when it is over 1) the lines thin out.
    static constexpr float kFullCellPixels = 1.0f;
    // Segments per run of the near selection (nearTexelSize).
    static constexpr int kChunkSegments = 64;
    // Segments drawn in the last frame.
    int64_t drawnSegments() const { return drawn_; }

  private:
    gpu::Program program_;
    gpu::Buffer buffer_;
    gpu::VertexArray vao_;
    gpu::Buffer quadIndices_;  // one batch of quads (render/passes/QuadBatch.h)
    size_t segments_ = 0;
    LinePassDesc desc_;
    // Per run of kChunkSegments segments: its box in grid coordinates (x0, z0, x1, z1).
    std::vector<glm::vec4> chunkBoxes_;
    int64_t drawn_ = 0;
};

}  // namespace sierra::render
