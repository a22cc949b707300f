#include <sierra/render/Surface.h>

#include <sierra/render/TerrainGpu.h>
#include <sierra/terrain/ColourRamp.h>
#include <sierra/terrain/Cpt.h>

namespace sierra::render {

namespace {

constexpr int kRampEntries = 1024;

class RampSurface final : public Surface {
  public:
    explicit RampSurface(gpu::Texture ramp) : ramp_(std::move(ramp)) {}
    std::string shaderFile() const override { return "surface_hypsometric.glsl"; }
    void bind() const override { glBindTextureUnit(1, ramp_.id()); }

  private:
    gpu::Texture ramp_;
};

class PaperSurface final : public Surface {
  public:
    std::string shaderFile() const override { return "surface_paper.glsl"; }
    bool lit() const override { return false; }
    void bind() const override {}
};

}  // namespace

std::unique_ptr<Surface> makePaperSurface() {
    return std::make_unique<PaperSurface>();
}

terrain::ColourRamp surfaceRamp(glm::vec2 range, std::optional<float> seaLevel,
                                const RampSurfaceDesc& desc) {
    if (!desc.cpt.empty()) return terrain::readCpt(desc.cpt).ramp(range.x, range.y);
    // Without water the ramp's sea level sits below the lowest height, so no
    // sample is coloured as sea or beach.
    const float sea = seaLevel ? *seaLevel : range.x - (range.y - range.x);
    return terrain::ColourRamp(
        {.scheme = desc.metric ? terrain::RampScheme::Elevation : terrain::RampScheme::Hypsometric,
         .minHeight = range.x,
         .maxHeight = range.y,
         .seaLevel = sea,
         .treeLine = desc.treeLine,
         .snowLine = desc.snowLine});
}

terrain::ColourRamp surfaceRamp(const TerrainGpu& terrain, const RampSurfaceDesc& desc) {
    // The ramp spans the terrain's heights in stored units (the shader looks it
    // up by world height over the same range, linearly), so metric stops stay
    // in metres whatever the vertical scale.
    return surfaceRamp(terrain.worldRange() / terrain.verticalScale(),
                       terrain.hasWater() ? std::optional<float>(terrain.seaLevel()) : std::nullopt,
                       desc);
}

std::unique_ptr<Surface> makeRampSurface(const terrain::ColourRamp& ramp) {
    std::vector<uint8_t> table = ramp.table(kRampEntries);
    gpu::Texture texture =
        gpu::Texture::create({.target = GL_TEXTURE_1D, .format = GL_RGBA8, .width = kRampEntries});
    texture.upload(GL_RGBA, GL_UNSIGNED_BYTE, table.data());
    return std::make_unique<RampSurface>(std::move(texture));
}

std::unique_ptr<Surface> makeRampSurface(const TerrainGpu& terrain, const RampSurfaceDesc& desc) {
    return makeRampSurface(surfaceRamp(terrain, desc));
}

}  // namespace sierra::render
