#pragma once
// The curvature field on the GPU (shaders/curvature.comp): the same field as
// analysis::computeCurvature, computed by two compute dispatches (vertex
// gradients from the chosen normals, then the four directions) into storage
// buffers of one value per sample, which the hatch pass reads through buffer
// textures (on llvmpipe both are far cheaper than 2D textures and image
// stores; see curvature.comp). It
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
    int width_ = 0, height_ = 0;
    float spacingX_ = 1.0f, spacingZ_ = 1.0f;
    std::array<gpu::Program, 3> gradientPrograms_;  // per NormalMethod, built on first use
    // [CurvatureMethod][distance 1 (CURVATURE_NEAR)][level control (CURVATURE_LEVELS)], built on first use.
    std::array<std::array<std::array<gpu::Program, 2>, 2>, 4> fieldPrograms_;
    gpu::Buffer heights_;   // world heights, float32 row-major, NaN = no data
    gpu::Buffer gradient_;  // 2 floats per sample, row-major
    gpu::Buffer field_;     // 4 floats per sample, row-major
    gpu::Texture heightsTexture_, gradientTexture_, fieldTexture_;  // buffer textures over them
};

}  // namespace sierra::render
