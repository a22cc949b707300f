#include <sierra/analysis/Style.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <initializer_list>
#include <set>

namespace sierra::analysis {

bool StyleLayers::enable(std::string_view name) {
    if (name == "shaded")
        shaded = true;
    else if (name == "lines")
        lines = true;
    else if (name == "hatch")
        hatch = true;
    else if (name == "contours")
        contours = true;
    else
        return false;
    return true;
}

using nlohmann::json;

namespace {

// Reads one object, checking types and rejecting unknown keys; every message
// starts with "<source>: <path>".
class Reader {
  public:
    Reader(const json& object, std::string source, std::string path)
        : j_(object), source_(std::move(source)), path_(std::move(path)) {
        if (!j_.is_object()) fail(path_, msg("must be an object, got ", typeName(j_)));
    }

    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw Error(msg(source_, ": ", where, " ", what));
    }

    std::string key(const char* name) const { return path_ + "." + name; }
    bool has(const char* name) const { return j_.contains(name); }

    void allowOnly(std::initializer_list<const char*> names) const {
        std::set<std::string> known(names.begin(), names.end());
        for (auto it = j_.begin(); it != j_.end(); ++it)
            if (!known.count(it.key())) {
                std::string list;
                for (const char* n : names) list += (list.empty() ? "" : ", ") + std::string(n);
                fail(path_, msg("has an unknown key '", it.key(), "' (known: ", list, ")"));
            }
    }

    Reader child(const char* name) const { return Reader(j_.at(name), source_, key(name)); }

    double number(const char* name, double fallback) const {
        if (!has(name)) return fallback;
        const json& v = j_.at(name);
        if (!v.is_number()) fail(key(name), msg("must be a number, got ", typeName(v)));
        double d = v.get<double>();
        if (!std::isfinite(d)) fail(key(name), "must be finite");
        return d;
    }

    int integer(const char* name, int fallback, const char* rule) const {
        if (!has(name)) return fallback;
        const json& v = j_.at(name);
        if (!v.is_number()) fail(key(name), msg("must be ", rule, ", got ", typeName(v)));
        double d = v.get<double>();
        if (d != std::floor(d) || std::fabs(d) > 1e9)
            fail(key(name), msg("must be ", rule, ", got ", v.dump()));
        return int(d);
    }

    bool boolean(const char* name, bool fallback) const {
        if (!has(name)) return fallback;
        const json& v = j_.at(name);
        if (!v.is_boolean()) fail(key(name), msg("must be true or false, got ", typeName(v)));
        return v.get<bool>();
    }

    std::string string(const char* name, const std::string& fallback) const {
        if (!has(name)) return fallback;
        const json& v = j_.at(name);
        if (!v.is_string()) fail(key(name), msg("must be a string, got ", typeName(v)));
        return v.get<std::string>();
    }

    // A named choice parsed by `parse` (which throws sierra::Error naming the choices).
    template <typename T, typename Parse>
    T choice(const char* name, T fallback, Parse parse) const {
        if (!has(name)) return fallback;
        std::string s = string(name, "");
        try {
            return parse(s);
        } catch (const Error& e) {
            fail(key(name), e.what());
        }
    }

    const json& raw(const char* name) const { return j_.at(name); }

    static std::string typeName(const json& v) {
        if (v.is_null()) return "null";
        if (v.is_string()) return "a string (" + v.dump() + ")";
        return std::string(v.type_name()) + " " + v.dump();
    }

  private:
    const json& j_;
    std::string source_;
    std::string path_;
};

}  // namespace

LineOptions lineOptions(const StyleParams& style) {
    return {.threshold = style.lines.threshold,
            .minVertices = style.lines.minLength,
            .polarity = style.lines.polarity,
            .blended = style.lines.blended};
}

float autoCurvatureTarget(const StyleParams& style) {
    return style.layers.lines ? style.lines.threshold : 1.0f;
}

float autoCurvatureScale(const CurvatureField& field, const StyleParams& style) {
    std::vector<float> largest = largestMagnitudes(field);
    return scaleToReach(topFivePercent(largest), style.curvature.scale, autoCurvatureTarget(style));
}

StyleParams styleFromJson(const json& style, const std::string& source) {
    StyleParams out;
    Reader r(style, source, "style");
    r.allowOnly({"description", "styles", "curvature", "lines", "hatch", "contours"});
    out.description = r.string("description", "");

    if (r.has("curvature")) {
        Reader c = r.child("curvature");
        c.allowOnly({"method", "distance", "scale", "normals", "signed", "levels"});
        CurvatureOptions& o = out.curvature;
        o.method = c.choice("method", o.method, parseCurvatureMethod);
        o.distance = c.integer("distance", o.distance, "an integer >= 1 (1 = no reinforcement)");
        if (o.distance < 1)
            c.fail(c.key("distance"),
                   msg("must be an integer >= 1 (1 = no reinforcement), got ", o.distance));
        if (o.method == CurvatureMethod::TwoNormal && o.distance != 1)
            c.fail(c.key("distance"),
                   msg("must be 1 for two-normal (it has no reinforcement), got ", o.distance));
        if (c.has("scale") && !c.raw("scale").is_number()) {
            if (c.raw("scale") != "auto")
                c.fail(c.key("scale"),
                       msg("must be a number >= 0 or \"auto\", got ", c.raw("scale").dump()));
            out.autoScale = true;
        } else {
            o.scale = float(c.number("scale", o.scale));
            if (o.scale < 0.0f) c.fail(c.key("scale"), msg("must be >= 0, got ", o.scale));
        }
        o.normals = c.choice("normals", o.normals, parseNormalMethod);
        o.signedValues = c.boolean("signed", o.signedValues);
        if (c.has("levels")) {
            Reader l = c.child("levels");
            l.allowOnly({"black", "white", "gamma"});
            o.levels.enabled = true;
            o.levels.black = float(l.number("black", o.levels.black));
            o.levels.white = float(l.number("white", o.levels.white));
            o.levels.gamma = float(l.number("gamma", o.levels.gamma));
            if (o.levels.black < 0.0f)
                l.fail(l.key("black"), msg("must be >= 0, got ", o.levels.black));
            if (!(o.levels.white > o.levels.black))
                l.fail(l.key("white"), msg("must be above the black point ", o.levels.black,
                                           ", got ", o.levels.white));
            if (!(o.levels.gamma > 0.0f))
                l.fail(l.key("gamma"), msg("must be > 0, got ", o.levels.gamma));
            if (out.autoScale)
                c.fail(c.key("scale"),
                       "is \"auto\", which picks the scale from the values, but \"levels\" is "
                       "set: with level control give the scale as a number");
        }
        try {
            validate(o);
        } catch (const Error& e) {
            r.fail(r.key("curvature"), e.what());
        }
    }

    if (r.has("lines")) {
        Reader l = r.child("lines");
        l.allowOnly({"min_length", "width", "threshold", "polarity", "blended"});
        LineStyle& s = out.lines;
        s.minLength = l.integer("min_length", s.minLength, "an integer >= 2 (vertices)");
        if (s.minLength < 2)
            l.fail(l.key("min_length"),
                   msg("must be an integer >= 2 (vertices), got ", s.minLength));
        s.width = float(l.number("width", s.width));
        if (!(s.width > 0.0f)) l.fail(l.key("width"), msg("must be > 0 (pixels), got ", s.width));
        s.threshold = float(l.number("threshold", s.threshold));
        if (s.threshold < 0.0f) l.fail(l.key("threshold"), msg("must be >= 0, got ", s.threshold));
        s.polarity = l.choice("polarity", s.polarity, parseLinePolarity);
        s.blended = l.boolean("blended", s.blended);
    }

    if (r.has("hatch")) {
        Reader h = r.child("hatch");
        h.allowOnly({"length", "width", "direction"});
        HatchStyle& s = out.hatch;
        s.length = float(h.number("length", s.length));
        if (!(s.length > 0.0f))
            h.fail(h.key("length"), msg("must be > 0 (grid units), got ", s.length));
        s.width = float(h.number("width", s.width));
        if (!(s.width > 0.0f)) h.fail(h.key("width"), msg("must be > 0 (pixels), got ", s.width));
        s.direction = h.choice("direction", s.direction, parseHatchDirection);
    }

    StyleLayers& layers = out.layers;
    if (r.has("styles")) {
        const json& list = r.raw("styles");
        if (!list.is_array())
            r.fail(r.key("styles"), msg("must be an array of names, got ", Reader::typeName(list)));
        layers = {.shaded = false};
        for (const json& item : list) {
            if (!item.is_string() || !layers.enable(item.get<std::string>()))
                r.fail(r.key("styles"), msg("has an unknown style ", item.dump(), " (expected ",
                                            kStyleLayerNames, ")"));
        }
    } else {
        layers.lines = r.has("lines");
        layers.hatch = r.has("hatch");
    }
    if (r.has("contours")) {
        bool contours = r.boolean("contours", false);
        if (!contours && layers.contours)
            r.fail(r.key("contours"), "is false but \"styles\" lists contours");
        layers.contours = layers.contours || contours;
    }
    return out;
}

StyleParams loadStyleFile(const std::string& path) {
    std::vector<uint8_t> bytes = readFileBytes(path);
    json doc;
    try {
        doc = json::parse(bytes.begin(), bytes.end());
    } catch (const json::exception& e) {  // parse errors and numbers out of range
        throw Error(msg(path, ": not valid JSON (", e.what(), ")"));
    }
    if (!doc.is_object() || !doc.contains("style"))
        throw Error(msg(path, ": expected a scene-file fragment {\"style\": {...}}"));
    return styleFromJson(doc.at("style"), path);
}

json styleToJson(const StyleParams& s) {
    json styles = json::array();
    if (s.layers.shaded) styles.push_back("shaded");
    if (s.layers.lines) styles.push_back("lines");
    if (s.layers.hatch) styles.push_back("hatch");
    json curvature = {{"method", curvatureMethodName(s.curvature.method)},
                      {"distance", s.curvature.distance},
                      {"scale", s.autoScale ? json("auto") : json(s.curvature.scale)},
                      {"normals", normalMethodName(s.curvature.normals)},
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
              {"polarity", linePolarityName(s.lines.polarity)},
              {"blended", s.lines.blended}}},
            {"hatch",
             {{"length", s.hatch.length},
              {"width", s.hatch.width},
              {"direction", hatchDirectionName(s.hatch.direction)}}},
            {"contours", s.layers.contours}};
}

}  // namespace sierra::analysis
