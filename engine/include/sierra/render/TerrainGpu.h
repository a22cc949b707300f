#pragma once
// A terrain's data on the GPU and beside it: the heights and the SBT's
// per-vertex data as textures, the terrain uniform block, its bounds and sea
// level, and the SBT itself (errors, radii, refinement). Built once per
// terrain; every pass and the SBT stream read it.
//
// Texture units (fixed, shared by every terrain shader, see terrain_common.glsl):
//   0  uData     RGBA32F: drawn surface height, geomorph base, error, radius
//   2  uHeights  R32F: true world heights, linearly filtered
//   7  uRelief   RG16F: the relief lighting fields, linearly filtered (the
//                terrain pass's, bound by bindRelief)
// Units 1 and 3..6 belong to the passes (a surface's ramp or tiles).

#include <sierra/gpu/Objects.h>
#include <sierra/render/Camera.h>
#include <sierra/terrain/Heightfield.h>

#include <glm/glm.hpp>

#include <limits>
#include <memory>
#include <string>

namespace sierra::render {

class SbtBridge;
struct SbtView;

struct TerrainGpuDesc {
    // The terrain, (2^n+1)^2 samples (pad with padToPowerOfTwoPlusOne first).
    const terrain::Heightfield* field = nullptr;
    // Sea level as a stored height (the heightfield's units); NaN = no water.
    float seaLevel = std::numeric_limits<float>::quiet_NaN();
    int threads = 0;  // CPU threads for the error pass, 0 = default
};

inline constexpr GLuint kReliefTextureUnit = 7;

// The relief lighting fields a frame asks for (analysis/Relief.h), on the
// drawn surface (water flat at sea level), over the real samples.
struct ReliefRequest {
    bool shadows = false;       // r: the visible share of the sun's disc (1 when off)
    bool skyLight = false;      // g: the cosine-weighted sky light (1 when off)
    float sunAzimuth = 0.0f;    // degrees clockwise from north
    float sunAltitude = 45.0f;  // degrees above the horizon
    float sunSize = 0.53f;      // angular diameter, degrees, > 0
    float radius = 0.0f;        // horizon search radius, world units; 0 = the whole grid
    bool any() const { return shadows || skyLight; }
};

class TerrainGpu {
  public:
    static TerrainGpu create(const TerrainGpuDesc& desc);
    // The largest (2^n+1) grid side the current GL context's textures take
    // (GL_MAX_TEXTURE_SIZE 16384 gives 8193), at most the loaders' default
    // budget terrain::kDefaultMaxPaddedSide: pass it to scene::loadTerrain so a
    // grid too large for this GL is refused before it is loaded.
    static int maxGridSide();
    TerrainGpu(TerrainGpu&&) noexcept;
    TerrainGpu& operator=(TerrainGpu&&) noexcept;
    ~TerrainGpu();

    // Binds the data textures (units 0 and 2) and the terrain uniform block.
    void bind() const;

    // Makes the relief texture hold the fields `request` asks for, computing
    // on the CPU only what is not kept: the sky light once per radius (it does
    // not depend on the sun), the sun's visibility once per distinct sun
    // (azimuth, altitude, size, radius; the last kReliefSunsKept), each
    // computation logged with its time. A sun whose disc is wholly below the
    // horizon is invisible everywhere, without a computation. The texture is
    // uploaded again only when its fields change. Returns request.any().
    bool prepareRelief(const ReliefRequest& request);
    // Binds the relief texture of the last prepareRelief to kReliefTextureUnit.
    void bindRelief() const;
    // CPU time of the relief computations so far, milliseconds.
    double reliefMs() const;
    static constexpr int kReliefSunsKept = 8;

    SbtBridge& sbt();
    // Every grid cell as indexed triangles, built on first use.
    const gpu::Buffer& fullGridIndices();
    uint64_t fullGridIndexCount() const;
    // A mesh of the terrain's own samples (a TIN) as indexed triangles of
    // linear grid positions j * side() + i, drawn with Lod::Mesh. Throws
    // sierra::Error for an index outside the grid or a count not a multiple of 3.
    void setMesh(const std::vector<uint32_t>& triangles);
    const gpu::Buffer& meshIndices() const;
    uint64_t meshIndexCount() const;

    SceneBounds bounds() const;    // the real samples' box (padding excluded), world units
    glm::vec2 worldRange() const;  // lowest and highest world height of the real samples
    bool hasWater() const;
    float seaLevel() const;       // stored height units; NaN without water
    float worldSeaLevel() const;  // world units; NaN without water
    // The drawn surface: the heightfield with water flattened to sea level
    // (the field itself without water); what the SBT refines and the
    // overlays' curvature describes.
    const terrain::Heightfield& surface() const;
    int side() const;             // samples per side
    glm::vec2 spacing() const;    // world units between samples along x and z
    float verticalScale() const;  // stored height -> world height
    // Builds the refiner's view keys for `view` before the first SBT frame
    // (SbtStream), outside its refinement time, and adds the time to
    // sbtBuildMs(); a renderer that never draws an SBT frame never builds them.
    void prepareSbtView(const SbtView& view);
    double sbtBuildMs() const;           // time spent building errors, radii and the refiner's keys
    size_t refinerKeyBytes() const;      // CPU bytes of the refiner's keys (sbt::Refiner::keyBytes)
    const std::string& summary() const;  // one line: grid, spacing, height range, sea level

  private:
    struct State;
    explicit TerrainGpu(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

}  // namespace sierra::render
