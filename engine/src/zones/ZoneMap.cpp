#include <sierra/zones/ZoneMap.h>

#include "Png.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/terrain/HeightfieldIO.h>
#include <sierra/terrain/Maps.h>

#include <stb/stb_image.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

namespace sierra::zones {
namespace {

// Largest zone-map side accepted (a 16384^2 map is 256 M pixels).
constexpr int kMaxSide = 16384;

}  // namespace

ZoneMap classifyZoneMap(int width, int height, std::span<const uint8_t> rgb, const Palette& palette,
                        const std::string& source) {
    SIERRA_CHECK(width > 0 && height > 0 && width <= kMaxSide && height <= kMaxSide, "zone map ",
                 source, ": size ", width, "x", height, " must be 1..", kMaxSide, " per side");
    SIERRA_CHECK(rgb.size() == size_t(width) * size_t(height) * 3, "zone map ", source,
                 ": expected ", size_t(width) * size_t(height) * 3, " RGB bytes, got ", rgb.size());
    ZoneMap map;
    map.width = width;
    map.height = height;
    map.ids.resize(size_t(width) * size_t(height));
    // A small cache: zone maps use few colours, so the last hit is usually right.
    Colour lastColour = 0xffffffffu;
    int16_t lastId = 0;
    bool anyBorderline = false;
    for (size_t p = 0; p < map.ids.size(); ++p) {
        Colour c = Colour(rgb[3 * p]) << 16 | Colour(rgb[3 * p + 1]) << 8 | Colour(rgb[3 * p + 2]);
        if (c != lastColour) {
            int id = c == palette.borderline ? kBorderlinePixel : palette.find(c);
            if (id < 0 && c != palette.borderline)
                throw Error(msg("zone map ", source, ": colour ", colourHex(c), " at pixel (",
                                p % size_t(width), ", ", p / size_t(width),
                                ") is not in the palette (nor the borderline colour ",
                                colourHex(palette.borderline), ")"));
            lastColour = c;
            lastId = int16_t(id);
        }
        map.ids[p] = lastId;
        anyBorderline |= lastId == kBorderlinePixel;
    }
    if (anyBorderline) {
        map.layout = ZoneLayout::Borderlines;
        // Its frame runs through the outer pixel centres: one row or column has none.
        SIERRA_CHECK(width >= 2 && height >= 2, "zone map ", source, ": ", width, "x", height,
                     " pixels with borderline pixels (", colourHex(palette.borderline),
                     "); a Figure 1 zone map needs at least 2x2");
        // Figure 1 needs a borderline between every two zones: 4-neighbours of
        // different zones would have no vertex between them.
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                int a = map.at(x, y);
                if (a < 0) continue;
                for (auto [nx, ny] : {std::array{x + 1, y}, std::array{x, y + 1}}) {
                    if (nx >= width || ny >= height) continue;
                    int b = map.at(nx, ny);
                    if (b >= 0 && b != a)
                        throw Error(
                            msg("zone map ", source, ": zones \"", palette.surfaces[a].name,
                                "\" and \"", palette.surfaces[b].name, "\" touch at pixels (", x,
                                ", ", y, ") and (", nx, ", ", ny,
                                ") with no borderline pixel between them (Figure 1 layout: ",
                                colourHex(palette.borderline), " lines between all zones)"));
                }
            }
    }
    return map;
}

ZoneMap loadZoneMap(const std::string& path, const Palette& palette) {
    // An RGB image of kMaxSide^2 stored uncompressed, plus framing, is the largest.
    const uint64_t maxBytes = uint64_t(kMaxSide) * kMaxSide * 4 + (uint64_t(1) << 20);
    const std::vector<uint8_t> bytes =
        readFileBytes(path, maxBytes,
                      msg("a zone map of at most ", kMaxSide, "x", kMaxSide, " pixels is smaller"));
    // PNG is decoded like a PNG heightmap: every CRC checked, the size limits
    // before the pixels are allocated.
    static const uint8_t kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() >= 8 && std::equal(kPngSignature, kPngSignature + 8, bytes.begin())) {
        const terrain::RgbImage image = terrain::decodePngRgb8(msg("zone map ", path), bytes);
        return classifyZoneMap(image.width, image.height, image.rgb, palette, path);
    }
    // Other formats (PPM/PGM, BMP, TGA) through the image library, its header
    // read and the size checked before the pixels are decoded.
    int w = 0, h = 0, channels = 0;
    if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels))
        throw Error(msg("zone map ", path, " is not an image (", stbi_failure_reason(),
                        "); expected a PNG whose colours are in the palette"));
    SIERRA_CHECK(w > 0 && h > 0 && w <= kMaxSide && h <= kMaxSide, "zone map ", path, ": size ", w,
                 "x", h, " must be 1..", kMaxSide, " per side");
    std::unique_ptr<uint8_t, void (*)(void*)> pixels(
        stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels, 3),
        stbi_image_free);
    if (!pixels) throw Error(msg("zone map ", path, " cannot be decoded: ", stbi_failure_reason()));
    return classifyZoneMap(w, h, std::span<const uint8_t>(pixels.get(), size_t(w) * size_t(h) * 3),
                           palette, path);
}

ZoneMap autoZones(const terrain::Heightfield& field, const Palette& palette,
                  const AutoZoneDesc& desc) {
    SIERRA_CHECK(!field.empty(), "auto-zoning needs a non-empty heightfield");
    for (float f : {desc.deepWater, desc.sandTop, desc.snowLine})
        SIERRA_CHECK(f >= 0.0f && f <= 1.0f, "auto-zoning: fractions must be in [0, 1], got ", f);
    SIERRA_CHECK(desc.rockSlope > 0.0f && desc.rockSlope <= 90.0f,
                 "auto-zoning: rockSlope must be in (0, 90] degrees, got ", desc.rockSlope);
    auto id = [&](const std::string& name) {
        int k = palette.findName(name);
        if (k < 0) throw Error(msg("auto-zoning: the palette has no surface named \"", name, "\""));
        return int16_t(k);
    };
    const int16_t deep = id(desc.deepName), shallow = id(desc.shallowName),
                  sand = id(desc.sandName), grass = id(desc.grassName), rock = id(desc.rockName),
                  snow = id(desc.snowName);
    auto [lo, hi] = field.range();
    const float sea = desc.seaLevel;
    const float deepBelow = sea - desc.deepWater * std::max(0.0f, sea - lo);
    const float sandTop = sea + desc.sandTop * std::max(0.0f, hi - sea);
    const float snowLine = sea + desc.snowLine * std::max(0.0f, hi - sea);
    const double tanRock = std::tan(double(desc.rockSlope) * 3.14159265358979323846 / 180.0);
    const int w = field.width(), h = field.height();
    const double vs = field.verticalScale();
    ZoneMap map;
    map.width = w;
    map.height = h;
    map.ids.resize(size_t(w) * size_t(h));
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            float z = field.at(i, j);
            int16_t zone;
            if (z < sea) {
                zone = z < deepBelow ? deep : shallow;
            } else {
                // Central differences (one-sided at the border), world units.
                int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, w - 1);
                int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, h - 1);
                double gx = i1 > i0 ? (field.at(i1, j) - field.at(i0, j)) * vs /
                                          ((i1 - i0) * double(field.spacingX()))
                                    : 0.0;
                double gz = j1 > j0 ? (field.at(i, j1) - field.at(i, j0)) * vs /
                                          ((j1 - j0) * double(field.spacingZ()))
                                    : 0.0;
                if (gx * gx + gz * gz > tanRock * tanRock)
                    zone = rock;
                else if (z < sandTop)
                    zone = sand;
                else if (z >= snowLine)
                    zone = snow;
                else
                    zone = grass;
            }
            map.ids[size_t(j) * size_t(w) + size_t(i)] = zone;
        }
    // Majority passes: a pixel takes the zone most of its 3x3 neighbourhood has
    // (5 of 9 or more), which removes single-pixel specks that would become
    // tiny islands of borderlines without changing the bands' shapes.
    for (int pass = 0; pass < desc.smoothPasses; ++pass) {
        std::vector<int16_t> next = map.ids;
        for (int j = 1; j + 1 < h; ++j)
            for (int i = 1; i + 1 < w; ++i) {
                std::array<int16_t, 9> n;
                int k = 0;
                for (int dj = -1; dj <= 1; ++dj)
                    for (int di = -1; di <= 1; ++di) n[k++] = map.at(i + di, j + dj);
                for (int a = 0; a < 9; ++a) {
                    int count = 0;
                    for (int b = 0; b < 9; ++b) count += n[b] == n[a];
                    if (count >= 5) {
                        next[size_t(j) * size_t(w) + size_t(i)] = n[a];
                        break;
                    }
                }
            }
        map.ids.swap(next);
    }
    return map;
}

ZoneMap drawBorderlines(const ZoneMap& map) {
    SIERRA_CHECK(map.layout == ZoneLayout::Touching, "drawBorderlines needs a Touching zone map");
    ZoneMap out = map;
    out.layout = ZoneLayout::Borderlines;
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) {
            int a = map.at(x, y);
            bool border = (x + 1 < map.width && map.at(x + 1, y) != a) ||
                          (y + 1 < map.height && map.at(x, y + 1) != a);
            if (border) out.ids[size_t(y) * size_t(map.width) + size_t(x)] = kBorderlinePixel;
        }
    return out;
}

std::vector<uint8_t> zoneMapRgb(const ZoneMap& map, const Palette& palette) {
    std::vector<uint8_t> rgb(map.ids.size() * 3);
    for (size_t p = 0; p < map.ids.size(); ++p) {
        int id = map.ids[p];
        SIERRA_CHECK(id < int(palette.surfaces.size()), "zone id ", id, " is not in the palette");
        Colour c = id < 0 ? palette.borderline : palette.surfaces[size_t(id)].colour;
        rgb[3 * p] = uint8_t(c >> 16);
        rgb[3 * p + 1] = uint8_t(c >> 8);
        rgb[3 * p + 2] = uint8_t(c);
    }
    return rgb;
}

std::vector<uint8_t> encodeZoneMapPng(const ZoneMap& map, const Palette& palette) {
    auto rgb = zoneMapRgb(map, palette);
    return detail::encodePng8(map.width, map.height, 3, rgb.data());
}

}  // namespace sierra::zones
