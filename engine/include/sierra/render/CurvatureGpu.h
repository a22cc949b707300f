#pragma once
// The curvature field on the GPU (shaders/curvature.comp): the same field as
// analysis::computeCurvature, computed by compute dispatches (vertex
// gradients from the chosen normals, then the four directions; on a field
// without no-data and without reinforcement each in runs of samples and then
// on the border, see curvature.comp) into storage buffers of one value per
// sample, which the hatch pass reads through buffer textures (on llvmpipe
// both are far cheaper than 2D textures and image stores). It
// agrees with the CPU reference within 1e-4 relative or 1e-6 absolute
// (tests/gl/curvature_gpu_test.cpp).
//
// Texture units and image units are those of the dispatch only; compute()
// leaves the GL state as it found it.

#include <sierra/analysis/Curvature.h>
#include <sierra/gpu/Objects.h>
#include <sierra/gpu/Program.h>
#include <sierra/terrain/Heightfield.h>

#include <glm/glm.hpp>

#include <array>
#include <string>

namespace sierra::render {

class CurvatureGpu {
public:
    // Uploads the heightfield's world heights (stored height * vertical
    // scale; NaN for no-data samples); the programs are built on first use. Throws
    // sierra::Error for an empty heightfield.
    static CurvatureGpu create(const terrain::Heightfield& field);

    // Computes the field into texture(); throws sierra::Error for bad options
    // (analysis::validate) or a grid too small for the stencil, with the
    // CPU's messages. The result is ready for any later GL command.
    // tangentPlanes: also fill gradient() (the hatch strokes need it); the
    // normal methods fill it anyway.
    void compute(const analysis::CurvatureOptions& options, bool tangentPlanes = true);

    // A buffer texture (GL_TEXTURE_BUFFER, RGBA32F): the 4 directions of
    // Curvature.h per sample, texel j * width + i (a samplerBuffer in shaders).
    const gpu::Texture& texture() const { return fieldTexture_; }
    // A buffer texture (RG32F), texel j * width + i: the surface gradient
    // (dy/dx, dy/dz) per sample from the options' normals (NaN = no data),
    // the tangent planes of the hatch strokes. Filled by compute() unless
    // told otherwise (see there).
    const gpu::Texture& gradient() const { return gradientTexture_; }
    // Reads the last compute() back (synchronously) in the CPU's layout.
    analysis::CurvatureField read() const;

    glm::vec2 spacing() const { return {spacingX_, spacingZ_}; }  // world units between samples
    int width() const { return width_; }
    int height() const { return height_; }

private:
    // The #defines every program of this grid shares (buffer layout, runs' texel offsets).
    std::string layoutDefines(bool gradients) const;
    void dispatchRuns(gpu::Program& program);
    void dispatchBorder(gpu::Program& program);

    int width_ = 0, height_ = 0;
    float spacingX_ = 1.0f, spacingZ_ = 1.0f;
    bool noData_ = false;     // some sample has no data: the per-sample programs only
    int heightsLead_ = 0;     // floats before sample 0 in heights_
    int gradientLead_ = 0;    // gradients before sample 0 in gradient_
    // Built on first use: per NormalMethod, per sample (whole grid or, with
    // CURVATURE_BORDER, its border) and in runs.
    std::array<gpu::Program, 3> gradientPrograms_, gradientBorderPrograms_, gradientRunPrograms_;
    // [CurvatureMethod][distance 1 (CURVATURE_NEAR)][level control (CURVATURE_LEVELS)], built on first use.
    std::array<std::array<std::array<gpu::Program, 2>, 2>, 4> fieldPrograms_;
    // [CurvatureMethod][level control]: runs, and the border after them (distance 1, no no-data).
    std::array<std::array<gpu::Program, 2>, 4> fieldRunPrograms_, fieldBorderPrograms_;
    gpu::Buffer heights_;   // world heights, float32 row-major after heightsLead_ floats, NaN = no data
    gpu::Buffer gradient_;  // 2 floats per sample, row-major after gradientLead_ gradients
    gpu::Buffer field_;     // 4 floats per sample, row-major, rounded up to whole runs
    gpu::Texture heightsTexture_, gradientTexture_, fieldTexture_;  // buffer textures over them
    gpu::Texture heights4Texture_, gradient4Texture_;  // RGBA32F views for the runs (from offset 0)
};

}  // namespace sierra::render
