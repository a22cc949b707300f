#include <sierra/scene/MapLayers.h>

#include "scene/Names.h"

#include <sierra/core/Error.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace sierra::scene {

namespace {
constexpr std::pair<const char*, FrameCorner> kCorners[] = {
    {"top-left", FrameCorner::TopLeft},
    {"top-right", FrameCorner::TopRight},
    {"bottom-left", FrameCorner::BottomLeft},
    {"bottom-right", FrameCorner::BottomRight}};
}  // namespace

const char* toString(FrameCorner corner) {
    for (const auto& [name, value] : kCorners)
        if (value == corner) return name;
    return "top-left";
}

FrameCorner parseFrameCorner(const std::string& text, const std::string& what) {
    return detail::parseName(text, what, kCorners);
}

namespace {

// A finite number filling all of `text`, or nullopt.
std::optional<double> number(const std::string& text) {
    if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (*end != '\0' || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
    return v;
}

double requireNumber(const std::string& text, const std::string& what, const std::string& part) {
    const auto v = number(text);
    if (!v) throw Error(msg(what, " '", text, "': ", part, " must be a number"));
    return *v;
}

// RRGGBB (with or without '#') to 0..1 channels.
std::array<float, 3> parseColour(const std::string& text, const std::string& what) {
    const std::string hex = !text.empty() && text[0] == '#' ? text.substr(1) : text;
    if (hex.size() != 6 || hex.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
        throw Error(msg(what, " colour '", text, "': expected #RRGGBB"));
    const unsigned long v = std::strtoul(hex.c_str(), nullptr, 16);
    return {float((v >> 16) & 255) / 255.0f, float((v >> 8) & 255) / 255.0f,
            float(v & 255) / 255.0f};
}

// A number with a hemisphere letter: "15.25E" = 15.25, "3W" = -3; nullopt
// without one of `letters` (positive first) at the end.
std::optional<double> hemisphere(const std::string& text, char positive, char negative) {
    if (text.size() < 2) return std::nullopt;
    const char last = char(std::toupper(static_cast<unsigned char>(text.back())));
    if (last != positive && last != negative) return std::nullopt;
    const auto v = number(text.substr(0, text.size() - 1));
    if (!v || *v < 0.0) return std::nullopt;
    return last == positive ? *v : -*v;
}

void check(bool ok, const std::string& key, const std::string& option, const std::string& what) {
    if (!ok) throw Error(msg(key, " (", option, ") ", what));
}

}  // namespace

DrapeDesc parseDrapeSpec(const std::string& spec, const std::string& what) {
    DrapeDesc d;
    std::string text = spec;
    for (const char* blend : {"multiply", "replace"}) {
        const std::string suffix = std::string(":") + blend;
        if (text.size() > suffix.size() && text.ends_with(suffix)) {
            d.blend = blend;
            text.resize(text.size() - suffix.size());
            break;
        }
    }
    d.image = text;
    const size_t colon = text.rfind(':');
    if (colon != std::string::npos && colon + 1 < text.size()) {
        if (const auto opacity = number(text.substr(colon + 1))) {
            if (!(*opacity >= 0.0 && *opacity <= 1.0))
                throw Error(msg(what, " '", text, "': the opacity after ':' must be 0..1"));
            d.image = text.substr(0, colon);
            d.opacity = float(*opacity);
        }
    }
    if (d.image.empty()) throw Error(msg(what, " '", text, "': no image named"));
    return d;
}

VectorDesc parseVectorSpec(const std::string& text, const std::string& what) {
    VectorDesc v;
    v.file = text;
    // The style follows the last colon when it holds key=value pairs.
    const size_t colon = text.rfind(':');
    if (colon == std::string::npos || text.find('=', colon) == std::string::npos) {
        if (v.file.empty()) throw Error(msg(what, ": no file named"));
        return v;
    }
    v.file = text.substr(0, colon);
    if (v.file.empty()) throw Error(msg(what, " '", text, "': no file named"));
    const std::string style = text.substr(colon + 1);
    size_t start = 0;
    while (start <= style.size()) {
        const size_t comma = std::min(style.find(',', start), style.size());
        const std::string item = style.substr(start, comma - start);
        start = comma + 1;
        if (item.empty()) continue;
        const size_t eq = item.find('=');
        const std::string key = item.substr(0, eq),
                          value = eq == std::string::npos ? "" : item.substr(eq + 1);
        if (key == "colour" || key == "color")
            v.colour = parseColour(value, what);
        else if (key == "width")
            v.width = float(requireNumber(value, what, "width"));
        else if (key == "opacity")
            v.opacity = float(requireNumber(value, what, "opacity"));
        else if (key == "fill")
            v.fillOpacity = float(requireNumber(value, what, "fill"));
        else if (key == "field")
            v.labelField = value;
        else if (key == "dash") {
            const size_t slash = value.find('/');
            if (slash == std::string::npos)
                throw Error(msg(what, " style '", item,
                                "': expected dash=ON/OFF in pixels, e.g. dash=8/4"));
            v.dashOn = float(requireNumber(value.substr(0, slash), what, "dash"));
            v.dashOff = float(requireNumber(value.substr(slash + 1), what, "dash"));
        } else
            throw Error(msg(what, " style '", item,
                            "': expected colour=#RRGGBB, width=PX, opacity=A, fill=A, field=NAME "
                            "or dash=ON/OFF"));
    }
    return v;
}

LabelDesc parseLabelSpec(const std::string& text, const std::string& what) {
    const size_t at = text.rfind('@');
    const std::string expected =
        "expected TEXT@X,Z (world units) or TEXT@LON,LAT with hemisphere "
        "letters, e.g. Summit@15.25E,45.1N";
    if (at == std::string::npos || at == 0) throw Error(msg(what, " '", text, "': ", expected));
    const std::string place = text.substr(at + 1);
    const size_t comma = place.find(',');
    if (comma == std::string::npos) throw Error(msg(what, " '", text, "': ", expected));
    const std::string a = place.substr(0, comma), b = place.substr(comma + 1);
    LabelDesc label;
    label.text = text.substr(0, at);
    if (const auto lon = hemisphere(a, 'E', 'W')) {
        const auto lat = hemisphere(b, 'N', 'S');
        if (!lat) throw Error(msg(what, " '", text, "': the latitude needs N or S: ", expected));
        label.geographic = true;
        label.x = *lon;
        label.z = *lat;
    } else {
        const auto x = number(a), z = number(b);
        if (!x || !z) throw Error(msg(what, " '", text, "': ", expected));
        label.x = *x;
        label.z = *z;
    }
    return label;
}

std::array<double, 4> parseBounds(const std::string& text, const std::string& what) {
    std::array<double, 4> out{};
    size_t start = 0;
    for (int k = 0; k < 4; ++k) {
        const size_t comma = k < 3 ? text.find(',', start) : text.size();
        if (comma == std::string::npos)
            throw Error(msg(what, " '", text, "': expected LEFT,TOP,RIGHT,BOTTOM"));
        const auto v = number(text.substr(start, comma - start));
        if (!v)
            throw Error(msg(what, " '", text, "': expected four numbers LEFT,TOP,RIGHT,BOTTOM"));
        out[size_t(k)] = *v;
        start = comma + 1;
    }
    return out;
}

void validateMapLayers(const MapLayersDesc& layers) {
    for (size_t k = 0; k < layers.drapes.size(); ++k) {
        const DrapeDesc& d = layers.drapes[k];
        const std::string key = "layers.drapes[" + std::to_string(k) + "]";
        check(!d.image.empty(), key + ".image", "--drape", "must name an image");
        check(d.opacity >= 0.0f && d.opacity <= 1.0f, key + ".opacity", "--drape IMAGE:OPACITY",
              msg("must be 0..1, got ", d.opacity));
        check(d.blend == "replace" || d.blend == "multiply", key + ".blend", "--drape-blend",
              "must be replace or multiply, got '" + d.blend + "'");
        check(d.boundsUnits == "samples" || d.boundsUnits == "crs", key + ".bounds_units",
              "--drape-bounds", "must be samples or crs, got '" + d.boundsUnits + "'");
        check(d.resampling == "bilinear" || d.resampling == "cubic", key + ".resampling",
              "--drape-resampling", "must be bilinear or cubic, got '" + d.resampling + "'");
        if (d.bounds) {
            const auto& b = *d.bounds;
            check(b[0] != b[2] && b[1] != b[3] && std::isfinite(b[0] + b[1] + b[2] + b[3]),
                  key + ".bounds", "--drape-bounds", "must span an area");
        }
    }
    for (size_t k = 0; k < layers.vectors.size(); ++k) {
        const VectorDesc& v = layers.vectors[k];
        const std::string key = "layers.vectors[" + std::to_string(k) + "]";
        check(!v.file.empty(), key + ".file", "--vector", "must name a file");
        check(v.width > 0.0f && v.width <= 64.0f, key + ".width", "--vector FILE:width=PX",
              msg("must be in (0, 64] pixels, got ", v.width));
        check(v.opacity >= 0.0f && v.opacity <= 1.0f, key + ".opacity", "--vector FILE:opacity=A",
              msg("must be 0..1, got ", v.opacity));
        check(v.fillOpacity >= 0.0f && v.fillOpacity <= 1.0f, key + ".fill_opacity",
              "--vector FILE:fill=A", msg("must be 0..1, got ", v.fillOpacity));
        check(v.dashOn >= 0.0f && v.dashOn <= 1000.0f && v.dashOff >= 0.0f &&
                  v.dashOff <= 1000.0f && (v.dashOn > 0.0f || v.dashOff == 0.0f),
              key + ".dash", "--vector FILE:dash=ON/OFF",
              msg("needs 0..1000 pixels each, ON > 0 when OFF is, got ", v.dashOn, "/", v.dashOff));
        for (float c : v.colour)
            check(c >= 0.0f && c <= 1.0f, key + ".colour", "--vector FILE:colour=#RRGGBB",
                  "channels must be 0..1");
    }
    for (size_t k = 0; k < layers.labels.size(); ++k) {
        const LabelDesc& l = layers.labels[k];
        const std::string key = "layers.labels[" + std::to_string(k) + "]";
        check(!l.text.empty(), key + ".text", "--label", "must not be empty");
        check(std::isfinite(l.x) && std::isfinite(l.z), key, "--label", "needs a finite place");
        if (l.geographic)
            check(std::abs(l.z) <= 90.0, key + ".latitude", "--label", "must be within 90 degrees");
    }
    const FurnitureDesc& f = layers.furniture;
    check(f.textPixels >= 6.0f && f.textPixels <= 128.0f, "layers.text_pixels", "--text-size",
          msg("must be 6..128 pixels, got ", f.textPixels));
}

}  // namespace sierra::scene
