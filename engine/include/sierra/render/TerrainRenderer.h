#pragma once
// A frame of a terrain as passes: the terrain's GPU data (TerrainGpu), the
// mesh of the frame (SbtStream: the view-dependent SBT streamed every frame,
// or the full grid), the per-frame uniform block, then the passes in order:
// the shaded terrain, the wireframe when asked for, and any pass added with
// addPass() (the overlays). The SBT and the full grid shade alike, so frames
// compare pixel for pixel.

#include <sierra/gpu/Objects.h>
#include <sierra/render/Camera.h>
#include <sierra/render/FrameUniforms.h>
#include <sierra/render/Pass.h>
#include <sierra/render/SbtStream.h>
#include <sierra/render/Surface.h>
#include <sierra/render/TerrainGpu.h>
#include <sierra/render/passes/DepthPass.h>
#include <sierra/render/passes/LabelPass.h>
#include <sierra/terrain/Heightfield.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace sierra::render {

struct TerrainDesc {
    // The terrain, (2^n+1)^2 samples (pad with padToPowerOfTwoPlusOne first).
    const terrain::Heightfield* field = nullptr;
    // Sea level as a stored height (the heightfield's units); NaN = no water.
    float seaLevel = std::numeric_limits<float>::quiet_NaN();
    int threads = 0;           // CPU threads for the error pass, 0 = default
    bool metric = false;       // heights in metres: absolute-elevation colours
    float treeLine = 2000.0f;  // metres (metric only)
    float snowLine = 3000.0f;  // metres (metric only)
    std::string cpt;           // .cpt colour table instead of the scheme; empty = none
};

// The terrain pass lights each fragment with one function (terrain.frag):
// albedo * (ambient * skyLight + (1 - ambient) * max(n . sun, 0) * sunVisibility),
// then fog. skyLight and sunVisibility are the relief fields (TerrainGpu::prepareRelief),
// 1 where they are off. A sun whose whole disc is below the horizon lights
// nothing directly: the frame is lit by the ambient (sky) term alone.
struct Lighting {
    // Towards the sun (unit): compass bearing 232.1 degrees (south-west), 52.8 degrees up.
    glm::vec3 sunDirection = glm::normalize(glm::vec3(-0.45f, 0.75f, 0.35f));
    float ambient = 0.32f;  // light that reaches faces turned away, 0..1
    // Haze per world unit; 0 = off; < 0 = automatic (automaticFog over
    // the terrain's bounding sphere; perspective only).
    float fogDensity = -1.0f;
    glm::vec3 sky{0.62f, 0.74f, 0.86f};  // sky and fog colour, linear 0..1
    bool transparent = false;            // sky alpha 0 (RGBA output)
    bool shadows = false;                // soft cast shadows (the sun's visible share)
    bool skyLight = false;               // the ambient term times the sky light
    float sunSize = 0.53f;               // the sun's angular diameter, degrees, > 0
    float horizonRadius = 0.0f;          // horizon search, world units; 0 = the whole grid
};

struct DrawOptions {
    Lod lod = Lod::Sbt;
    float tau = 1.0f;        // screen-space error threshold in pixels (SBT), default 1.0
    bool geomorph = true;    // SBT: blend newly active vertices in (no popping)
    bool cull = true;        // SBT: frustum culling by bounding spheres
    bool wireframe = false;  // the wireframe pass after the terrain
    bool polygons = true;    // the shaded terrain pass (false: points and/or lines only)
    bool points = false;     // the mesh's vertices as points after the terrain
    // Polygons coloured by SBT level or split-vertex screen error instead of
    // the surface function (0 surface, 1 level, 2 error; see DebugColourPass.h).
    int colourBy = 0;
    int threads = 0;  // refinement threads, 0 = default
    // The terrain pass colours by the ramp of TerrainDesc instead of the
    // surface given to setSurface() (sierra-bench frames --surface-costs
    // times the zone surface against it); no effect without setSurface().
    bool plainSurface = false;
    Lighting lighting;
    // Which passes added with addPass() draw: bit k for the k-th added (all by
    // default; sierra-bench frames --overlay-costs times them apart).
    uint64_t addedPasses = ~uint64_t(0);
};

// What one frame cost and produced. drawMs is GPU time from a timer query,
// filled by collectGpuTime().
struct DrawStats : MeshStats {
    double submitMs = 0.0;  // CPU time issuing the passes
    double drawMs = 0.0;    // GPU time of the passes
    double indicesPerTriangle() const {
        return triangles ? double(indices) / double(triangles) : 0.0;
    }
};

class TerrainRenderer {
  public:
    static TerrainRenderer create(const TerrainDesc& desc);
    TerrainRenderer(TerrainRenderer&&) noexcept;
    TerrainRenderer& operator=(TerrainRenderer&&) noexcept;
    ~TerrainRenderer();

    // Draws the frame's passes into the bound framebuffer of size width x height
    // (the caller clears it, see clearColour()). GL state is left as found.
    DrawStats draw(const Camera& camera, int width, int height, const DrawOptions& options);
    // Waits for the GPU timer of the last draw() and stores it in stats.drawMs.
    void collectGpuTime(DrawStats& stats);
    // The terrain pass's surface (default: the colour ramp of TerrainDesc,
    // which stays built for DrawOptions::plainSurface).
    void setSurface(std::unique_ptr<Surface> surface);
    // Runs after the terrain and wireframe passes, in the order added.
    void addPass(std::unique_ptr<Pass> pass);
    // The names of the passes added with addPass(), in order.
    std::vector<std::string> addedPassNames() const;
    // The linear eye-space depth of the terrain from `camera` (NaN where none).
    DepthImage renderDepth(const Camera& camera, int width, int height, const DrawOptions& options);
    // The dataset labels of the terrain from `camera` (LabelPass): normals
    // rotated by `normalRotation` (identity: world axes), the mask, and the
    // zone ids when the surface is the zone surface (hasZoneIds()). The same
    // mesh as renderDepth for the same camera, so the mask is exactly where
    // the depth is not NaN.
    LabelImage renderLabels(const Camera& camera, int width, int height, const DrawOptions& options,
                            const glm::mat3& normalRotation);
    // True when the surface set with setSurface() gives zone ids.
    bool hasZoneIds() const;

    // The frame's clear colour: the sky, alpha 0 when transparent.
    static glm::vec4 clearColour(const Lighting& lighting);

    TerrainGpu& terrain();
    SceneBounds bounds() const;
    float seaLevel() const;              // stored height units; NaN without water
    int side() const;                    // samples per side
    double sbtBuildMs() const;           // see TerrainGpu::sbtBuildMs
    const std::string& summary() const;  // one line: grid, spacing, height range

  private:
    struct State;
    explicit TerrainRenderer(std::unique_ptr<State> state);
    FrameUniformData frameUniforms(const Camera& camera, int width, int height,
                                   const DrawOptions& options) const;
    // The frame's mesh and uniforms drawn by `pass` alone into its own target
    // (the depth and label outputs), the uniform binding left as found.
    void drawAlone(Pass& pass, const Camera& camera, int width, int height,
                   const DrawOptions& options);
    std::unique_ptr<State> state_;
};

}  // namespace sierra::render
