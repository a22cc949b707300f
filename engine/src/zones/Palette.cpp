#include <sierra/zones/Palette.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace sierra::zones {
namespace {

Colour parseColour(const nlohmann::json& value, const std::string& where) {
    if (!value.is_string()) throw Error(msg(where, ": colour must be a string \"#rrggbb\""));
    std::string text = value.get<std::string>();
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
    if (!ok) throw Error(msg(where, ": colour \"", text, "\" is not of the form \"#rrggbb\""));
    return colour;
}

float parseNumber(const nlohmann::json& object, const char* key, float fallback, float lo, float hi,
                  const std::string& where) {
    if (!object.contains(key)) return fallback;
    const auto& v = object.at(key);
    if (!v.is_number()) throw Error(msg(where, ": \"", key, "\" must be a number"));
    double x = v.get<double>();
    if (!std::isfinite(x) || x < lo || x > hi)
        throw Error(msg(where, ": \"", key, "\" must be in [", lo, ", ", hi, "], got ", x));
    return float(x);
}

}  // namespace

std::string colourHex(Colour colour) {
    char text[8];
    std::snprintf(text, sizeof text, "#%06x", unsigned(colour & 0xffffffu));
    return text;
}

int Palette::find(Colour colour) const {
    for (size_t k = 0; k < surfaces.size(); ++k)
        if (surfaces[k].colour == colour) return int(k);
    return -1;
}

int Palette::findName(const std::string& name) const {
    for (size_t k = 0; k < surfaces.size(); ++k)
        if (surfaces[k].name == name) return int(k);
    return -1;
}

Palette parsePalette(const std::string& text, const std::string& baseDir, const std::string& source,
                     bool checkTiles) {
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {  // parse errors and numbers out of range
        throw Error(msg("palette ", source, " is not JSON: ", e.what()));
    }
    if (!doc.is_object() || !doc.contains("zones") || !doc["zones"].is_array())
        throw Error(msg("palette ", source, ": expected an object with a \"zones\" array"));
    Palette palette;
    if (doc.contains("borderline"))
        palette.borderline =
            parseColour(doc["borderline"], msg("palette ", source, ": borderline"));
    palette.bandWidth = parseNumber(doc, "bandWidth", 0.0f, 0.0f, 1e4f, msg("palette ", source));
    const auto& zones = doc["zones"];
    if (zones.empty()) throw Error(msg("palette ", source, ": \"zones\" is empty"));
    if (zones.size() > 255)
        throw Error(msg("palette ", source, ": at most 255 zones, got ", zones.size()));
    for (size_t k = 0; k < zones.size(); ++k) {
        const auto& z = zones[k];
        std::string where = msg("palette ", source, ": zone ", k);
        if (!z.is_object()) throw Error(msg(where, " must be an object"));
        if (!z.contains("name") || !z["name"].is_string() || z["name"].get<std::string>().empty())
            throw Error(msg(where, ": needs a non-empty \"name\""));
        SurfaceType s;
        s.name = z["name"].get<std::string>();
        where = msg(where, " (", s.name, ")");
        if (s.name.find('|') != std::string::npos)
            throw Error(msg(where, ": '|' is reserved for band zones"));
        if (!z.contains("colour")) throw Error(msg(where, ": needs a \"colour\" \"#rrggbb\""));
        s.colour = parseColour(z["colour"], where);
        if (!z.contains("tile") || !z["tile"].is_string())
            throw Error(msg(where, ": needs a \"tile\" image path (relative to the palette)"));
        std::filesystem::path tile = z["tile"].get<std::string>();
        if (tile.is_relative() && !baseDir.empty()) tile = std::filesystem::path(baseDir) / tile;
        s.tile = tile.lexically_normal().string();
        if (checkTiles && !std::filesystem::is_regular_file(s.tile))
            throw Error(msg(where, ": tile file ", s.tile, " does not exist"));
        s.tileSize = parseNumber(z, "tileSize", s.tileSize, 1e-3f, 1e6f, where);
        s.heightBlend = parseNumber(z, "heightBlend", s.heightBlend, 0.0f, 1.0f, where);
        if (s.colour == palette.borderline)
            throw Error(msg(where, ": colour ", colourHex(s.colour), " is the borderline colour"));
        if (palette.find(s.colour) >= 0)
            throw Error(msg(where, ": colour ", colourHex(s.colour), " is used twice"));
        if (palette.findName(s.name) >= 0)
            throw Error(msg(where, ": name \"", s.name, "\" is used twice"));
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
    nlohmann::json doc;
    doc["borderline"] = colourHex(palette.borderline);
    doc["bandWidth"] = palette.bandWidth;
    doc["zones"] = nlohmann::json::array();
    for (const auto& s : palette.surfaces)
        doc["zones"].push_back({{"name", s.name},
                                {"colour", colourHex(s.colour)},
                                {"tile", s.tile},
                                {"tileSize", s.tileSize},
                                {"heightBlend", s.heightBlend}});
    return doc.dump(2) + "\n";
}

}  // namespace sierra::zones
