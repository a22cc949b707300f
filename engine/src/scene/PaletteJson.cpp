#include <sierra/scene/PaletteJson.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <filesystem>

namespace sierra::scene {

using zones::Colour;
using zones::colourHex;
using zones::Palette;
using zones::SurfaceType;

namespace {

Colour parseColour(const JsonObject& r, const Json& value, const std::string& key) {
    const std::string text = r.toString(value, key);
    bool ok = text.size() == 7 && text[0] == '#';
    Colour colour = 0;
    for (size_t k = 1; ok && k < text.size(); ++k) {
        char c = text[k];
        int digit = c >= '0' && c <= '9'   ? c - '0'
                    : c >= 'a' && c <= 'f' ? c - 'a' + 10
                    : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                           : -1;
        if (digit < 0) ok = false;
        colour = colour * 16 + Colour(digit < 0 ? 0 : digit);
    }
    if (!ok) r.badValue(key, msg("colour \"", text, "\" is not of the form \"#rrggbb\""));
    return colour;
}

// A number of key `key` in [lo, hi]; `fallback` when absent.
float number(JsonObject& r, const char* key, float fallback, float lo, float hi) {
    const Json* v = r.allow(key);
    if (!v) return fallback;
    const float x = r.toFloat(*v, r.keyPath(key));
    if (x < lo || x > hi)
        r.badValue(r.keyPath(key), msg("must be in [", lo, ", ", hi, "], got ", x));
    return x;
}

SurfaceType readSurface(JsonObject& z, const std::string& baseDir, bool checkTiles) {
    SurfaceType s;
    const Json* name = z.allow("name");
    if (!name || !name->is_string() || name->get<std::string>().empty())
        z.badValue(z.path(), "needs a non-empty \"name\"");
    s.name = name->get<std::string>();
    const std::string where = msg(z.path(), " (", s.name, ")");
    if (s.name.find('|') != std::string::npos) z.badValue(where, "'|' is reserved for band zones");
    const Json* colour = z.allow("colour");
    if (!colour) z.badValue(where, "needs a \"colour\" \"#rrggbb\"");
    s.colour = parseColour(z, *colour, z.keyPath("colour"));
    const Json* tile = z.allow("tile");
    if (!tile || !tile->is_string())
        z.badValue(where, "needs a \"tile\" image path (relative to the palette)");
    std::filesystem::path path = tile->get<std::string>();
    if (path.is_relative() && !baseDir.empty()) path = std::filesystem::path(baseDir) / path;
    s.tile = path.lexically_normal().string();
    if (checkTiles && !std::filesystem::is_regular_file(s.tile))
        z.badValue(where, msg("tile file ", s.tile, " does not exist"));
    s.tileSize = number(z, "tile_size", s.tileSize, 1e-3f, 1e6f);
    s.heightBlend = number(z, "height_blend", s.heightBlend, 0.0f, 1.0f);
    z.finish();
    return s;
}

}  // namespace

Palette parsePalette(const std::string& text, const std::string& baseDir, const std::string& source,
                     bool checkTiles) {
    const Json doc = parseJson(text, source);
    JsonObject top(doc, "", source);
    Palette palette;
    if (const Json* borderline = top.allow("borderline"))
        palette.borderline = parseColour(top, *borderline, "borderline");
    palette.bandWidth = number(top, "band_width", 0.0f, 0.0f, 1e4f);
    const Json* zones = top.allow("zones");
    top.finish();
    if (!zones) top.badValue("the top level", "needs a \"zones\" array");
    if (!zones->is_array()) top.wrongType(*zones, "zones", "an array of zone objects");
    if (zones->empty()) top.badValue("zones", "is empty");
    if (zones->size() > 255) top.badValue("zones", msg("at most 255 zones, got ", zones->size()));
    for (size_t k = 0; k < zones->size(); ++k) {
        JsonObject z((*zones)[k], msg("zones[", k, "]"), source);
        SurfaceType s = readSurface(z, baseDir, checkTiles);
        const std::string where = msg(z.path(), " (", s.name, ")");
        if (s.colour == palette.borderline)
            z.badValue(where, msg("colour ", colourHex(s.colour), " is the borderline colour"));
        if (palette.find(s.colour) >= 0)
            z.badValue(where, msg("colour ", colourHex(s.colour), " is used twice"));
        if (palette.findName(s.name) >= 0)
            z.badValue(where, msg("name \"", s.name, "\" is used twice"));
        palette.surfaces.push_back(std::move(s));
    }
    return palette;
}

Palette loadPalette(const std::string& path, bool checkTiles) {
    auto bytes = readFileBytes(path);
    std::string text(bytes.begin(), bytes.end());
    std::string base = std::filesystem::path(path).parent_path().string();
    return parsePalette(text, base, path, checkTiles);
}

std::string paletteToJson(const Palette& palette) {
    Json doc;
    doc["borderline"] = colourHex(palette.borderline);
    doc["band_width"] = palette.bandWidth;
    doc["zones"] = Json::array();
    for (const auto& s : palette.surfaces)
        doc["zones"].push_back({{"name", s.name},
                                {"colour", colourHex(s.colour)},
                                {"tile", s.tile},
                                {"tile_size", s.tileSize},
                                {"height_blend", s.heightBlend}});
    return doc.dump(2) + "\n";
}

}  // namespace sierra::scene
