// The option table's entries for the layers over the terrain (MapLayers.h):
// drapes, vector layers, labels and map furniture. --drape, --vector and
// --label may be given several times (OptionEntry::repeatable); the file
// keeps each as an array of objects under "layers".
#include "OptionBuilder.h"

#include <sierra/scene/MapLayers.h>

#include <cmath>

namespace sierra::scene::detail {

namespace {

// A finite number kept as a double (places and bounds: CRS units need more
// than a float's digits).
double toDouble(const JsonObject& r, const Json& v, const std::string& key) {
    if (!v.is_number()) r.wrongType(v, key, "a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) r.badValue(key, "must be finite");
    return d;
}

Json drapeJson(const DrapeDesc& d) {
    Json j = Json::object();
    j["image"] = d.image;
    j["opacity"] = jsonNumber(d.opacity);
    j["blend"] = d.blend;
    j["bounds"] =
        d.bounds ? Json::array({(*d.bounds)[0], (*d.bounds)[1], (*d.bounds)[2], (*d.bounds)[3]})
                 : Json(nullptr);
    j["bounds_units"] = d.boundsUnits;
    j["resampling"] = d.resampling;
    return j;
}

DrapeDesc drapeFromJson(const JsonObject& parent, const Json& v, const std::string& key) {
    if (!v.is_object()) parent.wrongType(v, key, "an object");
    JsonObject r(v, key, parent.source());
    DrapeDesc d;
    r.field("image", [&](const Json& x, const std::string& k) { d.image = r.toString(x, k); });
    r.field("opacity", [&](const Json& x, const std::string& k) { d.opacity = r.toFloat(x, k); });
    r.field("blend", [&](const Json& x, const std::string& k) { d.blend = r.toString(x, k); });
    r.field("bounds", [&](const Json& x, const std::string& k) {
        if (x.is_null()) return d.bounds.reset();
        if (!x.is_array() || x.size() != 4) r.wrongType(x, k, "[left, top, right, bottom] or null");
        std::array<double, 4> b{};
        for (size_t i = 0; i < 4; ++i) b[i] = toDouble(r, x[i], k + "[" + std::to_string(i) + "]");
        d.bounds = b;
    });
    r.field("bounds_units",
            [&](const Json& x, const std::string& k) { d.boundsUnits = r.toString(x, k); });
    r.field("resampling",
            [&](const Json& x, const std::string& k) { d.resampling = r.toString(x, k); });
    r.finish();
    return d;
}

Json vectorJson(const VectorDesc& v) {
    Json j = Json::object();
    j["file"] = v.file;
    j["where"] = v.where;
    j["label_field"] = v.labelField;
    j["colour"] =
        Json::array({jsonNumber(v.colour[0]), jsonNumber(v.colour[1]), jsonNumber(v.colour[2])});
    j["width"] = jsonNumber(v.width);
    j["opacity"] = jsonNumber(v.opacity);
    j["fill_opacity"] = jsonNumber(v.fillOpacity);
    j["dash"] = Json::array({jsonNumber(v.dashOn), jsonNumber(v.dashOff)});
    return j;
}

VectorDesc vectorFromJson(const JsonObject& parent, const Json& v, const std::string& key) {
    if (!v.is_object()) parent.wrongType(v, key, "an object");
    JsonObject r(v, key, parent.source());
    VectorDesc d;
    r.field("file", [&](const Json& x, const std::string& k) { d.file = r.toString(x, k); });
    r.field("where", [&](const Json& x, const std::string& k) { d.where = r.toString(x, k); });
    r.field("label_field",
            [&](const Json& x, const std::string& k) { d.labelField = r.toString(x, k); });
    r.field("colour", [&](const Json& x, const std::string& k) {
        if (!x.is_array() || x.size() != 3) r.wrongType(x, k, "[r, g, b]");
        for (size_t i = 0; i < 3; ++i)
            d.colour[i] = r.toFloat(x[i], k + "[" + std::to_string(i) + "]");
    });
    r.field("width", [&](const Json& x, const std::string& k) { d.width = r.toFloat(x, k); });
    r.field("opacity", [&](const Json& x, const std::string& k) { d.opacity = r.toFloat(x, k); });
    r.field("fill_opacity",
            [&](const Json& x, const std::string& k) { d.fillOpacity = r.toFloat(x, k); });
    r.field("dash", [&](const Json& x, const std::string& k) {
        if (!x.is_array() || x.size() != 2) r.wrongType(x, k, "[on, off] pixels");
        d.dashOn = r.toFloat(x[0], k + "[0]");
        d.dashOff = r.toFloat(x[1], k + "[1]");
    });
    r.finish();
    return d;
}

Json labelJson(const LabelDesc& l) {
    Json j = Json::object();
    j["text"] = l.text;
    j["x"] = l.x;
    j["z"] = l.z;
    j["geographic"] = l.geographic;
    return j;
}

LabelDesc labelFromJson(const JsonObject& parent, const Json& v, const std::string& key) {
    if (!v.is_object()) parent.wrongType(v, key, "an object");
    JsonObject r(v, key, parent.source());
    LabelDesc l;
    r.field("text", [&](const Json& x, const std::string& k) { l.text = r.toString(x, k); });
    r.field("x", [&](const Json& x, const std::string& k) { l.x = toDouble(r, x, k); });
    r.field("z", [&](const Json& x, const std::string& k) { l.z = toDouble(r, x, k); });
    r.field("geographic",
            [&](const Json& x, const std::string& k) { l.geographic = r.toBool(x, k); });
    r.finish();
    return l;
}

// A repeatable option and its array key: each word one element.
template <typename T>
OptionEntry& list(Builder& b, const Text& t, std::vector<T>& (*ref)(Scene&),
                  T (*parse)(const std::string&, const std::string&), Json (*toJson)(const T&),
                  T (*fromJson)(const JsonObject&, const Json&, const std::string&)) {
    OptionEntry& e = b.entry(t, 1);
    e.repeatable = true;
    const std::string flag = t.flag;
    e.fromWords = [ref, parse, flag](Scene& s, Words w) {
        ref(s).clear();
        for (const std::string& word : w) ref(s).push_back(parse(word, flag));
    };
    e.toJson = [ref, toJson](const Scene& s) {
        Json a = Json::array();
        for (const T& item : ref(const_cast<Scene&>(s))) a.push_back(toJson(item));
        return a;
    };
    e.fromJson = [ref, fromJson](Scene& s, const JsonObject& r, const Json& v,
                                 const std::string& k) {
        if (!v.is_array()) r.wrongType(v, k, "an array");
        ref(s).clear();
        for (size_t i = 0; i < v.size(); ++i)
            ref(s).push_back(fromJson(r, v[i], k + "[" + std::to_string(i) + "]"));
    };
    return e;
}

}  // namespace

constexpr const char* kCornerNames =
    "`\"top-left\"`, `\"top-right\"`, `\"bottom-left\"`, `\"bottom-right\"`";

void layerEntries(std::vector<OptionEntry>& out) {
    Builder b(out, kLayerOptions, "Layers: drapes and vectors (docs/layers.md)");
    list<DrapeDesc>(
        b,
        {"--drape", "IMAGE[:OPACITY][:multiply]", "layers.drapes", "array of objects",
         "An image over the terrain (GeoTIFF, PNG, JPEG, ... through GDAL), warped "
         "from its georeference or stretched; repeat to stack; :multiply for the "
         "relief look",
         "images blended in order over the surface: `image`, `opacity` 0..1, `blend` "
         "replace or multiply, `bounds` [left, top, right, bottom] or null, "
         "`bounds_units` samples or crs, `resampling` bilinear or cubic"},
        [](Scene& s) -> std::vector<DrapeDesc>& { return s.layers.drapes; }, parseDrapeSpec,
        drapeJson, drapeFromJson);
    OptionEntry& bounds = b.entry({"--drape-bounds", "L,T,R,B", "", "",
                                   "Place the drapes' corners at left, top, right, bottom "
                                   "(grid samples; --drape-bounds-units crs for the DEM's system)"},
                                  1);
    bounds.fromWords = [](Scene& s, Words w) {
        const auto v = parseBounds(w[0], "--drape-bounds");
        for (DrapeDesc& d : s.layers.drapes) d.bounds = v;
    };
    bounds.docOption = "";
    OptionEntry& units =
        b.entry({"--drape-bounds-units", "samples|crs", "", "", "The units of --drape-bounds"}, 1);
    units.fromWords = [](Scene& s, Words w) {
        for (DrapeDesc& d : s.layers.drapes) d.boundsUnits = w[0];
    };
    list<VectorDesc>(
        b,
        {"--vector", "FILE[:STYLE]", "layers.vectors", "array of objects",
         "A vector layer (GeoJSON, GeoPackage, Shapefile, GPX, KML through OGR); "
         "STYLE: colour=#RRGGBB,width=PX,opacity=A,fill=A,field=NAME,dash=ON/OFF; repeat for more",
         "vector layers: `file`, `where` (OGR SQL), `label_field`, `colour` [r, g, b] "
         "0..1, `width` pixels, `opacity` 0..1, `fill_opacity` 0..1, `dash` [on, off] pixels ([0, "
         "0] solid)"},
        [](Scene& s) -> std::vector<VectorDesc>& { return s.layers.vectors; }, parseVectorSpec,
        vectorJson, vectorFromJson);
    OptionEntry& where =
        b.entry({"--vector-where", "SQL", "", "",
                 "OGR SQL filter of the vector layers' features, e.g. \"type = 'river'\""},
                1);
    where.fromWords = [](Scene& s, Words w) {
        for (VectorDesc& v : s.layers.vectors) v.where = w[0];
    };
    OptionEntry& field =
        b.entry({"--label-field", "NAME", "", "", "The field that labels each vector feature"}, 1);
    field.fromWords = [](Scene& s, Words w) {
        for (VectorDesc& v : s.layers.vectors)
            if (v.labelField.empty()) v.labelField = w[0];
    };
    Builder f(out, kFurnitureOptions, "Labels and map furniture (docs/layers.md)");
    list<LabelDesc>(
        f,
        {"--label", "TEXT@X,Z|TEXT@LON,LAT", "layers.labels", "array of objects",
         "A label at world x, z, or at a longitude and latitude with hemisphere "
         "letters (Summit@15.25E,45.1N); repeat for more",
         "labels: `text`, `x` and `z` (world units, or longitude and latitude in "
         "degrees when `geographic`)"},
        [](Scene& s) -> std::vector<LabelDesc>& { return s.layers.labels; }, parseLabelSpec,
        labelJson, labelFromJson);
    f.flag(
        {"--scale-bar", "", "layers.scale_bar", "boolean",
         "A scale bar (exact in orthographic frames; at the target's distance in perspective)"},
        [](Scene& s) -> bool& { return s.layers.furniture.scaleBar; }, true);
    f.flag(
        {"--north-arrow", "", "layers.north_arrow", "boolean", "A north arrow"},
        [](Scene& s) -> bool& { return s.layers.furniture.northArrow; }, true);
    f.string(
        {"--title", "TEXT", "layers.title", "string", "A title (top left unless --title-corner)"},
        [](Scene& s) -> std::string& { return s.layers.furniture.title; });
    f.flag(
        {"--legend", "", "layers.legend", "boolean",
         "A legend of the colour ramp, the .cpt or the zone palette"},
        [](Scene& s) -> bool& { return s.layers.furniture.legend; }, true);
    f.number({"--text-size", "PX", "layers.text_pixels", "number 6..128",
              "Label and map furniture text height, pixels"},
             [](Scene& s) -> float& { return s.layers.furniture.textPixels; });
    const Text corners[] = {
        {"--title-corner", "CORNER", "layers.title_corner", kCornerNames,
         "The title's corner: top-left (default), top-right, bottom-left or bottom-right"},
        {"--scale-bar-corner", "CORNER", "layers.scale_bar_corner", kCornerNames,
         "The scale bar's corner (default bottom-left)"},
        {"--north-arrow-corner", "CORNER", "layers.north_arrow_corner", kCornerNames,
         "The north arrow's corner (default top-right)"},
        {"--legend-corner", "CORNER", "layers.legend_corner", kCornerNames,
         "The legend's corner (default bottom-right)"},
    };
    f.choice<FrameCorner>(
        corners[0], [](Scene& s) -> FrameCorner& { return s.layers.furniture.titleCorner; },
        parseFrameCorner, toString);
    f.choice<FrameCorner>(
        corners[1], [](Scene& s) -> FrameCorner& { return s.layers.furniture.scaleBarCorner; },
        parseFrameCorner, toString);
    f.choice<FrameCorner>(
        corners[2], [](Scene& s) -> FrameCorner& { return s.layers.furniture.northArrowCorner; },
        parseFrameCorner, toString);
    f.choice<FrameCorner>(
        corners[3], [](Scene& s) -> FrameCorner& { return s.layers.furniture.legendCorner; },
        parseFrameCorner, toString);
}

}  // namespace sierra::scene::detail
