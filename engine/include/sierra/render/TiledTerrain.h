#pragma once
// A tiled terrain (.sierra, sbt/TileFile.h) drawn without the whole grid on
// the GPU: tiles stream from disk into sbt::TileCache, are refined across
// tile borders by sbt::TiledRefiner, and live on the GPU in a tile cache of
// array textures, one per tile resolution.
//
// GPU data. A tile whose first d tile levels are read is a regular grid of
// (2^c + 1)^2 heights, c = ceil(d / 2) (the vertices of an odd last level
// that are missing are the means of their hypotenuse's ends, as the coarser
// mesh draws them); class c's array texture holds such tiles in slots, one a
// layer or, where the class wants more tiles than the driver has layers,
// several side by side in a layer (each in a one-texel gutter repeating its
// edge, so bilinear lookups never bleed into a neighbour). A page table (one
// texel a tile) gives each tile's class, layer and slot. The GPU byte budget
// bounds the slots. The mesh streams as the refinement's (i, j) vertex pairs
// in a storage buffer: the vertex shader reads its height from the tile
// holding it, the fragment shader shades with the finest heights resident at
// the fragment. What the refinement may use is what is on the GPU: a tile's
// usable levels are the fewer of those read and those uploaded.
//
// Shading: a surface's albedo (render/Surface.h, the same surface functions
// as the in-memory renderer's: the hypsometric ramp over the terrain's height
// range unless setSurface gives another, such as drapes or zones), a sun and
// an ambient term, cast shadows and sky light from the overview
// (TiledRelief.h), haze towards the sky colour; fragments over the padding
// and over no-data samples (of tiles read whole) are dropped. The tile cache
// takes texture units 16..28, above the surfaces' own. Contour edges are
// drawn by the fragment stage, as the in-memory renderer's; the curvature
// lines and hatches near the camera by facade/TiledOverlays.h.

#include <sierra/gpu/Objects.h>
#include <sierra/render/Camera.h>
#include <sierra/render/Surface.h>
#include <sierra/render/TiledRelief.h>
#include <sierra/sbt/TileCache.h>
#include <sierra/sbt/TileFile.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <string>

namespace sierra::render {

struct TiledTerrainDesc {
    std::string path;                           // the .sierra file
    uint64_t memoryBudget = uint64_t(1) << 30;  // bytes: the CPU and GPU tile caches together
    int loaderThreads = 2;
    // Array layers a resolution class's texture may have, 0 = the driver's
    // GL_MAX_ARRAY_TEXTURE_LAYERS (2048 on Mesa); beyond it a layer packs
    // several tiles. Lower only to test the packing.
    int maxLayers = 0;
    // Samples a side of the overview that shadows and sky light are computed
    // on at most (render/TiledRelief.h); the driver's texture size caps it.
    // The horizons of 16 azimuths take 64 bytes a sample while they are
    // computed: 268 MB at 2049, 1.07 GB at 4097 (in the process on llvmpipe).
    int reliefMaxSide = 2049;
};

struct TiledFrameOptions {
    float tau = 1.0f;  // pixels
    bool cull = true;
    // Seconds of the camera's motion to prefetch ahead along (from the last frame's eye).
    float prefetchSeconds = 1.0f;
    float frameSeconds = 1.0f / 30.0f;  // the frame period the motion is measured over
    glm::vec3 sunDirection = glm::normalize(glm::vec3(-0.45f, 0.75f, 0.35f));  // towards the sun
    glm::vec3 sky{0.62f, 0.74f, 0.86f};                                        // linear 0..1
    float fogDensity = -1.0f;  // per world unit; < 0 = from the terrain's size
    float ambient = 0.32f;     // the sky's share of full light, 0..1
    // Relief lighting on the overview (render/TiledRelief.h), as the in-memory
    // renderer's: the ambient term times the sky light, the sun's term times
    // the visible share of its disc. Computed at the first frame asking.
    bool shadows = false;
    bool skyLight = false;
    float sunSize = 0.53f;       // the sun's angular diameter, degrees, (0, 20]
    float horizonRadius = 0.0f;  // world units, >= 0; 0 = the whole terrain
    // Contour edges (render/passes/ContourPass.h) this many pixels wide, as
    // the in-memory renderer's; 0 = none.
    float contourWidth = 0.0f;
    glm::vec4 contourColour{0.0f, 0.0f, 0.0f, 1.0f};  // RGBA 0..1
    // Tiles uploaded a frame at most, so one frame's uploads stay short; a
    // still that waits for its tiles takes them all.
    int uploadsPerFrame = 96;
};

struct TiledFrameStats {
    double refineMs = 0.0;  // refinement + strip
    double uploadMs = 0.0;  // tiles and the mesh to the GPU
    double reliefMs = 0.0;  // shadows and sky light computed for this frame
    int64_t triangles = 0;
    int coarseTiles = 0;    // drawn from coarser levels this frame (not arrived yet)
    int uploadedTiles = 0;  // to the GPU this frame
    int gpuTiles = 0;       // held on the GPU
    int gpuSlots = 0;       // tiles the GPU tile cache can hold, all resolutions
    uint64_t gpuBytes = 0;  // the GPU tile cache's textures
    sbt::TileCacheStats cache;
};

class TiledTerrain {
  public:
    // Opens the file and creates the GPU caches (needs a current GL context).
    // The budget goes 3/4 to the CPU cache, 1/4 to the GPU textures. Throws
    // sierra::Error for a file that cannot be read or a budget too small.
    static std::unique_ptr<TiledTerrain> open(const TiledTerrainDesc& desc);
    ~TiledTerrain();

    const sbt::TileFileInfo& info() const;
    const sbt::TileFile& file() const;  // for an overview (sbt::readOverview)
    SceneBounds bounds() const;         // the real samples' box, world units
    glm::vec2 worldRange() const;       // lowest and highest world height of the tile corners

    // Draws one frame into the bound framebuffer (the caller clears it to the
    // sky): makes what arrived resident, refines, asks for what is missing
    // and what lies ahead, uploads, draws. Never waits for a read.
    TiledFrameStats draw(const Camera& camera, int width, int height,
                         const TiledFrameOptions& options);
    // All of draw() but the mesh and the drawing: what a still repeats while
    // it waits for its tiles, without paying for a frame each time.
    TiledFrameStats prepare(const Camera& camera, int width, int height,
                            const TiledFrameOptions& options);
    // Blocks until the loaders have read what the last frame asked for.
    void waitForTiles();
    // Shadows and sky light as the last frame asking for them drew them.
    const TiledRelief& relief() const;
    // The surface the terrain is drawn with from the next frame; its shader
    // is built now (throws sierra::Error for one that does not compile). A
    // surface built for a grid (drapes, zones) takes the real samples'
    // extent, bounds(), as that grid's.
    void setSurface(std::unique_ptr<Surface> surface);
    // The ramp of makeRampSurface over the terrain's heights (stored units),
    // with `desc` as given; the default surface's is {.metric = info().metres}.
    terrain::ColourRamp surfaceRamp(const RampSurfaceDesc& desc) const;

  private:
    struct State;
    explicit TiledTerrain(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

}  // namespace sierra::render
