#pragma once
// The mesh of one frame: the SBT refined for the camera and copied into the
// persistently mapped ring (or the full grid's static indices), done once per
// frame and drawn by every pass that needs the mesh.

#include <sierra/gpu/Objects.h>
#include <sierra/gpu/StreamRing.h>
#include <sierra/render/Camera.h>

#include <cstdint>
#include <string>
#include <vector>

namespace sierra::render {

class TerrainGpu;

// Mesh: the TIN given to the terrain (TerrainGpu::setMesh), drawn as it is.
enum class Lod { Sbt, Full, Mesh };

Lod parseLod(const std::string& name);  // "sbt" or "full"; throws otherwise
const char* lodName(Lod lod);           // "sbt", "full" or "tin"

// One element-buffer range and how to draw it. Vertices carry no attributes:
// each index is a linear grid position that the vertex shader reads as
// gl_VertexID.
struct MeshDraw {
    GLenum mode = GL_TRIANGLES;  // GL_TRIANGLE_STRIP (SBT, restart 0xFFFFFFFF) or GL_TRIANGLES
    GLuint vertexArray = 0;
    GLuint elementBuffer = 0;
    size_t byteOffset = 0;
    GLsizei count = 0;
    // Binds the vertex array with the element buffer, turns on fixed-index
    // primitive restart and draws. Call inside a pass (which restores state).
    void draw() const;
};

struct LodSettings {
    Lod lod = Lod::Sbt;
    float tau = 1.0f;      // screen-space error threshold in pixels (SBT), default 1.0
    bool cull = true;      // SBT: frustum culling by bounding spheres
    bool geomorph = true;  // SBT: refine for blending vertices in within tau (see sbt/Morph.h)
    int threads = 0;       // refinement threads, 0 = default
};

// What the frame's mesh cost and holds. CPU stages in wall-clock ms.
struct MeshStats {
    double refineMs = 0.0;   // refinement + strip emission (one pass)
    double uploadMs = 0.0;   // copy into the persistently mapped ring
    uint64_t triangles = 0;  // triangles drawn (strip: non-degenerate)
    uint64_t indices = 0;    // indices drawn, restarts included
    uint64_t bytesUploaded = 0;
    int refineThreads = 0;  // threads the refinement ran on (0: none ran)
    // The CPU the calling thread was on when it finished refining (-1: none ran).
    int refineCpu = -1;
};

class SbtStream {
  public:
    static SbtStream create();

    // Refines the SBT for `camera` (or takes the full grid) and uploads it.
    MeshDraw prepare(TerrainGpu& terrain, const Camera& camera, int width, int height,
                     const LodSettings& lod, MeshStats& stats);
    // Fences the ring region once every pass has issued its draws.
    void finishFrame();

  private:
    gpu::VertexArray vao_;
    gpu::StreamRing ring_;
    std::vector<uint32_t> strip_;  // reused every frame
    bool pending_ = false;
};

}  // namespace sierra::render
