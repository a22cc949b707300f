#include <sierra/render/ZoneSurface.h>

#include "render/TextureFiltering.h"

#include <sierra/core/Error.h>
#include <sierra/core/Timer.h>
#include <sierra/render/Capture.h>
#include <sierra/render/TerrainGpu.h>
#include <sierra/zones/BorderField.h>
#include <sierra/zones/Borderlines.h>
#include <sierra/zones/Palette.h>

#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace sierra::render {

namespace {

constexpr GLuint kZoneUniformBinding = 2;
constexpr int kMaxZones = 256;

// Field for field the layout of `uniform Zones` in shaders/surface_zones.glsl.
struct ZoneUniformData {
    glm::vec4 map{
        0.0f};  // xy: zone-map size in pixels; z: field texels per pixel; w: band width in pixels
    glm::vec4 field{0.0f};  // xy: 1 / the field's size in texels
    std::array<glm::vec4, kMaxZones>
        tile{};  // x: 1 / zone-map pixels per tile repetition; y: height blend 0..1
    std::array<glm::vec4, kMaxZones> colour{};  // rgb: the zone's colour in the palette
};

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
        // The options are compiled in (see surface_zones.glsl): on llvmpipe
        // an option tested at run time costs its instructions even when off.
        std::string d;
        if (triplanar_) d += "#define SIERRA_ZONE_TRIPLANAR 1\n";
        if (variation_) d += "#define SIERRA_ZONE_VARIATION 1\n";
        if (heightBlend_) d += "#define SIERRA_ZONE_HEIGHT_BLEND 1\n";
        d += "#define SIERRA_ZONE_DEBUG " + std::to_string(int(debugView_)) + "\n";
        // The tiles' colour does not follow the height; the water flag alone
        // reads it (terrain_common.glsl).
        d += "#define SIERRA_GROUND_BILINEAR_HEIGHT 1\n";
        return d;
    }
    bool zoneIds() const override { return true; }
    void bind() const override {
        glBindTextureUnit(3, tiles_.id());
        glBindTextureUnit(4, field_.id());
        glBindBufferBase(GL_UNIFORM_BUFFER, kZoneUniformBinding, uniforms_.id());
    }

    gpu::Texture tiles_, field_;
    bool triplanar_ = false, variation_ = false, heightBlend_ = false;
    ZoneDebugView debugView_ = ZoneDebugView::None;
    gpu::Buffer uniforms_;
};

}  // namespace

std::unique_ptr<Surface> makeZoneSurface(const TerrainGpu& terrain,
                                         const terrain::Heightfield& field,
                                         const ZoneSurfaceDesc& desc, ZoneSurfaceInfo* info) {
    if (desc.map != "auto") return makeZoneSurface(field, desc, info);  // the field is not read
    return makeZoneSurface(realSamples(field, terrain), desc, info);
}

std::unique_ptr<Surface> makeZoneSurface(const terrain::Heightfield& real,
                                         const ZoneSurfaceDesc& desc, ZoneSurfaceInfo* info) {
    Stopwatch sw;
    const zones::Palette& palette = desc.palette;
    SIERRA_CHECK(!palette.surfaces.empty() && palette.surfaces.size() <= size_t(kMaxZones),
                 desc.paletteName, ": ", palette.surfaces.size(),
                 " surface types; the renderer takes 1..", kMaxZones);
    zones::ZoneMap map;
    if (desc.map == "auto")
        map = zones::autoZones(real, palette, desc.autoZones);
    else
        map = zones::loadZoneMap(desc.map, palette);
    float band = desc.band >= 0.0f ? desc.band : palette.bandWidth;
    // The field is at least as fine as the map, finer for small maps so bands
    // of a pixel or two stay smooth on screen.
    int maxSide = std::max(map.width, map.height);
    int texelsPerPixel = std::clamp(2048 / std::max(maxSide, 1), 1, 4);
    zones::Borderlines lines =
        zones::buildBorderlines(map, palette, {.epsilon = desc.epsilon, .bandWidth = 0.0});
    zones::BorderField f = zones::buildBorderField(lines, {.texelsPerPixel = texelsPerPixel});

    auto surface = std::make_unique<ZoneSurface>();
    // One 32-bit texel per field texel, so the shader reads the four around a
    // fragment with one textureGather: the pair's zones in the low bytes, the
    // signed distance (texels) as a half float in the high half. The texel's
    // zone is the pair's first where the distance is negative (its sign bit,
    // so -0 counts), else the second: buildBorderField signs it so.
    std::vector<uint32_t> packed(f.zone.size());
    for (size_t k = 0; k < f.zone.size(); ++k) {
        // Where the map has no borderline the field holds 1e9: the largest half.
        const float d = std::clamp(f.signedDistance[k], -65504.0f, 65504.0f);
        packed[k] = uint32_t(f.lowZone[k]) | uint32_t(f.highZone[k]) << 8 |
                    uint32_t(glm::packHalf1x16(d)) << 16;
        const bool negative = (packed[k] & 0x80000000u) != 0;
        SIERRA_CHECK(f.zone[k] == (negative ? f.lowZone[k] : f.highZone[k]), "zone field texel ", k,
                     ": zone ", int(f.zone[k]), " is not the side of its pair (", int(f.lowZone[k]),
                     ", ", int(f.highZone[k]), ") at distance ", f.signedDistance[k]);
    }
    surface->field_ = gpu::Texture::create(
        {.format = GL_R32UI, .width = f.width, .height = f.height, .filter = GL_NEAREST});
    surface->field_.upload(GL_RED_INTEGER, GL_UNSIGNED_INT, packed.data());

    // Tiles: one layer per surface type, all of one square size.
    int tileSize = 0;
    std::vector<gpu::Image> images;
    for (const zones::SurfaceType& s : palette.surfaces) {
        gpu::Image image = readPng(s.tile);
        if (tileSize == 0) tileSize = image.width;
        SIERRA_CHECK(image.width == tileSize && image.height == tileSize, "tile ", s.tile, " is ",
                     image.width, "x", image.height, "; every tile of ", desc.paletteName,
                     " must be ", tileSize, "x", tileSize);
        images.push_back(std::move(image));
    }
    int levels = 1;
    while ((tileSize >> levels) > 0) ++levels;
    surface->tiles_ = gpu::Texture::create({.target = GL_TEXTURE_2D_ARRAY,
                                            .format = GL_RGBA8,
                                            .width = tileSize,
                                            .height = tileSize,
                                            .layers = int(images.size()),
                                            .levels = levels,
                                            .wrap = GL_REPEAT});
    for (size_t k = 0; k < images.size(); ++k)
        surface->tiles_.uploadLayer(int(k), GL_RGBA, GL_UNSIGNED_BYTE, images[k].rgba.data());
    if (levels > 1) surface->tiles_.generateMipmaps();
    applyMipmapFiltering(surface->tiles_, levels);

    auto u = std::make_unique<ZoneUniformData>();
    u->map = {float(map.width), float(map.height), float(texelsPerPixel), band};
    u->field = {1.0f / float(f.width), 1.0f / float(f.height), 0.0f, 0.0f};
    surface->triplanar_ = desc.triplanar;
    surface->variation_ = desc.variation;
    surface->heightBlend_ = desc.heightBlend;
    surface->debugView_ = desc.debugView;
    for (size_t k = 0; k < palette.surfaces.size(); ++k) {
        const zones::SurfaceType& s = palette.surfaces[k];
        u->tile[k] = {float(std::max(desc.samplesPerPixel, 1)) / std::max(s.tileSize, 1e-3f),
                      s.heightBlend, 0.0f, 0.0f};
        u->colour[k] = {float((s.colour >> 16) & 255) / 255.0f,
                        float((s.colour >> 8) & 255) / 255.0f, float(s.colour & 255) / 255.0f,
                        1.0f};
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
