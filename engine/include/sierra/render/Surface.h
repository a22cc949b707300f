#pragma once
// A surface: the albedo function the terrain pass is built with
// (shaders/surface_NAME.glsl defines `vec3 surfaceAlbedo(vec3 world, Ground g)`)
// and the inputs it reads (textures on units 1 and 3..6, uniform blocks from
// binding 2 on). A surface chooses the colour only; the terrain pass lights
// it (terrain.frag). A new shading is a new Surface, never a copy of the
// terrain shader.

#include <sierra/gpu/Objects.h>
#include <sierra/terrain/ColourRamp.h>

#include <glm/glm.hpp>

#include <memory>
#include <optional>
#include <string>

namespace sierra::render {

class TerrainGpu;

class Surface {
  public:
    virtual ~Surface() = default;
    // The shader file that stands for "surface.glsl" in terrain.frag.
    virtual std::string shaderFile() const = 0;
    // Lines inserted after #version when the program is built (driver workarounds, options).
    virtual std::string defines() const { return {}; }
    // False for a surface drawn unlit, one flat tone whatever the light (the
    // paper of the line styles): the pass then compiles the lighting out
    // (SIERRA_UNLIT) and computes no relief fields for it.
    virtual bool lit() const { return true; }
    // True for the zone surface: its bind() binds the zone field and block
    // that shaders/zone_field.glsl reads (the label pass's zone ids).
    virtual bool zoneIds() const { return false; }
    // Binds the surface's textures and blocks (inside the terrain pass's state scope).
    virtual void bind() const = 0;
    // A surface over another (the drapes): the shader file that stands for
    // "surface_base.glsl" in its own; empty for a surface of its own.
    virtual std::string baseShaderFile() const { return {}; }
};

struct RampSurfaceDesc {
    // Heights in metres: colour by absolute elevation with these lines (see
    // terrain::RampScheme::Elevation); otherwise a ramp over the terrain's range.
    bool metric = false;
    float treeLine = 2000.0f;  // metres
    float snowLine = 3000.0f;  // metres
    // A GMT .cpt colour table (absolute stored heights) replacing the scheme;
    // empty = none. It is sampled over the terrain's range.
    std::string cpt;
};

// The hypsometric colour ramp (or the absolute elevation ramp for metric
// heights) as a 1D texture over the terrain's height range, on unit 1.
// Plain paper (shaders/surface_paper.glsl): one flat tone whatever the light,
// for line and hatch styles drawn without shading.
std::unique_ptr<Surface> makePaperSurface();

std::unique_ptr<Surface> makeRampSurface(const TerrainGpu& terrain,
                                         const RampSurfaceDesc& desc = {});
// The same surface drawing `ramp` (over the terrain's world height range).
std::unique_ptr<Surface> makeRampSurface(const terrain::ColourRamp& ramp);

// The ramp makeRampSurface draws with, over the terrain's stored heights (a
// legend shows it).
terrain::ColourRamp surfaceRamp(const TerrainGpu& terrain, const RampSurfaceDesc& desc = {});
// The ramp over stored heights lowest..highest (x, y), with the sea at
// `seaLevel` (stored units; none: no sample is coloured as sea or beach).
terrain::ColourRamp surfaceRamp(glm::vec2 storedRange, std::optional<float> seaLevel,
                                const RampSurfaceDesc& desc = {});

}  // namespace sierra::render
