#pragma once
// The shaded terrain: the mesh with its albedo from one surface function,
// Lambert light and fog. The surface is picked when the program is built
// (shaders/surface_<name>.glsl), so a new shading is a new function.

#include <sierra/gpu/Objects.h>
#include <sierra/gpu/Program.h>
#include <sierra/render/Pass.h>

#include <memory>
#include <string>

namespace sierra::render {

struct TerrainPassDesc {
    std::string surface = "hypsometric";  // shaders/surface_<surface>.glsl
    // Heights in metres: colour by absolute elevation with these lines (see
    // terrain::RampScheme::Elevation); otherwise a ramp over the terrain's range.
    bool metric = false;
    float treeLine = 2000.0f;  // metres
    float snowLine = 3000.0f;  // metres
    // A GMT .cpt colour table (absolute stored heights) replacing the scheme;
    // empty = none. Its table is sampled over the terrain's range.
    std::string cpt;
};

class TerrainPass final : public Pass {
public:
    // Builds the program and the surface's inputs (the hypsometric ramp over
    // the terrain's height range and sea level).
    static std::unique_ptr<TerrainPass> create(const TerrainGpu& terrain, const TerrainPassDesc& desc = {});
    const char* name() const override { return "terrain"; }
    void draw(const FrameContext& frame) override;

private:
    gpu::Program program_;
    gpu::Texture ramp_;
};

}  // namespace sierra::render
