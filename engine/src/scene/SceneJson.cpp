#include <sierra/scene/SceneJson.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/scene/StyleJson.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string_view>
#include <vector>

namespace sierra::scene {
namespace {

// ---- writing --------------------------------------------------------------

// The shortest decimal (at most 9 significant digits, which always suffice)
// whose double, narrowed to float, is `f` again: reading goes text -> double
// -> float, and the double's shortest form is what the JSON writer prints.
Json number(float f) {
    if (!std::isfinite(f)) return nullptr;  // validateScene rejects these before any save
    for (int digits = 1; digits <= 9; ++digits) {
        char text[32];
        std::snprintf(text, sizeof text, "%.*g", digits, double(f));
        double d = std::strtod(text, nullptr);
        if (float(d) == f) return d;
    }
    return double(f);
}

Json vec3(const Vec3& v) {
    return Json::array({number(v.x), number(v.y), number(v.z)});
}

template <typename T, typename F>
Json optional(const std::optional<T>& value, F write) {
    return value ? write(*value) : Json(nullptr);
}

// ---- reading --------------------------------------------------------------

// A JsonObject with the scene's one compound value type.
class ObjectReader : public JsonObject {
  public:
    using JsonObject::JsonObject;

    Vec3 toVec3(const Json& v, const std::string& key) const {
        if (!v.is_array() || v.size() != 3) wrongType(v, key, "an array of 3 numbers [x, y, z]");
        return {toFloat(v[0], key + "[0]"), toFloat(v[1], key + "[1]"), toFloat(v[2], key + "[2]")};
    }
};

template <typename T, typename F>
void readOptional(const Json& v, std::optional<T>& out, F read) {
    if (v.is_null())
        out.reset();
    else
        out = read(v);
}

// Reads a sub-object if present: fn(ObjectReader&), then rejects unknown keys.
template <typename F>
void object(ObjectReader& parent, const char* key, F fn) {
    parent.field(key, [&](const Json& v, const std::string& path) {
        ObjectReader r(v, path, parent.source());
        fn(r);
        r.finish();
    });
}

void readTerrain(ObjectReader& r, TerrainSource& t) {
    r.field("heightmap",
            [&](const Json& v, const std::string& k) { t.heightmap = r.toString(v, k); });
    r.field("generate",
            [&](const Json& v, const std::string& k) { t.generateSize = r.toInt(v, k); });
    r.field("seed", [&](const Json& v, const std::string& k) { t.seed = r.toUnsigned(v, k); });
    r.field("roughness",
            [&](const Json& v, const std::string& k) { t.roughness = r.toFloat(v, k); });
    r.field("hurst", [&](const Json& v, const std::string& k) {
        readOptional(v, t.hurst,
                     [&](const Json& x) { return r.toFloat(x, k, "a number or null"); });
    });
    r.field("raw_width", [&](const Json& v, const std::string& k) { t.rawWidth = r.toInt(v, k); });
    r.field("raw_height",
            [&](const Json& v, const std::string& k) { t.rawHeight = r.toInt(v, k); });
    r.field("spacing", [&](const Json& v, const std::string& k) { t.spacing = r.toFloat(v, k); });
    r.field("vertical_scale",
            [&](const Json& v, const std::string& k) { t.verticalScale = r.toFloat(v, k); });
    r.field("sea_level", [&](const Json& v, const std::string& k) {
        if (v.is_string()) {
            std::string s = v.get<std::string>();
            if (s == "auto")
                t.seaLevel = {};
            else if (s == "none")
                t.seaLevel = {.mode = SeaLevel::Mode::None};
            else
                r.badValue(k, msg("'", s, "' is not one of auto, none (or a height)"));
        } else {
            t.seaLevel = {.mode = SeaLevel::Mode::Value,
                          .value = r.toFloat(v, k, "a height (number), \"auto\" or \"none\"")};
        }
    });
    r.field("height_units", [&](const Json& v, const std::string& k) {
        t.heightUnits = parseHeightUnits(r.toString(v, k), msg(r.source(), ": ", k));
    });
    r.field("channel", [&](const Json& v, const std::string& k) {
        t.channel =
            v.is_null() ? Channel::Grey : parseChannel(r.toString(v, k), msg(r.source(), ": ", k));
    });
}

void readCamera(ObjectReader& r, CameraDesc& c) {
    auto vec = [&](std::optional<Vec3>& out) {
        return [&](const Json& v, const std::string& k) {
            readOptional(v, out, [&](const Json& x) { return r.toVec3(x, k); });
        };
    };
    auto num = [&](std::optional<float>& out) {
        return [&](const Json& v, const std::string& k) {
            readOptional(v, out,
                         [&](const Json& x) { return r.toFloat(x, k, "a number or null"); });
        };
    };
    r.field("position", vec(c.position));
    r.field("target", vec(c.target));
    r.field("azimuth", num(c.azimuth));
    r.field("elevation", num(c.elevation));
    r.field("distance", num(c.distance));
    r.field("fov", [&](const Json& v, const std::string& k) { c.fov = r.toFloat(v, k); });
    r.field("projection", [&](const Json& v, const std::string& k) {
        c.projection = parseProjection(r.toString(v, k), msg(r.source(), ": ", k));
    });
}

void readPath(ObjectReader& r, PathDesc& p) {
    r.field("type", [&](const Json& v, const std::string& k) {
        p.type = parsePathType(r.toString(v, k), msg(r.source(), ": ", k));
    });
    r.field("frames", [&](const Json& v, const std::string& k) { p.frames = r.toInt(v, k); });
    r.field("range", [&](const Json& v, const std::string& k) {
        readOptional(v, p.range, [&](const Json& x) {
            if (!x.is_array() || x.size() != 2) r.wrongType(x, k, "an array [first, last] or null");
            return FrameRange{r.toInt(x[0], k + "[0]"), r.toInt(x[1], k + "[1]")};
        });
    });
    r.field("keyframes", [&](const Json& v, const std::string& k) {
        if (!v.is_array()) r.wrongType(v, k, "an array of {time, position, target} objects");
        p.keyframes.clear();
        for (size_t i = 0; i < v.size(); ++i) {
            ObjectReader f(v[i], msg(k, "[", i, "]"), r.source());
            Keyframe key;
            f.field("time",
                    [&](const Json& x, const std::string& kk) { key.time = f.toFloat(x, kk); });
            f.field("position",
                    [&](const Json& x, const std::string& kk) { key.position = f.toVec3(x, kk); });
            f.field("target",
                    [&](const Json& x, const std::string& kk) { key.target = f.toVec3(x, kk); });
            f.finish();
            p.keyframes.push_back(key);
        }
    });
}

void readLighting(ObjectReader& r, LightingDesc& l) {
    r.field("sun_azimuth",
            [&](const Json& v, const std::string& k) { l.sunAzimuth = r.toFloat(v, k); });
    r.field("sun_altitude",
            [&](const Json& v, const std::string& k) { l.sunAltitude = r.toFloat(v, k); });
    r.field("ambient", [&](const Json& v, const std::string& k) { l.ambient = r.toFloat(v, k); });
    r.field("fog", [&](const Json& v, const std::string& k) {
        readOptional(v, l.fog, [&](const Json& x) {
            return r.toFloat(x, k, "a number or null (automatic)");
        });
    });
    r.field("sky", [&](const Json& v, const std::string& k) {
        if (!v.is_array() || v.size() != 3) r.wrongType(v, k, "an array of 3 numbers [r, g, b]");
        l.sky = {r.toFloat(v[0], k + "[0]"), r.toFloat(v[1], k + "[1]"),
                 r.toFloat(v[2], k + "[2]")};
    });
    r.field("shadows", [&](const Json& v, const std::string& k) { l.shadows = r.toBool(v, k); });
    r.field("sky_light", [&](const Json& v, const std::string& k) { l.skyLight = r.toBool(v, k); });
    r.field("sun_size", [&](const Json& v, const std::string& k) { l.sunSize = r.toFloat(v, k); });
    r.field("horizon_radius",
            [&](const Json& v, const std::string& k) { l.horizonRadius = r.toFloat(v, k); });
    r.field("sun_time", [&](const Json& v, const std::string& k) {
        readOptional(v, l.sunTime, [&](const Json& x) {
            return r.toString(x, k);  // checked by validateScene
        });
    });
    auto degrees = [&](std::optional<float>& out) {
        return [&](const Json& v, const std::string& k) {
            readOptional(v, out, [&](const Json& x) {
                return r.toFloat(x, k, "degrees or null (the DEM's centre)");
            });
        };
    };
    r.field("latitude", degrees(l.latitude));
    r.field("longitude", degrees(l.longitude));
    r.field("sun_step", [&](const Json& v, const std::string& k) { l.sunStep = r.toFloat(v, k); });
}

void readLod(ObjectReader& r, LodDesc& l) {
    r.field("mode", [&](const Json& v, const std::string& k) {
        l.mode = parseLodMode(r.toString(v, k), msg(r.source(), ": ", k));
    });
    r.field("tau", [&](const Json& v, const std::string& k) { l.tau = r.toFloat(v, k); });
    r.field("geomorph", [&](const Json& v, const std::string& k) { l.geomorph = r.toBool(v, k); });
    r.field("cull", [&](const Json& v, const std::string& k) { l.cull = r.toBool(v, k); });
    r.field("threads", [&](const Json& v, const std::string& k) { l.threads = r.toInt(v, k); });
    r.field("mesh", [&](const Json& v, const std::string& k) { l.mesh = r.toString(v, k); });
}

void readOutput(ObjectReader& r, OutputDesc& o) {
    r.field("width", [&](const Json& v, const std::string& k) { o.width = r.toInt(v, k); });
    r.field("height", [&](const Json& v, const std::string& k) { o.height = r.toInt(v, k); });
    r.field("msaa", [&](const Json& v, const std::string& k) { o.msaa = r.toInt(v, k); });
    r.field("frame", [&](const Json& v, const std::string& k) { o.frame = r.toString(v, k); });
    r.field("debug", [&](const Json& v, const std::string& k) { o.debug = r.toString(v, k); });
    r.field("snapshot_only",
            [&](const Json& v, const std::string& k) { o.snapshotOnly = r.toString(v, k); });
    r.field("snapshot_every",
            [&](const Json& v, const std::string& k) { o.snapshotEvery = r.toInt(v, k); });
    r.field("snapshot_deterministic",
            [&](const Json& v, const std::string& k) { o.snapshotDeterministic = r.toBool(v, k); });
    r.field("depth", [&](const Json& v, const std::string& k) { o.depth = r.toString(v, k); });
    r.field("alpha", [&](const Json& v, const std::string& k) { o.alpha = r.toBool(v, k); });
    r.field("fps", [&](const Json& v, const std::string& k) { o.fps = r.toInt(v, k); });
    r.field("video_codec",
            [&](const Json& v, const std::string& k) { o.videoCodec = r.toString(v, k); });
    r.field("crf", [&](const Json& v, const std::string& k) { o.crf = r.toInt(v, k); });
    r.field("bitrate", [&](const Json& v, const std::string& k) {
        o.bitrate = int64_t(
            std::min<uint64_t>(r.toUnsigned(v, k), uint64_t(std::numeric_limits<int64_t>::max())));
    });
    r.field("video_preset",
            [&](const Json& v, const std::string& k) { o.videoPreset = r.toString(v, k); });
    r.field("png_compression", [&](const Json& v, const std::string& k) {
        o.pngCompression = parsePngCompression(r.toString(v, k), msg(r.source(), ": ", k));
    });
    r.field("jpeg_quality",
            [&](const Json& v, const std::string& k) { o.jpegQuality = r.toInt(v, k); });
    r.field("max_queued_frames",
            [&](const Json& v, const std::string& k) { o.maxQueuedFrames = r.toInt(v, k); });
}

void readStyle(ObjectReader& r, StyleDesc& s) {
    r.field("wireframe",
            [&](const Json& v, const std::string& k) { s.wireframe = r.toBool(v, k); });
    r.field("tree_line",
            [&](const Json& v, const std::string& k) { s.treeLine = r.toFloat(v, k); });
    r.field("snow_line",
            [&](const Json& v, const std::string& k) { s.snowLine = r.toFloat(v, k); });
    r.field("cpt", [&](const Json& v, const std::string& k) { s.cpt = r.toString(v, k); });
    r.field("polygons", [&](const Json& v, const std::string& k) { s.polygons = r.toBool(v, k); });
    r.field("points", [&](const Json& v, const std::string& k) { s.points = r.toBool(v, k); });
    r.field("colour_by",
            [&](const Json& v, const std::string& k) { s.colourBy = r.toString(v, k); });
    // Overlays: a preset first, then the analysis module's style keys over it.
    bool preset = false;
    r.field("preset", [&](const Json& v, const std::string& k) {
        s.preset = r.toString(v, k);
        preset = true;
    });
    Json keys = Json::object();
    for (const char* key : {"description", "styles", "curvature", "lines", "hatch", "contours"})
        r.field(key, [&, key](const Json& v, const std::string&) { keys[key] = v; });
    if (preset) s.overlay = loadPreset(s.preset);
    if (!keys.empty()) {
        Json merged = preset ? styleToJson(s.overlay) : Json::object();
        merged.merge_patch(keys);
        s.overlay = styleFromJson(merged, r.source());
    }
}

void readZones(ObjectReader& r, ZonesDesc& z) {
    r.field("map", [&](const Json& v, const std::string& k) { z.map = r.toString(v, k); });
    r.field("palette", [&](const Json& v, const std::string& k) { z.palette = r.toString(v, k); });
    r.field("band", [&](const Json& v, const std::string& k) { z.band = r.toFloat(v, k); });
    r.field("epsilon", [&](const Json& v, const std::string& k) { z.epsilon = r.toFloat(v, k); });
    r.field("blend", [&](const Json& v, const std::string& k) { z.blend = r.toString(v, k); });
    r.field("triplanar",
            [&](const Json& v, const std::string& k) { z.triplanar = r.toBool(v, k); });
    r.field("variation",
            [&](const Json& v, const std::string& k) { z.variation = r.toBool(v, k); });
    r.field("debug_view",
            [&](const Json& v, const std::string& k) { z.debugView = r.toString(v, k); });
    r.field("deep_water",
            [&](const Json& v, const std::string& k) { z.deepWater = r.toFloat(v, k); });
    r.field("sand_top", [&](const Json& v, const std::string& k) { z.sandTop = r.toFloat(v, k); });
    r.field("snow_line",
            [&](const Json& v, const std::string& k) { z.snowLine = r.toFloat(v, k); });
    r.field("rock_slope",
            [&](const Json& v, const std::string& k) { z.rockSlope = r.toFloat(v, k); });
}

}  // namespace

Scene sceneFromJson(const Json& json, const std::string& source, const Scene& base) {
    Scene scene = base;
    ObjectReader top(json, "", source);
    object(top, "terrain", [&](ObjectReader& r) { readTerrain(r, scene.terrain); });
    object(top, "camera", [&](ObjectReader& r) { readCamera(r, scene.camera); });
    object(top, "path", [&](ObjectReader& r) { readPath(r, scene.path); });
    object(top, "lighting", [&](ObjectReader& r) { readLighting(r, scene.lighting); });
    object(top, "lod", [&](ObjectReader& r) { readLod(r, scene.lod); });
    object(top, "output", [&](ObjectReader& r) { readOutput(r, scene.output); });
    object(top, "style", [&](ObjectReader& r) { readStyle(r, scene.style); });
    object(top, "zones", [&](ObjectReader& r) { readZones(r, scene.zones); });
    top.finish();
    return scene;
}

Scene loadScene(const std::string& path, const Scene& base) {
    Scene scene = sceneFromJson(readJsonFile(path), path, base);
    try {
        validateScene(scene);
    } catch (const Error& e) {
        throw Error(msg(path, ": ", e.what()));
    }
    return scene;
}

Json sceneToJson(const Scene& s) {
    const TerrainSource& t = s.terrain;
    Json seaLevel = t.seaLevel.mode == SeaLevel::Mode::Value ? number(t.seaLevel.value)
                                                             : Json(toString(t.seaLevel.mode));
    Json terrain = {
        {"heightmap", t.heightmap},
        {"generate", t.generateSize},
        {"seed", t.seed},
        {"roughness", number(t.roughness)},
        {"hurst", optional(t.hurst, number)},
        {"raw_width", t.rawWidth},
        {"raw_height", t.rawHeight},
        {"spacing", number(t.spacing)},
        {"vertical_scale", number(t.verticalScale)},
        {"sea_level", seaLevel},
        {"height_units", toString(t.heightUnits)},
        {"channel", toString(t.channel)},
    };
    const CameraDesc& c = s.camera;
    Json camera = {
        {"position", optional(c.position, vec3)},   {"target", optional(c.target, vec3)},
        {"azimuth", optional(c.azimuth, number)},   {"elevation", optional(c.elevation, number)},
        {"distance", optional(c.distance, number)}, {"fov", number(c.fov)},
        {"projection", toString(c.projection)},
    };
    const PathDesc& p = s.path;
    Json keyframes = Json::array();
    for (const Keyframe& k : p.keyframes)
        keyframes.push_back(
            {{"time", number(k.time)}, {"position", vec3(k.position)}, {"target", vec3(k.target)}});
    Json path = {
        {"type", toString(p.type)},
        {"frames", p.frames},
        {"range", optional(p.range,
                           [](const FrameRange& r) {
                               return Json::array({r.first, r.last});
                           })},
        {"keyframes", keyframes},
    };
    const LightingDesc& l = s.lighting;
    Json lighting = {
        {"sun_azimuth", number(l.sunAzimuth)},
        {"sun_altitude", number(l.sunAltitude)},
        {"ambient", number(l.ambient)},
        {"fog", optional(l.fog, number)},
        {"sky", Json::array({number(l.sky.r), number(l.sky.g), number(l.sky.b)})},
        {"shadows", l.shadows},
        {"sky_light", l.skyLight},
        {"sun_size", number(l.sunSize)},
        {"horizon_radius", number(l.horizonRadius)},
        {"sun_time", l.sunTime ? Json(*l.sunTime) : Json(nullptr)},
        {"latitude", optional(l.latitude, number)},
        {"longitude", optional(l.longitude, number)},
        {"sun_step", number(l.sunStep)},
    };
    Json lod = {
        {"mode", toString(s.lod.mode)}, {"tau", number(s.lod.tau)}, {"geomorph", s.lod.geomorph},
        {"cull", s.lod.cull},           {"threads", s.lod.threads}, {"mesh", s.lod.mesh},
    };
    const OutputDesc& o = s.output;
    Json output = {
        {"width", o.width},
        {"height", o.height},
        {"msaa", o.msaa},
        {"frame", o.frame},
        {"debug", o.debug},
        {"depth", o.depth},
        {"alpha", o.alpha},
        {"png_compression", toString(o.pngCompression)},
        {"jpeg_quality", o.jpegQuality},
        {"max_queued_frames", o.maxQueuedFrames},
        {"snapshot_only", o.snapshotOnly},
        {"snapshot_every", o.snapshotEvery},
        {"snapshot_deterministic", o.snapshotDeterministic},
        {"fps", o.fps},
        {"video_codec", o.videoCodec},
        {"crf", o.crf},
        {"bitrate", o.bitrate},
        {"video_preset", o.videoPreset},
    };
    Json style = {{"wireframe", s.style.wireframe},        {"tree_line", number(s.style.treeLine)},
                  {"snow_line", number(s.style.snowLine)}, {"cpt", s.style.cpt},
                  {"polygons", s.style.polygons},          {"points", s.style.points},
                  {"colour_by", s.style.colourBy}};
    const ZonesDesc& z = s.zones;
    Json zones = {{"map", z.map},
                  {"palette", z.palette},
                  {"band", number(z.band)},
                  {"epsilon", number(z.epsilon)},
                  {"blend", z.blend},
                  {"triplanar", z.triplanar},
                  {"variation", z.variation},
                  {"debug_view", z.debugView},
                  {"deep_water", number(z.deepWater)},
                  {"sand_top", number(z.sandTop)},
                  {"snow_line", number(z.snowLine)},
                  {"rock_slope", number(z.rockSlope)}};
    if (!s.style.preset.empty()) style["preset"] = s.style.preset;
    style.update(styleToJson(s.style.overlay));
    return {{"terrain", terrain}, {"camera", camera}, {"path", path},   {"lighting", lighting},
            {"lod", lod},         {"output", output}, {"style", style}, {"zones", zones}};
}

std::string sceneToText(const Scene& scene) {
    return sceneToJson(scene).dump(2) + "\n";
}

void saveScene(const std::string& path, const Scene& scene) {
    writeFileAtomic(path, sceneToText(scene));
}

}  // namespace sierra::scene
