#include <sierra/render/ZoneSurface.h>

#include <sierra/core/Error.h>
#include <sierra/core/Timer.h>
#include <sierra/render/Capture.h>
#include <sierra/render/TerrainGpu.h>
#include <sierra/zones/BorderField.h>
#include <sierra/zones/Borderlines.h>
#include <sierra/zones/Palette.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace sierra::render {

namespace {

constexpr GLuint kZoneUniformBinding = 2;
constexpr int kMaxZones = 256;
// GL_TEXTURE_MAX_ANISOTROPY (core in 4.6, the same value as the EXT extension's).
constexpr GLenum kMaxAnisotropy = 0x84FE;
constexpr GLenum kMaxAnisotropyLimit = 0x84FF;

// Field for field the layout of `uniform Zones` in shaders/surface_zones.glsl.
struct ZoneUniformData {
    glm::vec4 map{0.0f};    // xy: zone-map size in pixels; z: field texels per pixel; w: band width in pixels
    glm::vec4 flags{0.0f};  // x: height blend; y: triplanar; z: variation; w: debug view (0, 1 zones, 2 bands)
    std::array<glm::vec4, kMaxZones> tile{};    // x: zone-map pixels per tile repetition; y: height blend 0..1
    std::array<glm::vec4, kMaxZones> colour{};  // rgb: the zone's colour in the palette
};

bool hasExtension(const char* name) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint k = 0; k < count; ++k)
        if (std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(k))), name) == 0) return true;
    return false;
}

// The real samples of a padded field (padding lies beyond the last real row and column).
terrain::Heightfield realSamples(const terrain::Heightfield& field, const TerrainGpu& terrain) {
    SceneBounds b = terrain.bounds();
    int w = int(std::lround(b.max.x / terrain.spacing().x)) + 1;
    int h = int(std::lround(b.max.z / terrain.spacing().y)) + 1;
    w = std::clamp(w, 1, field.width());
    h = std::clamp(h, 1, field.height());
    terrain::Heightfield real(w, h);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) real.at(i, j) = field.at(i, j);
    real.setSpacing(field.spacingX(), field.spacingZ());
    real.setVerticalScale(field.verticalScale());
    return real;
}

class ZoneSurface final : public Surface {
public:
    std::string shaderFile() const override { return "surface_zones.glsl"; }
    std::string defines() const override {
        return manualFilter_ ? "#define SIERRA_MANUAL_TILE_FILTER 1\n" : std::string();
    }
    void bind() const override {
        glBindTextureUnit(3, tiles_.id());
        glBindTextureUnit(4, zoneId_.id());
        glBindTextureUnit(5, zonePair_.id());
        glBindTextureUnit(6, distance_.id());
        glBindBufferBase(GL_UNIFORM_BUFFER, kZoneUniformBinding, uniforms_.id());
    }

    gpu::Texture tiles_, zoneId_, zonePair_, distance_;
    bool manualFilter_ = false;  // llvmpipe: tiles filtered in the shader (see surface_zones.glsl)
    gpu::Buffer uniforms_;
};

}  // namespace

std::unique_ptr<Surface> makeZoneSurface(const TerrainGpu& terrain, const terrain::Heightfield& field,
                                         const ZoneSurfaceDesc& desc, ZoneSurfaceInfo* info) {
    Stopwatch sw;
    zones::Palette palette = zones::loadPalette(desc.palette);
    SIERRA_CHECK(!palette.surfaces.empty() && palette.surfaces.size() <= size_t(kMaxZones), desc.palette, ": ",
                 palette.surfaces.size(), " surface types; the renderer takes 1..", kMaxZones);
    zones::ZoneMap map;
    if (desc.map == "auto")
        map = zones::autoZones(realSamples(field, terrain), palette, desc.autoZones);
    else
        map = zones::loadZoneMap(desc.map, palette);
    float band = desc.band >= 0.0f ? desc.band : palette.bandWidth;
    // The field is at least as fine as the map, finer for small maps so bands
    // of a pixel or two stay smooth on screen.
    int maxSide = std::max(map.width, map.height);
    int texelsPerPixel = std::clamp(2048 / std::max(maxSide, 1), 1, 4);
    zones::Borderlines lines = zones::buildBorderlines(map, palette, {.epsilon = desc.epsilon, .bandWidth = 0.0});
    zones::BorderField f = zones::buildBorderField(lines, {.texelsPerPixel = texelsPerPixel});

    auto surface = std::make_unique<ZoneSurface>();
    surface->zoneId_ = gpu::Texture::create({.format = GL_R8UI, .width = f.width, .height = f.height,
                                             .filter = GL_NEAREST});
    surface->zoneId_.upload(GL_RED_INTEGER, GL_UNSIGNED_BYTE, f.zone.data());
    std::vector<uint8_t> pairs(f.zone.size() * 2);
    for (size_t k = 0; k < f.zone.size(); ++k) {
        pairs[2 * k] = f.lowZone[k];
        pairs[2 * k + 1] = f.highZone[k];
    }
    surface->zonePair_ = gpu::Texture::create({.format = GL_RG8UI, .width = f.width, .height = f.height,
                                               .filter = GL_NEAREST});
    surface->zonePair_.upload(GL_RG_INTEGER, GL_UNSIGNED_BYTE, pairs.data());
    // Where the map has no borderline the field holds 1e9: clamp so linear
    // filtering stays finite.
    std::vector<float> distance(f.signedDistance);
    for (float& d : distance) d = std::clamp(d, -1e6f, 1e6f);
    surface->distance_ = gpu::Texture::create({.format = GL_R32F, .width = f.width, .height = f.height});
    surface->distance_.upload(GL_RED, GL_FLOAT, distance.data());

    // Tiles: one layer per surface type, all of one square size.
    int tileSize = 0;
    std::vector<gpu::Image> images;
    for (const zones::SurfaceType& s : palette.surfaces) {
        gpu::Image image = readPng(s.tile);
        if (tileSize == 0) tileSize = image.width;
        SIERRA_CHECK(image.width == tileSize && image.height == tileSize, "tile ", s.tile, " is ", image.width, "x",
                     image.height, "; every tile of ", desc.palette, " must be ", tileSize, "x", tileSize);
        images.push_back(std::move(image));
    }
    // The shader's own tile filter (llvmpipe) wraps texel indices by a mask.
    SIERRA_CHECK(tileSize > 0 && (tileSize & (tileSize - 1)) == 0, "tiles of ", desc.palette, " are ", tileSize, "x",
                 tileSize, "; tile sides must be a power of two (256 as sierra-gen tiles makes them)");
    int levels = 1;
    while ((tileSize >> levels) > 0) ++levels;
    surface->tiles_ = gpu::Texture::create({.target = GL_TEXTURE_2D_ARRAY, .format = GL_RGBA8, .width = tileSize,
                                            .height = tileSize, .layers = int(images.size()), .levels = levels,
                                            .wrap = GL_REPEAT});
    for (size_t k = 0; k < images.size(); ++k)
        surface->tiles_.uploadLayer(int(k), GL_RGBA, GL_UNSIGNED_BYTE, images[k].rgba.data());
    if (levels > 1) surface->tiles_.generateMipmaps();
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    surface->manualFilter_ = renderer && std::strstr(renderer, "llvmpipe") != nullptr;
    // No anisotropy on llvmpipe (Mesa 22.3): its software anisotropic filter
    // makes one 1080p frame that samples the array with texture() or
    // textureGrad take minutes; at anisotropy 1 the hardware path costs about
    // what the shader's own filter does (docs/zones.md, "Frame cost").
    if (!surface->manualFilter_ &&
        (hasExtension("GL_EXT_texture_filter_anisotropic") || hasExtension("GL_ARB_texture_filter_anisotropic"))) {
        float limit = 1.0f;
        glGetFloatv(kMaxAnisotropyLimit, &limit);
        glTextureParameterf(surface->tiles_.id(), kMaxAnisotropy, std::min(8.0f, limit));
    }

    auto u = std::make_unique<ZoneUniformData>();
    u->map = {float(map.width), float(map.height), float(texelsPerPixel), band};
    u->flags = {desc.heightBlend ? 1.0f : 0.0f, desc.triplanar ? 1.0f : 0.0f, desc.variation ? 1.0f : 0.0f,
                float(int(desc.debugView))};
    for (size_t k = 0; k < palette.surfaces.size(); ++k) {
        const zones::SurfaceType& s = palette.surfaces[k];
        u->tile[k] = {s.tileSize, s.heightBlend, 0.0f, 0.0f};
        u->colour[k] = {float((s.colour >> 16) & 255) / 255.0f, float((s.colour >> 8) & 255) / 255.0f,
                        float(s.colour & 255) / 255.0f, 1.0f};
    }
    surface->uniforms_ = gpu::Buffer::create({.size = sizeof(ZoneUniformData), .data = u.get()});
    if (info) {
        *info = {.mapWidth = map.width,
                 .mapHeight = map.height,
                 .zoneCount = int(palette.surfaces.size()),
                 .borderVertices = lines.vertices.size(),
                 .borderEdges = lines.edges.size(),
                 .texelsPerPixel = texelsPerPixel,
                 .band = band,
                 .buildMs = sw.ms()};
    }
    return surface;
}

}  // namespace sierra::render
