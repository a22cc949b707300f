#include <sierra/render/passes/TerrainPass.h>

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/TerrainGpu.h>
#include <sierra/terrain/ColourRamp.h>
#include <sierra/terrain/Cpt.h>

#include <cmath>

namespace sierra::render {

namespace {
constexpr int kRampEntries = 1024;
}

std::unique_ptr<TerrainPass> TerrainPass::create(const TerrainGpu& terrain, const TerrainPassDesc& desc) {
    SIERRA_CHECK(desc.surface == "hypsometric", "unknown surface '", desc.surface, "': use hypsometric");
    auto pass = std::make_unique<TerrainPass>();
    std::string surfaceFile = "surface_" + desc.surface + ".glsl";
    gpu::IncludeAlias alias{"surface.glsl", surfaceFile};
    pass->program_ = gpu::Program::create({.vertex = "terrain.vert", .fragment = "terrain.frag",
                                           .aliases = std::span<const gpu::IncludeAlias>(&alias, 1)});
    // The ramp spans the terrain's heights in stored units (the shader looks it
    // up by world height over the same range, linearly), so metric stops stay
    // in metres whatever the vertical scale.
    glm::vec2 range = terrain.worldRange() / terrain.verticalScale();
    // Without water the ramp's sea level sits below the lowest height, so no
    // sample is coloured as sea or beach.
    float sea = terrain.hasWater() ? terrain.seaLevel() : range.x - (range.y - range.x);
    terrain::ColourRamp ramp({.scheme = desc.metric ? terrain::RampScheme::Elevation : terrain::RampScheme::Hypsometric,
                              .minHeight = range.x,
                              .maxHeight = range.y,
                              .seaLevel = sea,
                              .treeLine = desc.treeLine,
                              .snowLine = desc.snowLine});
    std::vector<uint8_t> table = desc.cpt.empty() ? ramp.table(kRampEntries)
                                                  : terrain::readCpt(desc.cpt).ramp(range.x, range.y).table(kRampEntries);
    pass->ramp_ = gpu::Texture::create({.target = GL_TEXTURE_1D, .format = GL_RGBA8, .width = kRampEntries});
    pass->ramp_.upload(GL_RGBA, GL_UNSIGNED_BYTE, table.data());
    return pass;
}

void TerrainPass::draw(const FrameContext& frame) {
    gpu::GlStateScope scope;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glUseProgram(program_.id());
    frame.terrain.bind();
    glBindTextureUnit(1, ramp_.id());
    frame.mesh.draw();
}

}  // namespace sierra::render
