#pragma once
// The relief lighting fields of analysis/Relief.h on the GPU: horizon angles
// in D azimuths, the sun's visibility, the sky-view factor and the sky light,
// by the CPU's sweep (shaders/horizon.comp: one invocation per digital line of
// an azimuth, its hull in a stack of its own in a scratch buffer, O(samples)
// per azimuth) and one pass per sample for the sky (shaders/relief_sky.comp).
// The fields agree with the CPU's within 1e-4 (radians for angles, absolute
// for the 0..1 fields; tests/gl/relief_gpu_test.cpp). Float throughout:
// distances are differences of integer indices times the azimuth's steps, so
// they keep float's relative precision at any distance (docs/relief.md, "GPU
// path").
//
// The results stay on the GPU as R32F textures for the terrain pass (NaN at
// no data and in the padding, texelFetch only) and can be read back in the
// CPU's layout. Calls leave the GL state as they found it.

#include <sierra/analysis/Relief.h>
#include <sierra/gpu/Objects.h>
#include <sierra/gpu/Program.h>
#include <sierra/terrain/Heightfield.h>

#include <cstdint>
#include <vector>

namespace sierra::render {

class ReliefGpu {
  public:
    // Uploads the heightfield's stored heights and its no-data mask. Throws
    // sierra::Error for an empty heightfield or a side beyond the driver's
    // textures or 32767 samples (the shader packs doubled indices in 16 bits).
    static ReliefGpu create(const terrain::Heightfield& field);
    // Uploads another heightfield (or the same one changed) with create()'s
    // checks, keeping the programs and, for the same size, the textures;
    // results of another size are dropped.
    void upload(const terrain::Heightfield& field);

    // Horizon angles into horizons(); the options and errors of
    // analysis::computeHorizons (threads is not used).
    void computeHorizons(const analysis::HorizonOptions& options);
    // The sun's visibility into sunVisibility(); as analysis::sunVisibility.
    void computeSunVisibility(const analysis::SunDisc& sun,
                              const analysis::HorizonOptions& options = {});
    // Both in one dispatch, the sun's azimuth beside the others: the GPU is
    // far from full with one azimuth's lines (a few thousand invocations),
    // and a dispatch lasts as long as its longest line.
    void computeHorizonsAndSun(const analysis::HorizonOptions& options,
                               const analysis::SunDisc& sun);
    // The sky-view factor and the sky light of the last computeHorizons()
    // into skyViewFactor() and skyLight(). Throws sierra::Error before any.
    void computeSky();

    // A 2D array texture (R32F, width x height x directions): layer d is
    // azimuth d's horizon elevation in radians (analysis::Horizons::angle).
    const gpu::Texture& horizons() const { return horizons_; }
    // 2D textures (R32F, width x height).
    const gpu::Texture& sunVisibility() const { return sun_; }
    const gpu::Texture& skyViewFactor() const { return skyView_; }
    const gpu::Texture& skyLight() const { return skyLight_; }

    // The last results read back (synchronously) in the CPU's layout; empty
    // before the first computation of each.
    analysis::Horizons readHorizons() const;
    std::vector<float> readSunVisibility() const;
    std::vector<float> readSkyViewFactor() const;
    std::vector<float> readSkyLight() const;

    int width() const { return width_; }
    int height() const { return height_; }
    int directions() const { return directions_; }

    // Lines per workgroup (HORIZON_GROUP in horizon.comp).
    static constexpr int kGroup = 64;
    // The largest scratch buffer one dispatch uses, bytes (the driver's limit
    // on storage blocks if smaller): the lines beyond it go to further
    // dispatches. 8 bytes per hull entry, entries per line its length (twice
    // on a diagonal, three times that with a radius): at 4097^2 about 135 MB
    // per azimuth, 270 MB per diagonal.
    static constexpr size_t kScratchBytes = size_t(2) << 30;

  private:
    void computeHorizons(const analysis::HorizonOptions& options, const analysis::SunDisc* sun);
    void prepareSun();  // sun_ allocated and NaN
    // Sweeps `azimuths` (degrees) into layers 0... of horizons_ and, unless
    // null, the sun's azimuth into sun_.
    void sweep(const std::vector<double>& azimuths, const analysis::HorizonOptions& options,
               const analysis::SunDisc* sun);

    int width_ = 0, height_ = 0;
    float spacingX_ = 1.0f, spacingZ_ = 1.0f, scale_ = 1.0f;
    bool masked_ = false;
    int directions_ = 0;
    float firstAzimuth_ = 0.0f;
    gpu::Texture heights_, mask_;  // R32F stored heights; R8UI, 0 = no data (1x1 without)
    gpu::Texture horizons_, sun_, skyView_, skyLight_;
    gpu::Buffer scratch_;
    gpu::Program horizonProgram_, skyProgram_;  // built on first use
};

// One-call forms of the CPU's functions, in a current GL 4.5 context: the
// same fields, computed on the GPU and read back.
analysis::Horizons computeHorizonsGpu(const terrain::Heightfield& field,
                                      const analysis::HorizonOptions& options);
std::vector<float> sunVisibilityGpu(const terrain::Heightfield& field, const analysis::SunDisc& sun,
                                    const analysis::HorizonOptions& options = {});
// The horizons of `options` and from them the sky-view factor or the sky light.
std::vector<float> skyViewFactorGpu(const terrain::Heightfield& field,
                                    const analysis::HorizonOptions& options = {});
std::vector<float> skyLightGpu(const terrain::Heightfield& field,
                               const analysis::HorizonOptions& options = {});

}  // namespace sierra::render
