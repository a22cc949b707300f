// The scene option table (OptionTable.h): the entries of the terrain, the
// camera and its path, lighting and level of detail (the others are in
// OptionTableOutput.cpp), and the table in command-line order.
#include <sierra/scene/OptionTable.h>

#include "scene/OptionBuilder.h"

#include <sierra/terrain/SunPosition.h>

#include <cstdio>

namespace sierra::scene {

// Numbers are parsed here rather than by CLI11, so every bad value gets the
// same kind of message: the option, the text and what was expected.
float parseFloat(const std::string& text, const std::string& option, const char* expected) {
    char* end = nullptr;
    errno = 0;
    float v = std::strtof(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
        throw Error(msg(option, " '", text, "': expected ", expected));
    return v;
}

Json jsonNumber(float f) {
    if (!std::isfinite(f)) return nullptr;  // validateScene rejects these before any save
    // Reading goes text -> double -> float, and the double's shortest form is
    // what the JSON writer prints.
    for (int digits = 1; digits <= 9; ++digits) {
        char text[32];
        std::snprintf(text, sizeof text, "%.*g", digits, double(f));
        double d = std::strtod(text, nullptr);
        if (float(d) == f) return d;
    }
    return double(f);
}

namespace detail {

namespace {

// --sea-level H|auto|none <-> terrain.sea_level: a height, "auto" or "none".
void addSeaLevel(Builder& b) {
    OptionEntry& sea = b.entry(
        {"--sea-level", "H|auto|none", "terrain.sea_level", "number, `\"auto\"` or `\"none\"`",
         "Water level in stored height units, 'auto' (from the data) or 'none'",
         "water level in stored height units (the file's own numbers); auto = chosen from the "
         "data; none = no water"},
        1);
    sea.shown = [](const Scene& s) {
        const SeaLevel& l = s.terrain.seaLevel;
        return l.mode == SeaLevel::Mode::Value ? msg(l.value) : std::string(toString(l.mode));
    };
    sea.fromWords = [](Scene& s, Words w) {
        if (w[0] == "auto")
            s.terrain.seaLevel = {};
        else if (w[0] == "none")
            s.terrain.seaLevel = {.mode = SeaLevel::Mode::None};
        else
            s.terrain.seaLevel = {
                .mode = SeaLevel::Mode::Value,
                .value = parseFloat(w[0], "--sea-level", "a height, 'auto' or 'none'")};
    };
    sea.toJson = [](const Scene& s) {
        const SeaLevel& l = s.terrain.seaLevel;
        return l.mode == SeaLevel::Mode::Value ? jsonNumber(l.value) : Json(toString(l.mode));
    };
    sea.fromJson = [](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
        if (!v.is_string()) {
            s.terrain.seaLevel = {
                .mode = SeaLevel::Mode::Value,
                .value = r.toFloat(v, k, "a height (number), \"auto\" or \"none\"")};
        } else if (v == "auto") {
            s.terrain.seaLevel = {};
        } else if (v == "none") {
            s.terrain.seaLevel = {.mode = SeaLevel::Mode::None};
        } else {
            r.badValue(k,
                       msg("'", v.get<std::string>(), "' is not one of auto, none (or a height)"));
        }
    };
}

}  // namespace

void terrainEntries(std::vector<OptionEntry>& out) {
    Builder b(out, kTerrainOptions, "Terrain");
    OptionEntry& heightmap = b.string(
        {"--heightmap", "FILE", "terrain.heightmap", "string",
         "Heightmap to load: .png (8/16-bit grey), .pgm, .r16/.r32 (with --raw-size), .hgt, .npy, "
         ".npz (.tif with GDAL)",
         "heightmap file; `\"\"` = generate. Formats: `.png` `.pgm` `.r16` `.r32` `.hgt` `.npy` "
         "`.npz` (`.tif` with GDAL)"},
        [](Scene& s) -> std::string& { return s.terrain.heightmap; });
    heightmap.existingFile = true;
    OptionEntry& generate = b.integer(
        {"--generate", "N", "terrain.generate", "integer",
         "Generate a diamond-square terrain of N x N samples, N = 2^n + 1",
         "samples per side of a generated (diamond-square) terrain, 2^n + 1"},
        [](Scene& s) -> int& { return s.terrain.generateSize; }, "an integer 2^n + 1");
    generate.excludes = {"--heightmap"};
    generate.fromWords = [](Scene& s, Words w) {
        s.terrain.heightmap.clear();
        s.terrain.generateSize = parseInt(w[0], "--generate", "an integer 2^n + 1");
    };
    OptionEntry& seed =
        b.entry({"--seed", "S", "terrain.seed", "integer >= 0", "Seed of the generated terrain",
                 "generator seed (64-bit): same seed, same terrain"},
                1);
    seed.shown = [](const Scene& s) { return msg(s.terrain.seed); };
    seed.fromWords = [](Scene& s, Words w) { s.terrain.seed = parseUnsigned(w[0], "--seed"); };
    seed.toJson = [](const Scene& s) { return Json(s.terrain.seed); };
    seed.fromJson = [](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
        s.terrain.seed = r.toUnsigned(v, k);
    };
    b.number({"--roughness", "R", "terrain.roughness", "number > 0",
              "Amplitude factor of the generator's random offsets (> 0)",
              "amplitude factor of the generator's random offsets"},
             [](Scene& s) -> float& { return s.terrain.roughness; });
    b.optionalNumber(
        {"--hurst", "H", "terrain.hurst", "number or null",
         "Generator's per-level amplitude factor 2^-H (default: the generator's own scaling)",
         "per-level amplitude factor 2^-H of the generator; null = the generator's default "
         "scaling"},
        [](Scene& s) -> std::optional<float>& { return s.terrain.hurst; }, "");
    OptionEntry& raw =
        b.entry({"--raw-size", "WxH", "", "",
                 "Samples per row and rows of a .r16/.r32 heightmap (each 1..65537)"},
                1);
    raw.shown = [](const Scene& s) {
        return s.terrain.rawWidth ? msg(s.terrain.rawWidth, "x", s.terrain.rawHeight)
                                  : std::string();
    };
    raw.fromWords = [](Scene& s, Words w) {
        auto [width, height] = parseRawSize(w[0], "--raw-size");
        s.terrain.rawWidth = width;
        s.terrain.rawHeight = height;
    };
    const char* rawDoc = "size of a raw `.r16`/`.r32` file, each 1..65537; both 0 = guess a square";
    b.integer({"", "", "terrain.raw_width", "integer", "", rawDoc, "--raw-size WxH"},
              [](Scene& s) -> int& { return s.terrain.rawWidth; });
    b.integer({"", "", "terrain.raw_height", "integer", "", rawDoc, "--raw-size WxH"},
              [](Scene& s) -> int& { return s.terrain.rawHeight; });
    b.number(
        {"--spacing", "S", "terrain.spacing", "number >= 0",
         "World units between samples (0 = the file's: 1, or metres for SRTM, GeoTIFF and "
         "georeferenced .npz)",
         "world units between samples; 0 = the file's (1 for images and arrays; metres for SRTM "
         "(at the latitude its name gives), GeoTIFF and `.npz` with geographic coordinates)"},
        [](Scene& s) -> float& { return s.terrain.spacing; });
    b.number({"--vertical-scale", "V", "terrain.vertical_scale", "number >= 0",
              "Stored height to world height (0 = automatic: 1 for metres, else relief 20% of the "
              "extent)",
              "stored height -> world height; 0 = automatic: 1 for metric heights, else the relief "
              "is 20% of the horizontal extent"},
             [](Scene& s) -> float& { return s.terrain.verticalScale; });
    addSeaLevel(b);
    b.choice<HeightUnits>(
        {"--height-units", "auto|m|none", "terrain.height_units", "`\"auto\"`, `\"m\"`, `\"none\"`",
         "What heights measure: auto (metres for SRTM, GeoTIFF and .npz with geographic "
         "coordinates), m (metres) or none",
         "what heights measure: auto = metres for SRTM, GeoTIFF and `.npz` archives with "
         "geographic coordinates, unitless otherwise; `\"metres\"` is read as `\"m\"`"},
        [](Scene& s) -> HeightUnits& { return s.terrain.heightUnits; }, parseHeightUnits, toString);
    OptionEntry& channel = b.choice<Channel>(
        {"--channel", "NAME", "terrain.channel",
         "`\"grey\"`, `\"luminance\"`, `\"r\"`, `\"g\"`, `\"b\"`",
         "Height channel of a colour image: luminance, r, g or b (default: grey images only)",
         "the height channel of a colour image; grey = grey images only"},
        [](Scene& s) -> Channel& { return s.terrain.channel; }, parseChannel, toString);
    channel.shown = [](const Scene& s) {
        return s.terrain.channel == Channel::Grey ? std::string() : toString(s.terrain.channel);
    };
}

void cameraEntries(std::vector<OptionEntry>& out) {
    Builder b(out, kCameraOptions, "Camera");
    auto vec3 = [&](const Text& t, Ref<std::optional<Vec3>> ref) -> OptionEntry& {
        OptionEntry& e = b.entry(t, 3);
        const std::string flag = t.flag;
        e.shown = [ref](const Scene& s) { return show(get(ref, s)); };
        e.fromWords = [ref, flag](Scene& s, Words w) { ref(s) = parseVec3(w, flag); };
        e.toJson = [ref](const Scene& s) {
            return get(ref, s) ? vec3Json(*get(ref, s)) : Json(nullptr);
        };
        e.fromJson = [ref](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
            if (v.is_null())
                ref(s).reset();
            else
                ref(s) = vec3FromJson(r, v, k);
        };
        return e;
    };
    OptionEntry& pos =
        vec3({"--camera-pos", "X Y Z", "camera.position", "[x, y, z] or null",
              "Camera position X Y Z in world units (default: fits the whole terrain)",
              "camera position; null = automatic, fitting the whole terrain in the frame"},
             [](Scene& s) -> std::optional<Vec3>& { return s.camera.position; });
    pos.fromWords = [](Scene& s, Words w) {
        s.camera.position = parseVec3(w, "--camera-pos");
        // Given here, it replaces a scene file's orbit-style camera.
        s.camera.azimuth.reset();
        s.camera.elevation.reset();
        s.camera.distance.reset();
    };
    pos.excludes = {"--azimuth", "--elevation", "--distance"};
    vec3({"--camera-target", "X Y Z", "camera.target", "[x, y, z] or null",
          "Point the camera looks at, X Y Z (default: the terrain's centre)",
          "point looked at; null = the terrain's centre"},
         [](Scene& s) -> std::optional<Vec3>& { return s.camera.target; });
    // The three angles replace a scene file's position, as --camera-pos replaces them.
    auto angle = [&](const Text& t, Ref<std::optional<float>> ref) {
        OptionEntry& e = b.optionalNumber(t, ref);
        const std::string flag = t.flag;
        e.fromWords = [ref, flag](Scene& s, Words w) {
            ref(s) = parseFloat(w[0], flag);
            s.camera.position.reset();
        };
    };
    angle({"--azimuth", "DEG", "camera.azimuth", "number or null",
           "Camera bearing from the target, degrees clockwise from north (-z)",
           "bearing of the camera seen from the target (alternative to `position`)"},
          [](Scene& s) -> std::optional<float>& { return s.camera.azimuth; });
    angle({"--elevation", "DEG", "camera.elevation", "number or null",
           "Camera elevation above the horizon seen from the target, degrees",
           "camera height above the horizon seen from the target, -90..90"},
          [](Scene& s) -> std::optional<float>& { return s.camera.elevation; });
    angle({"--distance", "D", "camera.distance", "number or null",
           "Camera distance from the target, world units",
           "camera distance from the target, world units > 0"},
          [](Scene& s) -> std::optional<float>& { return s.camera.distance; });
    b.number({"--fov", "DEG", "camera.fov", "number", "Vertical field of view in degrees, (0, 180)",
              "vertical field of view, (0, 180) degrees (perspective)"},
             [](Scene& s) -> float& { return s.camera.fov; });
    OptionEntry& ortho = b.choice<Projection>(
        {"--ortho", "", "camera.projection", "`\"perspective\"`, `\"orthographic\"`",
         "Orthographic projection (map-like); tau stays in pixels",
         "orthographic gives map-like renders; tau stays in pixels"},
        [](Scene& s) -> Projection& { return s.camera.projection; }, parseProjection, toString);
    ortho.count = 0;
    ortho.shown = nullptr;
    ortho.fromWords = [](Scene& s, Words) { s.camera.projection = Projection::Orthographic; };
}

void pathEntries(std::vector<OptionEntry>& out) {
    Builder b(out, kPathOptions, "Camera path");
    b.choice<PathType>(
        {"--path", "none|orbit|flyover|keyframes", "path.type",
         "`\"none\"`, `\"orbit\"`, `\"flyover\"`, `\"keyframes\"`",
         "Camera path over the frames: none, orbit, flyover or keyframes (from --config)",
         "how the camera moves over the frames"},
        [](Scene& s) -> PathType& { return s.path.type; }, parsePathType, toString);
    OptionEntry& frames = b.entry(
        {"--frames", "N|A:B", "", "",
         "N frames, or A:B = frames A..B (0-based, inclusive) of the sequence (its count from "
         "--frame-count or --config), same files and bytes as the whole run"},
        1);
    frames.shown = [](const Scene& s) { return msg(s.path.frames); };
    frames.fromWords = [](Scene& s, Words w) {
        const std::string& text = w[0];
        size_t colon = text.find(':');
        if (colon == std::string::npos) {
            s.path.frames = parseInt(text, "--frames", "N (>= 1) or A:B");
            s.path.range.reset();
        } else {
            const char* expected = "A:B, two integers 0 <= A <= B";
            s.path.range = FrameRange{parseInt(text.substr(0, colon), "--frames", expected),
                                      parseInt(text.substr(colon + 1), "--frames", expected)};
        }
    };
    OptionEntry& count =
        b.integer({"--frame-count", "N", "", "", "Frames in the whole sequence, for --frames A:B"},
                  [](Scene& s) -> int& { return s.path.frames; });
    count.shown = nullptr;
    b.integer({"", "", "path.frames", "integer >= 1", "", "frames in the whole sequence",
               "--frames N, --frame-count N"},
              [](Scene& s) -> int& { return s.path.frames; });
    OptionEntry& range = b.entry(
        {"", "", "path.range", "[first, last] or null", "",
         "render only frames first..last (0-based, inclusive) of the sequence: same file names "
         "and bytes as the whole run",
         "--frames A:B"},
        1);
    range.toJson = [](const Scene& s) {
        return s.path.range ? Json::array({s.path.range->first, s.path.range->last})
                            : Json(nullptr);
    };
    range.fromJson = [](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
        if (v.is_null()) {
            s.path.range.reset();
            return;
        }
        if (!v.is_array() || v.size() != 2) r.wrongType(v, k, "an array [first, last] or null");
        s.path.range = FrameRange{r.toInt(v[0], k + "[0]"), r.toInt(v[1], k + "[1]")};
    };
    OptionEntry& keys = b.entry(
        {"", "", "path.keyframes", "array of {`time`, `position`, `target`}", "",
         "camera keys for `\"keyframes\"` (at least 2, times increasing), interpolated smoothly; "
         "frames are spread evenly from the first to the last time"},
        1);
    keys.toJson = [](const Scene& s) {
        Json list = Json::array();
        for (const Keyframe& k : s.path.keyframes)
            list.push_back({{"time", jsonNumber(k.time)},
                            {"position", vec3Json(k.position)},
                            {"target", vec3Json(k.target)}});
        return list;
    };
    keys.fromJson = [](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
        if (!v.is_array()) r.wrongType(v, k, "an array of {time, position, target} objects");
        s.path.keyframes.clear();
        for (size_t i = 0; i < v.size(); ++i) {
            JsonObject f(v[i], msg(k, "[", i, "]"), r.source());
            Keyframe key;
            f.field("time",
                    [&](const Json& x, const std::string& kk) { key.time = f.toFloat(x, kk); });
            f.field("position", [&](const Json& x, const std::string& kk) {
                key.position = vec3FromJson(f, x, kk);
            });
            f.field("target", [&](const Json& x, const std::string& kk) {
                key.target = vec3FromJson(f, x, kk);
            });
            f.finish();
            s.path.keyframes.push_back(key);
        }
    };
}

void lightingEntries(std::vector<OptionEntry>& out) {
    Builder b(out, kLightingOptions, "Lighting");
    // Given here, a fixed sun replaces a scene file's time.
    auto sun = [&](const Text& t, Ref<float> ref) {
        OptionEntry& e = b.number(t, ref);
        const std::string flag = t.flag;
        e.fromWords = [ref, flag](Scene& s, Words w) {
            ref(s) = parseFloat(w[0], flag);
            clearSunTime(s);
        };
    };
    sun({"--sun-azimuth", "DEG", "lighting.sun_azimuth", "number",
         "Sun bearing, degrees clockwise from north (-z)",
         "bearing of the sun (default: south-west)"},
        [](Scene& s) -> float& { return s.lighting.sunAzimuth; });
    sun({"--sun-altitude", "DEG", "lighting.sun_altitude", "number",
         "Sun altitude above the horizon, degrees", "sun height above the horizon, -90..90"},
        [](Scene& s) -> float& { return s.lighting.sunAltitude; });
    b.number({"--ambient", "A", "lighting.ambient", "number",
              "Ambient light, fraction of full light 0..1",
              "ambient light (the sky), fraction of full light, 0..1; scaled by the sky light "
              "where that is on"},
             [](Scene& s) -> float& { return s.lighting.ambient; });
    OptionEntry& fog = b.optionalNumber(
        {"--fog", "D|auto", "lighting.fog", "number >= 0 or null",
         "Fog density per world unit; 0 = off, auto = 0.35 / the terrain's extent",
         "fog density per world unit; null = automatic (aerial perspective over the framed "
         "terrain, below); 0 = off"},
        [](Scene& s) -> std::optional<float>& { return s.lighting.fog; });
    fog.fromWords = [](Scene& s, Words w) {
        if (w[0] == "auto")
            s.lighting.fog.reset();
        else
            s.lighting.fog = parseFloat(w[0], "--fog", "a density >= 0 or 'auto'");
    };
    OptionEntry& sky =
        b.entry({"--sky", "R,G,B", "lighting.sky", "[r, g, b]", "Sky and fog colour, each 0..1",
                 "background and fog colour, each 0..1"},
                1);
    sky.shown = [](const Scene& s) {
        return msg(s.lighting.sky.r, ",", s.lighting.sky.g, ",", s.lighting.sky.b);
    };
    sky.fromWords = [](Scene& s, Words w) { s.lighting.sky = parseRgb(w[0], "--sky"); };
    sky.toJson = [](const Scene& s) {
        const Rgb& c = s.lighting.sky;
        return Json::array({jsonNumber(c.r), jsonNumber(c.g), jsonNumber(c.b)});
    };
    sky.fromJson = [](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
        if (!v.is_array() || v.size() != 3) r.wrongType(v, k, "an array of 3 numbers [r, g, b]");
        s.lighting.sky = {r.toFloat(v[0], k + "[0]"), r.toFloat(v[1], k + "[1]"),
                          r.toFloat(v[2], k + "[2]")};
    };
    b.onOff({"--shadows", "on|off", "lighting.shadows", "boolean",
             "Soft shadows the terrain casts from the sun",
             "soft shadows the terrain casts: the share of the sun's disc each point sees"},
            [](Scene& s) -> bool& { return s.lighting.shadows; });
    b.onOff({"--sky-light", "on|off", "lighting.sky_light", "boolean",
             "Ambient light scaled by the share of the sky each point sees (darker valleys)",
             "the ambient term times the sky light each point receives past its horizons (darker "
             "valleys)"},
            [](Scene& s) -> bool& { return s.lighting.skyLight; });
    b.number({"--sun-size", "DEG", "lighting.sun_size", "number",
              "Angular diameter of the sun, degrees (the penumbra's width), > 0",
              "the sun's angular diameter, (0, 20] degrees: the width of the penumbra"},
             [](Scene& s) -> float& { return s.lighting.sunSize; });
    b.number(
        {"--horizon-radius", "D", "lighting.horizon_radius", "number",
         "How far shadows and sky light search for the horizon, world units (0 = the whole "
         "grid)",
         "how far shadows and sky light look for the horizon, world units; 0 = the whole grid"},
        [](Scene& s) -> float& { return s.lighting.horizonRadius; });
    OptionEntry& time =
        b.entry({"--sun-time", "TIME", "lighting.sun_time", "string or null",
                 "Place the sun at this time over the DEM's centre (ISO 8601 with zone, e.g. "
                 "2026-06-21T17:30:00Z); replaces --sun-azimuth and --sun-altitude",
                 "place the sun at this ISO 8601 time (with `Z` or `+hh:mm`) over the DEM; "
                 "replaces `sun_azimuth` and `sun_altitude`"},
                1);
    time.excludes = {"--sun-azimuth", "--sun-altitude"};
    time.shown = [](const Scene& s) { return s.lighting.sunTime.value_or(""); };
    time.fromWords = [](Scene& s, Words w) {
        terrain::parseUtcTime(w[0], "--sun-time");
        s.lighting.sunTime = w[0];
    };
    time.toJson = [](const Scene& s) {
        return s.lighting.sunTime ? Json(*s.lighting.sunTime) : Json(nullptr);
    };
    time.fromJson = [](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
        if (v.is_null())
            s.lighting.sunTime.reset();
        else
            s.lighting.sunTime = r.toString(v, k);  // checked by validateScene
    };
    b.optionalNumber(
        {"--latitude", "DEG", "lighting.latitude", "number or null",
         "Latitude of --sun-time, degrees north (default: the DEM's centre)",
         "the place of `sun_time`, degrees north; null = the DEM's centre"},
        [](Scene& s) -> std::optional<float>& { return s.lighting.latitude; }, "DEM");
    b.optionalNumber(
        {"--longitude", "DEG", "lighting.longitude", "number or null",
         "Longitude of --sun-time, degrees east (default: the DEM's centre)",
         "the place of `sun_time`, degrees east; null = the DEM's centre"},
        [](Scene& s) -> std::optional<float>& { return s.lighting.longitude; }, "DEM");
    b.number(
        {"--sun-step", "S", "lighting.sun_step", "number",
         "Seconds of --sun-time between frames of a sequence (0 = a fixed sun)",
         "seconds of `sun_time` between the frames of a sequence; 0 = the same sun in every frame"},
        [](Scene& s) -> float& { return s.lighting.sunStep; });
}

void lodEntries(std::vector<OptionEntry>& out) {
    Builder b(out, kLodOptions, "Level of detail");
    b.choice<LodMode>(
        {"--lod", "sbt|full", "lod.mode", "`\"sbt\"`, `\"full\"`",
         "Level of detail: sbt (view-dependent) or full (every grid cell)",
         "view-dependent SBT mesh, or every grid cell"},
        [](Scene& s) -> LodMode& { return s.lod.mode; }, parseLodMode, toString);
    b.number(
        {"--tau", "PX", "lod.tau", "number > 0", "SBT screen-space error threshold in pixels (> 0)",
         "SBT screen-space error threshold in pixels"},
        [](Scene& s) -> float& { return s.lod.tau; });
    b.flag(
        {"--no-geomorph", "", "lod.geomorph", "boolean", "Do not blend newly active vertices in",
         "blend newly active vertices in, so none pops"},
        [](Scene& s) -> bool& { return s.lod.geomorph; }, false);
    b.flag(
        {"--no-cull", "", "lod.cull", "boolean", "Do not cull against the view frustum",
         "frustum culling during refinement"},
        [](Scene& s) -> bool& { return s.lod.cull; }, false);
    b.integer({"--threads", "N", "lod.threads", "integer 0..256",
               "CPU threads (0 = all cores; the SBT refinement then runs on one or all, whichever "
               "it measures faster)",
               "CPU threads; 0 = all cores (the SBT refinement then runs on one or all, whichever "
               "it measures faster: `docs/refinement.md`)"},
              [](Scene& s) -> int& { return s.lod.threads; });
    b.string({"--mesh", "MESH.obj", "lod.mesh", "string",
              "Draw this TIN (an OBJ from sierra-tin of the same terrain) instead of the SBT",
              "a TIN drawn instead of the SBT or the full grid; `\"\"` = none"},
             [](Scene& s) -> std::string& { return s.lod.mesh; });
}

}  // namespace detail

const std::vector<OptionEntry>& optionTable() {
    static const std::vector<OptionEntry> table = [] {
        std::vector<OptionEntry> t;
        using namespace detail;
        terrainEntries(t);
        cameraEntries(t);
        pathEntries(t);
        lightingEntries(t);
        lodEntries(t);
        frameEntries(t);
        outputEntries(t);
        debugEntries(t);
        zoneEntries(t);
        styleEntries(t);
        overlayEntries(t);
        layerEntries(t);
        return t;
    }();
    return table;
}

}  // namespace sierra::scene
