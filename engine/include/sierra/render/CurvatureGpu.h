#pragma once
// The curvature field on the GPU (shaders/curvature_field.glsl): the same
// field as analysis::computeCurvature, in two passes (vertex gradients from
// the chosen normals, then the four directions), by one of two paths:
// - Fragment: full-screen fragment passes, each fragment a run of kRun
//   samples of a row written to kRun colour attachments. On llvmpipe a
//   fragment's colour outputs are stored as vectors, far cheaper than a
//   compute shader's storage stores (docs/curvature.md, "GPU against CPU").
// - Compute: a compute shader, one sample per invocation, into the same
//   layers as images. On a GPU compute units outnumber the units that run
//   fragments (an H100 runs fragments on a few of its units only).
// Both agree with the CPU reference within 1e-4 relative or 1e-6 absolute
// (tests/gl/curvature_gpu_test.cpp), and with each other.
//
// Texture units and framebuffers are those of the passes only; compute()
// leaves the GL state as it found it.

#include <sierra/analysis/Curvature.h>
#include <sierra/gpu/Objects.h>
#include <sierra/gpu/Program.h>
#include <sierra/terrain/Heightfield.h>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sierra::render {

class CurvatureGpu {
  public:
    enum class Path { Fragment, Compute };

    // The path for the current context's driver: Fragment on a software
    // rasteriser (llvmpipe, softpipe), Compute on any other.
    static Path defaultPath();

    // Uploads the heightfield's world heights (stored height * vertical
    // scale; NaN for no-data samples); the programs are built on first use. Throws
    // sierra::Error for an empty heightfield or one larger than the driver's
    // buffer textures or textures hold. `path`: defaultPath() when not given.
    static CurvatureGpu create(const terrain::Heightfield& field,
                               std::optional<Path> path = std::nullopt);

    // Computes the field into texture(); throws sierra::Error for bad options
    // (analysis::validate) or a grid too small for the stencil, with the
    // CPU's messages. The result is ready for any later GL command.
    // tangentPlanes: also fill gradient() (the hatch strokes need it); the
    // normal methods fill it anyway.
    void compute(const analysis::CurvatureOptions& options, bool tangentPlanes = true);

    // Samples per run: the layers of texture() and twice those of gradient().
    static constexpr int kRun = 8;
    // The largest reinforcement distance the Fragment path computes in runs
    // (farther ones take the per-sample program everywhere).
    static constexpr int kMaxRunDistance = 4;

    // A 2D array texture (RGBA32F, runs() x height x kRun layers): the 4
    // directions of Curvature.h of sample (i, j) at texel (i / kRun, j),
    // layer i % kRun (a sampler2DArray in shaders, texelFetch only).
    const gpu::Texture& texture() const { return fieldTexture_; }
    // A 2D array texture (RGBA32F, runs() x height x kRun / 2 layers): the
    // surface gradient (dy/dx, dy/dz) of sample (i, j) from the options'
    // normals (NaN = no data), the tangent planes of the hatch strokes, at
    // texel (i / kRun, j), layer (i % kRun) / 2, in .xy for even i and .zw for
    // odd i. Filled by compute() unless told otherwise (see there).
    const gpu::Texture& gradient() const { return gradientTexture_; }
    // Runs per row: width rounded up to whole runs, divided by kRun.
    int runs() const { return (width_ + kRun - 1) / kRun; }
    // Reads the last compute() back (synchronously) in the CPU's layout.
    analysis::CurvatureField read() const;

    Path path() const { return path_; }

    // For a field with no data (the Fragment path's stencil): per run c and
    // row j (index j * runs + c), kNoDataRun when every sample of the run has
    // no data, else min(kMaxRunDistance + 1, the smallest R whose window of
    // reach R, samples c * kRun - R ... c * kRun + kRun - 1 + R of rows j - R
    // ... j + R, holds a no-data sample). The runs of reach R draw where it
    // is above R (and not kNoDataRun), NaN is written where it is
    // kNoDataRun, the per-sample program draws the rest. `heights`: NaN = no
    // data, sample (i, j) at (j + 1) * pitch + i + 1.
    static constexpr uint8_t kNoDataRun = 0x80;
    static std::vector<uint8_t> runClearance(const std::vector<float>& heights, int width,
                                             int height, int pitch);
    glm::vec2 spacing() const { return {spacingX_, spacingZ_}; }  // world units between samples
    int width() const { return width_; }
    int height() const { return height_; }

  private:
    // The programs of one pass (curvature.frag): general, and the runs and
    // the one-sample border program; the runs are wrong within `reach`
    // samples of the border (1, or the field's reinforcement distance) and
    // of no data (where clearance_ keeps them out).
    struct Pass {
        gpu::Program* general = nullptr;
        gpu::Program* runs = nullptr;
        gpu::Program* oneSample = nullptr;
        gpu::Program* noData = nullptr;  // NaN in every output (made only with clearance_)
        int reach = 1;
    };

    // Draws a pass into the bound framebuffer of `layers` attachments;
    // `gradient`: two samples per attachment (.xy, .zw).
    void draw(const Pass& pass, int layers, bool gradient);
    // The Compute path's two dispatches (see compute()).
    void dispatch(const analysis::CurvatureOptions& options, bool normalBased, bool gradients);
    // The buffer the field pass reads the gradients from, made on first use.
    void ensureGradientCopy();
    // The programs' #defines (grid layout, method or normals) and uniforms,
    // shared by both paths.
    std::string gradientDefines(analysis::NormalMethod normals) const;
    std::string fieldDefines(const analysis::CurvatureOptions& options) const;
    void setGridUniforms(const gpu::Program& program) const;  // uSize, uSpacing
    // Uses `program` and sets the options' uniforms.
    static void setFieldUniforms(const gpu::Program& program,
                                 const analysis::CurvatureOptions& options);

    Path path_ = Path::Fragment;
    int width_ = 0, height_ = 0;
    float spacingX_ = 1.0f, spacingZ_ = 1.0f;
    bool noData_ = false;  // some sample has no data: the general programs only
    int pitch_ = 0;        // floats per row of heights_ (a multiple of 4)
    // Built on first use: per NormalMethod, general, runs and one-sample.
    std::array<gpu::Program, 3> gradientPrograms_, gradientRunPrograms_, gradientSamplePrograms_;
    // [CurvatureMethod][level control (CURVATURE_LEVELS)], general and
    // one-sample; the runs also per reinforcement distance (1 ...
    // kMaxRunDistance).
    std::array<std::array<gpu::Program, 2>, 4> fieldPrograms_, fieldSamplePrograms_;
    std::array<std::array<std::array<gpu::Program, kMaxRunDistance>, 2>, 4> fieldRunPrograms_;
    gpu::Program gradientNoDataProgram_, fieldNoDataProgram_;  // NaN everywhere (CURVATURE_NO_DATA)
    // The Compute path's (curvature.comp), likewise.
    std::array<gpu::Program, 3> gradientComputePrograms_;
    std::array<std::array<gpu::Program, 2>, 4> fieldComputePrograms_;
    // World heights, NaN = no data: sample (i, j) at float (j + 1) * pitch_ + i + 1.
    gpu::Buffer heights_;
    gpu::Texture heightsTexture_, heights4Texture_;  // R32F and RGBA32F buffer textures over it
    gpu::Texture fieldTexture_, gradientTexture_;
    // gradientTexture_'s layers copied for the field pass (a buffer texture
    // over it, RGBA32F), layer-major: see curvature.frag.
    gpu::Buffer gradientCopy_;
    gpu::Texture gradientCopyTexture_;
    gpu::Framebuffer fieldFramebuffer_, gradientFramebuffer_;  // their layers as colour attachments
    // With no data (Fragment path): runClearance() as the framebuffers'
    // stencil (STENCIL_INDEX8, runs() x height).
    gpu::Texture clearance_;
    gpu::VertexArray vertexArray_;  // empty: the full-screen triangle
};

}  // namespace sierra::render
