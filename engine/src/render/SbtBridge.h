#pragma once
// The render module's view of the SBT: per-vertex data for the GPU texture,
// per-frame view-dependent refinement into a reused index vector, and the
// full-grid triangle list.

#include <sierra/terrain/Heightfield.h>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace sierra::render {

struct SbtView {
    glm::vec3 eye{0.0f};
    float lambda = 1.0f;  // viewport height / (2 tan(fovy / 2))
    float tau = 1.0f;     // pixels
    bool cull = true;
    // Geomorphing: refine at sbt::refinementTau(tau), so every vertex has
    // finished blending in by the time its error bound reaches tau.
    bool geomorph = true;
    std::array<glm::vec4, 6> planes{};
};

class SbtBridge {
  public:
    SbtBridge(const terrain::Heightfield& field, int threads);
    ~SbtBridge();

    std::span<const float> errors() const;      // world units, per sample
    std::span<const float> radii() const;       // world units, per sample
    const terrain::Heightfield& field() const;  // the refined surface (outlives the bridge)
    std::span<const float> morphBase() const;   // world heights, per sample
    // Frees the morph base once it is on the GPU (4 bytes per sample).
    void releaseMorphBase();
    // Builds the refiner's view keys for `view` if not yet built
    // (sbt::Refiner::prepareView).
    void prepareView(const SbtView& view);
    // Bytes of the refiner's keys built so far.
    size_t keyBytes() const;

    // Refines for the view and writes the strip (restart 0xFFFFFFFF) into out;
    // returns the triangle count.
    uint64_t refineView(const SbtView& view, std::vector<uint32_t>& out, int threads);
    // Subtrees the last refineView dropped whole at the frustum (0 without culling).
    int64_t lastCulledSubtrees() const;
    // Threads the last refineView ran on (sbt::StripMesh::threads).
    int lastThreads() const;

    // Every cell of the grid as indexed triangles (3 indices each), with the
    // diagonals of the SBT's finest level.
    std::vector<uint32_t> fullGridTriangles() const;

  private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace sierra::render
