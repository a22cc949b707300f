#include <sierra/scene/StyleJson.h>

#include <sierra/core/Error.h>

#include <cmath>

namespace sierra::scene {

using analysis::CurvatureOptions;
using analysis::HatchStyle;
using analysis::LineStyle;
using analysis::StyleLayers;
using analysis::StyleParams;

namespace {

// A JsonObject with the style's range checks: fail() gives
// "SOURCE: KEY: WHAT", values absent from the object keep `fallback`.
class StyleObject : public JsonObject {
  public:
    using JsonObject::JsonObject;

    [[noreturn]] void fail(const char* name, const std::string& what) const {
        badValue(keyPath(name), what);
    }
    float number(const char* name, float fallback) {
        const Json* v = allow(name);
        return v ? toFloat(*v, keyPath(name)) : fallback;
    }
    int integer(const char* name, int fallback, const char* rule) {
        const Json* v = allow(name);
        return v ? toInt(*v, keyPath(name), rule) : fallback;
    }
    bool boolean(const char* name, bool fallback) {
        const Json* v = allow(name);
        return v ? toBool(*v, keyPath(name)) : fallback;
    }
    std::string string(const char* name, const std::string& fallback) {
        const Json* v = allow(name);
        return v ? toString(*v, keyPath(name)) : fallback;
    }
    // A named choice parsed by `parse` (which throws sierra::Error naming the choices).
    template <typename T, typename Parse>
    T choice(const char* name, T fallback, Parse parse) {
        if (!has(name)) return fallback;
        std::string s = string(name, "");
        try {
            return parse(s);
        } catch (const Error& e) {
            fail(name, e.what());
        }
    }
    // Reads sub-object `name` when present with read(StyleObject&), then
    // refuses its unknown keys.
    template <typename F>
    bool child(const char* name, F read) {
        const Json* v = allow(name);
        if (!v) return false;
        StyleObject c(*v, keyPath(name), source());
        read(c);
        c.finish();
        return true;
    }
};

void readCurvature(StyleObject& c, StyleParams& out) {
    CurvatureOptions& o = out.curvature;
    o.method = c.choice("method", o.method, analysis::parseCurvatureMethod);
    const char* distanceRule = "an integer >= 1 (1 = no reinforcement)";
    o.distance = c.integer("distance", o.distance, distanceRule);
    if (o.distance < 1) c.fail("distance", msg("must be ", distanceRule, ", got ", o.distance));
    if (o.method == analysis::CurvatureMethod::TwoNormal && o.distance != 1)
        c.fail("distance",
               msg("must be 1 for two-normal (it has no reinforcement), got ", o.distance));
    if (const Json* scale = c.allow("scale"); scale && scale->is_string()) {
        if (*scale != "auto")
            c.fail("scale", msg("must be a number >= 0 or \"auto\", got ", scale->dump()));
        out.autoScale = true;
    } else if (scale) {
        o.scale = c.toFloat(*scale, c.keyPath("scale"), "a number >= 0 or \"auto\"");
        if (o.scale < 0.0f) c.fail("scale", msg("must be >= 0, got ", o.scale));
    }
    o.normals = c.choice("normals", o.normals, analysis::parseNormalMethod);
    o.signedValues = c.boolean("signed", o.signedValues);
    c.child("levels", [&](StyleObject& l) {
        o.levels.enabled = true;
        o.levels.black = l.number("black", o.levels.black);
        o.levels.white = l.number("white", o.levels.white);
        o.levels.gamma = l.number("gamma", o.levels.gamma);
        if (o.levels.black < 0.0f) l.fail("black", msg("must be >= 0, got ", o.levels.black));
        if (!(o.levels.white > o.levels.black))
            l.fail("white",
                   msg("must be above the black point ", o.levels.black, ", got ", o.levels.white));
        if (!(o.levels.gamma > 0.0f)) l.fail("gamma", msg("must be > 0, got ", o.levels.gamma));
        if (out.autoScale)
            c.fail("scale",
                   "is \"auto\", which picks the scale from the values, but \"levels\" is "
                   "set: with level control give the scale as a number");
    });
    try {
        validate(o);
    } catch (const Error& e) {
        c.badValue(c.path(), e.what());
    }
}

void readLines(StyleObject& l, LineStyle& s) {
    s.minLength = l.integer("min_length", s.minLength, "an integer >= 2 (vertices)");
    if (s.minLength < 2)
        l.fail("min_length", msg("must be an integer >= 2 (vertices), got ", s.minLength));
    s.width = l.number("width", s.width);
    if (!(s.width > 0.0f)) l.fail("width", msg("must be > 0 (pixels), got ", s.width));
    s.threshold = l.number("threshold", s.threshold);
    if (s.threshold < 0.0f) l.fail("threshold", msg("must be >= 0, got ", s.threshold));
    s.polarity = l.choice("polarity", s.polarity, analysis::parseLinePolarity);
    s.blended = l.boolean("blended", s.blended);
}

void readHatch(StyleObject& h, HatchStyle& s) {
    s.length = h.number("length", s.length);
    if (!(s.length > 0.0f)) h.fail("length", msg("must be > 0 (grid units), got ", s.length));
    s.width = h.number("width", s.width);
    if (!(s.width > 0.0f)) h.fail("width", msg("must be > 0 (pixels), got ", s.width));
    s.direction = h.choice("direction", s.direction, analysis::parseHatchDirection);
}

}  // namespace

StyleParams styleFromJson(const Json& style, const std::string& source) {
    StyleParams out;
    StyleObject r(style, "style", source);
    out.description = r.string("description", "");
    r.child("curvature", [&](StyleObject& c) { readCurvature(c, out); });
    const bool lines = r.child("lines", [&](StyleObject& l) { readLines(l, out.lines); });
    const bool hatch = r.child("hatch", [&](StyleObject& h) { readHatch(h, out.hatch); });

    StyleLayers& layers = out.layers;
    if (const Json* list = r.allow("styles")) {
        if (!list->is_array()) r.wrongType(*list, r.keyPath("styles"), "an array of names");
        layers = {.shaded = false};
        for (const Json& item : *list) {
            if (!item.is_string() || !layers.enable(item.get<std::string>()))
                r.fail("styles", msg("has an unknown style ", item.dump(), " (expected ",
                                     analysis::kStyleLayerNames, ")"));
        }
    } else {
        layers.lines = lines;
        layers.hatch = hatch;
    }
    if (r.has("contours")) {
        bool contours = r.boolean("contours", false);
        if (!contours && layers.contours)
            r.fail("contours", "is false but \"styles\" lists contours");
        layers.contours = layers.contours || contours;
    }
    r.allow("contours");
    r.finish();
    return out;
}

StyleParams loadStyleFile(const std::string& path) {
    const Json doc = readJsonFile(path);
    JsonObject top(doc, "", path);
    const Json* style = top.allow("style");
    if (!style) throw Error(msg(path, ": expected a scene-file fragment {\"style\": {...}}"));
    top.finish();
    return styleFromJson(*style, path);
}

Json styleToJson(const StyleParams& s) {
    Json styles = Json::array();
    if (s.layers.shaded) styles.push_back("shaded");
    if (s.layers.lines) styles.push_back("lines");
    if (s.layers.hatch) styles.push_back("hatch");
    Json curvature = {{"method", analysis::curvatureMethodName(s.curvature.method)},
                      {"distance", s.curvature.distance},
                      {"scale", s.autoScale ? Json("auto") : Json(s.curvature.scale)},
                      {"normals", analysis::normalMethodName(s.curvature.normals)},
                      {"signed", s.curvature.signedValues}};
    if (s.curvature.levels.enabled)
        curvature["levels"] = {{"black", s.curvature.levels.black},
                               {"white", s.curvature.levels.white},
                               {"gamma", s.curvature.levels.gamma}};
    return {{"description", s.description},
            {"styles", styles},
            {"curvature", curvature},
            {"lines",
             {{"min_length", s.lines.minLength},
              {"width", s.lines.width},
              {"threshold", s.lines.threshold},
              {"polarity", analysis::linePolarityName(s.lines.polarity)},
              {"blended", s.lines.blended}}},
            {"hatch",
             {{"length", s.hatch.length},
              {"width", s.hatch.width},
              {"direction", analysis::hatchDirectionName(s.hatch.direction)}}},
            {"contours", s.layers.contours}};
}

}  // namespace sierra::scene
