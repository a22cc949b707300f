#pragma once
// The terrain pass: one heightfield on the GPU, drawn either as the
// view-dependent SBT mesh streamed every frame or as the full grid (every
// cell, indexed triangles), with the same shading so frames compare pixel for
// pixel.

#include <sierra/gpu/Objects.h>
#include <sierra/gpu/Program.h>
#include <sierra/gpu/StreamRing.h>
#include <sierra/render/Camera.h>
#include <sierra/terrain/Heightfield.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <string>

namespace sierra::render {

enum class Lod { Sbt, Full };

Lod parseLod(const std::string& name);  // "sbt" or "full"; throws otherwise
const char* lodName(Lod lod);

struct TerrainDesc {
    // The terrain, (2^n+1)^2 samples (pad with padToPowerOfTwoPlusOne first).
    const terrain::Heightfield* field = nullptr;
    // Sea level as a stored height (the units of the heightfield's samples);
    // NaN = automatic: the height below which 30% of the samples lie.
    float seaLevel = std::numeric_limits<float>::quiet_NaN();
    int threads = 0;  // CPU threads for the error pass and refinement, 0 = default
};

struct DrawOptions {
    Lod lod = Lod::Sbt;
    float tau = 1.0f;        // screen-space error threshold in pixels (SBT), default 1.0
    bool geomorph = true;    // SBT: blend newly active vertices in (no popping)
    bool cull = true;        // SBT: frustum culling by bounding spheres
    bool wireframe = false;  // overlay the triangulation's edges
    int threads = 0;         // refinement threads, 0 = default
    float fogDensity = -1.0f;  // haze per world unit; < 0 = automatic from the extent
};

// What one draw cost and produced. CPU stages in wall-clock ms; drawMs is GPU
// time from a timer query, filled by collectGpuTime().
struct DrawStats {
    double refineMs = 0.0;   // refinement + strip emission (one pass)
    double uploadMs = 0.0;   // copy into the persistently mapped ring
    double submitMs = 0.0;   // CPU time issuing the draw calls
    double drawMs = 0.0;     // GPU time of the terrain pass
    uint64_t triangles = 0;  // triangles drawn (strip: non-degenerate)
    uint64_t indices = 0;    // indices drawn, restarts included
    uint64_t bytesUploaded = 0;
    double indicesPerTriangle() const { return triangles ? double(indices) / double(triangles) : 0.0; }
};

class TerrainRenderer {
public:
    // Builds the SBT errors and radii, uploads the terrain data and colour ramp.
    static TerrainRenderer create(const TerrainDesc& desc);
    TerrainRenderer(TerrainRenderer&&) noexcept;
    TerrainRenderer& operator=(TerrainRenderer&&) noexcept;
    ~TerrainRenderer();

    // Draws the terrain into the bound framebuffer of size width x height (the
    // caller clears it). Depth test on, state restored afterwards.
    DrawStats draw(const Camera& camera, int width, int height, const DrawOptions& options);
    // Waits for the GPU timer of the last draw() and stores it in stats.drawMs.
    void collectGpuTime(DrawStats& stats);

    SceneBounds bounds() const;
    glm::vec3 skyColour() const;
    float seaLevel() const;      // stored height units
    int side() const;            // samples per side
    double errorPassMs() const;  // time spent building errors and radii
    const std::string& summary() const;  // one line: grid, spacing, height range

private:
    struct State;
    explicit TerrainRenderer(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

}  // namespace sierra::render
