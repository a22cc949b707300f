#include <sierra/scene/Options.h>

#include <sierra/core/Error.h>
#include <sierra/scene/SceneJson.h>
#include <sierra/terrain/SunPosition.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

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

namespace {

int parseInt(const std::string& text, const std::string& option,
             const char* expected = "an integer") {
    char* end = nullptr;
    errno = 0;
    long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE || v < std::numeric_limits<int>::min() ||
        v > std::numeric_limits<int>::max())
        throw Error(msg(option, " '", text, "': expected ", expected));
    return int(v);
}

uint64_t parseUnsigned(const std::string& text, const std::string& option) {
    char* end = nullptr;
    errno = 0;
    unsigned long long v = std::strtoull(text.c_str(), &end, 10);
    if (text.empty() || text[0] == '-' || text[0] == '+' || *end != '\0' || errno == ERANGE)
        throw Error(msg(option, " '", text, "': expected an integer 0..",
                        std::numeric_limits<uint64_t>::max()));
    return uint64_t(v);
}

// Bits per second: an integer, or a number with a k (1e3) or M (1e6) suffix.
int64_t parseBitrate(const std::string& text, const std::string& option) {
    const char* expected = "bits per second, e.g. 8000000, 8000k or 8M";
    double factor = 1.0;
    std::string number = text;
    if (!number.empty() && (number.back() == 'k' || number.back() == 'K')) factor = 1e3;
    if (!number.empty() && number.back() == 'M') factor = 1e6;
    if (factor > 1.0) number.pop_back();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(number.c_str(), &end) * factor;
    if (number.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v) || v < 0.0 ||
        v > 1e12)
        throw Error(msg(option, " '", text, "': expected ", expected));
    return int64_t(std::llround(v));
}

Vec3 parseVec3(const std::vector<std::string>& words, const std::string& option) {
    if (words.size() != 3) throw Error(msg(option, ": expected 3 numbers X Y Z"));
    return {parseFloat(words[0], option, "a number (X)"),
            parseFloat(words[1], option, "a number (Y)"),
            parseFloat(words[2], option, "a number (Z)")};
}

// "R,G,B", each a number.
Rgb parseRgb(const std::string& text, const std::string& option) {
    std::vector<std::string> parts(1);
    for (char ch : text) {
        if (ch == ',')
            parts.emplace_back();
        else
            parts.back() += ch;
    }
    if (parts.size() != 3)
        throw Error(msg(option, " '", text, "': expected R,G,B, each 0..1, e.g. 0.62,0.74,0.86"));
    return {parseFloat(parts[0], option, "R,G,B numbers"),
            parseFloat(parts[1], option, "R,G,B numbers"),
            parseFloat(parts[2], option, "R,G,B numbers")};
}

// "on" or "off" (also true/false, yes/no, 1/0).
bool parseOnOff(const std::string& text, const std::string& option) {
    if (text == "on" || text == "true" || text == "yes" || text == "1") return true;
    if (text == "off" || text == "false" || text == "no" || text == "0") return false;
    throw Error(msg(option, " '", text, "': expected on or off"));
}

const char* onOff(bool on) {
    return on ? "on" : "off";
}

void clearSunTime(Scene& s) {
    s.lighting.sunTime.reset();
    s.lighting.latitude.reset();
    s.lighting.longitude.reset();
    s.lighting.sunStep = 0.0f;
}

std::string show(float v) {
    return msg(v);
}

std::string show(const std::optional<float>& v, const char* absent = "auto") {
    return v ? msg(*v) : absent;
}

std::string show(const std::optional<Vec3>& v, const char* absent = "auto") {
    return v ? msg(v->x, " ", v->y, " ", v->z) : absent;
}

}  // namespace

CLI::Option* SceneOptions::add(const char* name, const std::string& help, const std::string& group,
                               const char* typeName, const std::string& defaultText, int values,
                               Setter set) {
    std::vector<std::string>& storage = values_.emplace_back();
    CLI::Option* option = app_.add_option(name, storage, help);
    // Given twice, the last one counts (as a later word overrides an earlier one).
    option->expected(values)->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    option->type_name(typeName)->group(group);
    if (!defaultText.empty()) option->default_str(defaultText);
    entries_.push_back({option, &storage, std::move(set)});
    return option;
}

CLI::Option* SceneOptions::addFlag(const char* name, const std::string& help,
                                   const std::string& group, Setter set) {
    CLI::Option* option = app_.add_flag(name)->description(help)->group(group);
    entries_.push_back({option, nullptr, std::move(set)});
    return option;
}

SceneOptions::SceneOptions(CLI::App& app, Scene& scene, unsigned groups)
    : app_(app), scene_(scene), defaults_(scene) {
    const Scene& d = defaults_;
    using Words = const std::vector<std::string>&;

    configOption_ =
        app_.add_option(
                "--config", config_,
                "Scene file (JSON, see docs/scene.md) loaded first; options given beside it "
                "override it")
            ->type_name("FILE.json")
            ->group("Scene file");
    printOption_ = app_.add_flag("--print-config")
                       ->description("Print the effective scene as JSON and exit")
                       ->group("Scene file");

    if (groups & kTerrainOptions) {
        const std::string g = "Terrain";
        auto* heightmap = add("--heightmap",
                              "Heightmap to load: .png (8/16-bit grey), .pgm, .r16/.r32 (with "
                              "--raw-size), .hgt, .npy, .npz (.tif with GDAL)",
                              g, "FILE", d.terrain.heightmap.empty() ? "" : d.terrain.heightmap, 1,
                              [](Scene& s, Words w) { s.terrain.heightmap = w[0]; });
        // The check alone, without its "FILE" appended to the type name in --help.
        heightmap->check(CLI::Validator(CLI::ExistingFile).description(""));
        auto* generate =
            add("--generate", "Generate a diamond-square terrain of N x N samples, N = 2^n + 1", g,
                "N", msg(d.terrain.generateSize), 1, [](Scene& s, Words w) {
                    s.terrain.heightmap.clear();
                    s.terrain.generateSize = parseInt(w[0], "--generate", "an integer 2^n + 1");
                });
        generate->excludes(heightmap);
        add("--seed", "Seed of the generated terrain", g, "S", msg(d.terrain.seed), 1,
            [](Scene& s, Words w) { s.terrain.seed = parseUnsigned(w[0], "--seed"); });
        add("--roughness", "Amplitude factor of the generator's random offsets (> 0)", g, "R",
            show(d.terrain.roughness), 1,
            [](Scene& s, Words w) { s.terrain.roughness = parseFloat(w[0], "--roughness"); });
        add("--hurst",
            "Generator's per-level amplitude factor 2^-H (default: the generator's own scaling)", g,
            "H", show(d.terrain.hurst, ""), 1,
            [](Scene& s, Words w) { s.terrain.hurst = parseFloat(w[0], "--hurst"); });
        add("--raw-size", "Samples per row and rows of a .r16/.r32 heightmap (each 1..65537)", g,
            "WxH", d.terrain.rawWidth ? msg(d.terrain.rawWidth, "x", d.terrain.rawHeight) : "", 1,
            [](Scene& s, Words w) {
                auto [width, height] = parseRawSize(w[0], "--raw-size");
                s.terrain.rawWidth = width;
                s.terrain.rawHeight = height;
            });
        add("--spacing",
            "World units between samples (0 = the file's: 1, or metres for SRTM, GeoTIFF and "
            "georeferenced .npz)",
            g, "S", show(d.terrain.spacing), 1,
            [](Scene& s, Words w) { s.terrain.spacing = parseFloat(w[0], "--spacing"); });
        add("--vertical-scale",
            "Stored height to world height (0 = automatic: 1 for metres, else relief 20% of the "
            "extent)",
            g, "V", show(d.terrain.verticalScale), 1, [](Scene& s, Words w) {
                s.terrain.verticalScale = parseFloat(w[0], "--vertical-scale");
            });
        std::string seaDefault = d.terrain.seaLevel.mode == SeaLevel::Mode::Value
                                     ? show(d.terrain.seaLevel.value)
                                     : toString(d.terrain.seaLevel.mode);
        add("--sea-level", "Water level in stored height units, 'auto' (from the data) or 'none'",
            g, "H|auto|none", seaDefault, 1, [](Scene& s, Words w) {
                if (w[0] == "auto")
                    s.terrain.seaLevel = {};
                else if (w[0] == "none")
                    s.terrain.seaLevel = {.mode = SeaLevel::Mode::None};
                else
                    s.terrain.seaLevel = {
                        .mode = SeaLevel::Mode::Value,
                        .value = parseFloat(w[0], "--sea-level", "a height, 'auto' or 'none'")};
            });
        add("--height-units",
            "What heights measure: auto (metres for SRTM, GeoTIFF and .npz with geographic "
            "coordinates), m (metres) or none",
            g, "auto|m|none", toString(d.terrain.heightUnits), 1, [](Scene& s, Words w) {
                s.terrain.heightUnits = parseHeightUnits(w[0], "--height-units");
            });
        add("--channel",
            "Height channel of a colour image: luminance, r, g or b (default: grey images only)", g,
            "NAME", d.terrain.channel == Channel::Grey ? "" : toString(d.terrain.channel), 1,
            [](Scene& s, Words w) { s.terrain.channel = parseChannel(w[0], "--channel"); });
    }

    if (groups & kCameraOptions) {
        const std::string g = "Camera";
        auto* pos = add("--camera-pos",
                        "Camera position X Y Z in world units (default: fits the whole terrain)", g,
                        "X Y Z", show(d.camera.position), 3, [](Scene& s, Words w) {
                            s.camera.position = parseVec3(w, "--camera-pos");
                            // Given here, it replaces a scene file's orbit-style camera.
                            s.camera.azimuth.reset();
                            s.camera.elevation.reset();
                            s.camera.distance.reset();
                        });
        add("--camera-target", "Point the camera looks at, X Y Z (default: the terrain's centre)",
            g, "X Y Z", show(d.camera.target), 3,
            [](Scene& s, Words w) { s.camera.target = parseVec3(w, "--camera-target"); });
        // The three angles replace a scene file's position, as --camera-pos replaces them.
        auto* azimuth =
            add("--azimuth", "Camera bearing from the target, degrees clockwise from north (-z)", g,
                "DEG", show(d.camera.azimuth), 1, [](Scene& s, Words w) {
                    s.camera.azimuth = parseFloat(w[0], "--azimuth");
                    s.camera.position.reset();
                });
        auto* elevation =
            add("--elevation", "Camera elevation above the horizon seen from the target, degrees",
                g, "DEG", show(d.camera.elevation), 1, [](Scene& s, Words w) {
                    s.camera.elevation = parseFloat(w[0], "--elevation");
                    s.camera.position.reset();
                });
        auto* distance = add("--distance", "Camera distance from the target, world units", g, "D",
                             show(d.camera.distance), 1, [](Scene& s, Words w) {
                                 s.camera.distance = parseFloat(w[0], "--distance");
                                 s.camera.position.reset();
                             });
        pos->excludes(azimuth)->excludes(elevation)->excludes(distance);
        add("--fov", "Vertical field of view in degrees, (0, 180)", g, "DEG", show(d.camera.fov), 1,
            [](Scene& s, Words w) { s.camera.fov = parseFloat(w[0], "--fov"); });
        addFlag("--ortho", "Orthographic projection (map-like); tau stays in pixels", g,
                [](Scene& s, Words) { s.camera.projection = Projection::Orthographic; });
    }

    if (groups & kPathOptions) {
        const std::string g = "Camera path";
        add("--path",
            "Camera path over the frames: none, orbit, flyover or keyframes (from --config)", g,
            "none|orbit|flyover|keyframes", toString(d.path.type), 1,
            [](Scene& s, Words w) { s.path.type = parsePathType(w[0], "--path"); });
        add("--frames",
            "N frames, or A:B = frames A..B (0-based, inclusive) of the sequence (its count from "
            "--frame-count or "
            "--config), same files and bytes as the whole run",
            g, "N|A:B", msg(d.path.frames), 1, [](Scene& s, Words w) {
                const std::string& text = w[0];
                size_t colon = text.find(':');
                if (colon == std::string::npos) {
                    s.path.frames = parseInt(text, "--frames", "N (>= 1) or A:B");
                    s.path.range.reset();
                } else {
                    const char* expected = "A:B, two integers 0 <= A <= B";
                    s.path.range =
                        FrameRange{parseInt(text.substr(0, colon), "--frames", expected),
                                   parseInt(text.substr(colon + 1), "--frames", expected)};
                }
            });
        frameCountOption_ =
            add("--frame-count", "Frames in the whole sequence, for --frames A:B", g, "N", "", 1,
                [](Scene& s, Words w) { s.path.frames = parseInt(w[0], "--frame-count"); });
    }

    if (groups & kLightingOptions) {
        const std::string g = "Lighting";
        // Given here, a fixed sun replaces a scene file's time.
        auto* sunAzimuth = add("--sun-azimuth", "Sun bearing, degrees clockwise from north (-z)", g,
                               "DEG", show(d.lighting.sunAzimuth), 1, [](Scene& s, Words w) {
                                   s.lighting.sunAzimuth = parseFloat(w[0], "--sun-azimuth");
                                   clearSunTime(s);
                               });
        auto* sunAltitude = add("--sun-altitude", "Sun altitude above the horizon, degrees", g,
                                "DEG", show(d.lighting.sunAltitude), 1, [](Scene& s, Words w) {
                                    s.lighting.sunAltitude = parseFloat(w[0], "--sun-altitude");
                                    clearSunTime(s);
                                });
        add("--ambient", "Ambient light, fraction of full light 0..1", g, "A",
            show(d.lighting.ambient), 1,
            [](Scene& s, Words w) { s.lighting.ambient = parseFloat(w[0], "--ambient"); });
        add("--fog", "Fog density per world unit; 0 = off, auto = 0.35 / the terrain's extent", g,
            "D|auto", show(d.lighting.fog), 1, [](Scene& s, Words w) {
                if (w[0] == "auto")
                    s.lighting.fog.reset();
                else
                    s.lighting.fog = parseFloat(w[0], "--fog", "a density >= 0 or 'auto'");
            });
        add("--sky", "Sky and fog colour, each 0..1", g, "R,G,B",
            msg(d.lighting.sky.r, ",", d.lighting.sky.g, ",", d.lighting.sky.b), 1,
            [](Scene& s, Words w) { s.lighting.sky = parseRgb(w[0], "--sky"); });
        add("--shadows", "Soft shadows the terrain casts from the sun", g, "on|off",
            onOff(d.lighting.shadows), 1,
            [](Scene& s, Words w) { s.lighting.shadows = parseOnOff(w[0], "--shadows"); });
        add("--sky-light",
            "Ambient light scaled by the share of the sky each point sees (darker valleys)", g,
            "on|off", onOff(d.lighting.skyLight), 1,
            [](Scene& s, Words w) { s.lighting.skyLight = parseOnOff(w[0], "--sky-light"); });
        add("--sun-size", "Angular diameter of the sun, degrees (the penumbra's width), > 0", g,
            "DEG", show(d.lighting.sunSize), 1,
            [](Scene& s, Words w) { s.lighting.sunSize = parseFloat(w[0], "--sun-size"); });
        add("--horizon-radius",
            "How far shadows and sky light search for the horizon, world units (0 = the whole "
            "grid)",
            g, "D", show(d.lighting.horizonRadius), 1, [](Scene& s, Words w) {
                s.lighting.horizonRadius = parseFloat(w[0], "--horizon-radius");
            });
        auto* sunTime =
            add("--sun-time",
                "Place the sun at this time over the DEM's centre (ISO 8601 with zone, e.g. "
                "2026-06-21T17:30:00Z); replaces --sun-azimuth and --sun-altitude",
                g, "TIME", d.lighting.sunTime.value_or(""), 1, [](Scene& s, Words w) {
                    terrain::parseUtcTime(w[0], "--sun-time");
                    s.lighting.sunTime = w[0];
                });
        sunTime->excludes(sunAzimuth)->excludes(sunAltitude);
        add("--latitude", "Latitude of --sun-time, degrees north (default: the DEM's centre)", g,
            "DEG", show(d.lighting.latitude, "DEM"), 1,
            [](Scene& s, Words w) { s.lighting.latitude = parseFloat(w[0], "--latitude"); });
        add("--longitude", "Longitude of --sun-time, degrees east (default: the DEM's centre)", g,
            "DEG", show(d.lighting.longitude, "DEM"), 1,
            [](Scene& s, Words w) { s.lighting.longitude = parseFloat(w[0], "--longitude"); });
        add("--sun-step", "Seconds of --sun-time between frames of a sequence (0 = a fixed sun)", g,
            "S", show(d.lighting.sunStep), 1,
            [](Scene& s, Words w) { s.lighting.sunStep = parseFloat(w[0], "--sun-step"); });
    }

    if (groups & kLodOptions) {
        const std::string g = "Level of detail";
        add("--lod", "Level of detail: sbt (view-dependent) or full (every grid cell)", g,
            "sbt|full", toString(d.lod.mode), 1,
            [](Scene& s, Words w) { s.lod.mode = parseLodMode(w[0], "--lod"); });
        add("--tau", "SBT screen-space error threshold in pixels (> 0)", g, "PX", show(d.lod.tau),
            1, [](Scene& s, Words w) { s.lod.tau = parseFloat(w[0], "--tau"); });
        addFlag("--no-geomorph", "Do not blend newly active vertices in", g,
                [](Scene& s, Words) { s.lod.geomorph = false; });
        addFlag("--no-cull", "Do not cull against the view frustum", g,
                [](Scene& s, Words) { s.lod.cull = false; });
        add("--threads",
            "CPU threads (0 = all cores; the SBT refinement then runs on one or all, whichever it "
            "measures faster)",
            g, "N", msg(d.lod.threads), 1,
            [](Scene& s, Words w) { s.lod.threads = parseInt(w[0], "--threads"); });
        add("--mesh",
            "Draw this TIN (an OBJ from sierra-tin of the same terrain) instead of the SBT", g,
            "MESH.obj", d.lod.mesh, 1, [](Scene& s, Words w) { s.lod.mesh = w[0]; });
    }

    if (groups & kFrameOptions) {
        const std::string g = "Frame";
        add("--size", "Frame size in pixels", g, "WxH", msg(d.output.width, "x", d.output.height),
            1, [](Scene& s, Words w) {
                auto [width, height] = parseFrameSize(w[0], "--size");
                s.output.width = width;
                s.output.height = height;
            });
        add("--msaa", "Samples per pixel: 0 (off), 2, 4 or 8", g, "N", msg(d.output.msaa), 1,
            [](Scene& s, Words w) { s.output.msaa = parseInt(w[0], "--msaa", "0, 2, 4 or 8"); });
    }

    if (groups & kOutputOptions) {
        const std::string g = "Output";
        add("--out",
            "Frame PNG, or JPEG for .jpg / .jpeg (sequences: NAME_0000.png, ...), or a video of "
            "all frames: .mp4, .mov, .mkv, .webm or .gif",
            g, "FILE.png|FILE.mp4", d.output.frame, 1,
            [](Scene& s, Words w) { s.output.frame = w[0]; });
        add("--depth-out", "Linear eye-space depth per pixel, float32 .npy (NaN where no terrain)",
            g, "FILE.npy", d.output.depth, 1, [](Scene& s, Words w) { s.output.depth = w[0]; });
        addFlag("--alpha", "RGBA PNG with a transparent sky", g,
                [](Scene& s, Words) { s.output.alpha = true; });
        add("--png-compression",
            "PNG frames: fast (zlib level 1, run-length matches, one filter), default (level 6) or "
            "best (level 9), every filter tried per row for the last two",
            g, "fast|default|best", toString(d.output.pngCompression), 1, [](Scene& s, Words w) {
                s.output.pngCompression = parsePngCompression(w[0], "--png-compression");
            });
        add("--jpeg-quality", "JPEG frames (--out NAME.jpg): quality 1..100", g, "Q",
            msg(d.output.jpegQuality), 1, [](Scene& s, Words w) {
                s.output.jpegQuality = parseInt(w[0], "--jpeg-quality", "an integer 1..100");
            });
        add("--max-queued-frames",
            "Sequences: frames read back and waiting for their encoder, at most (0 = from the "
            "memory available, 2..16)",
            g, "N", msg(d.output.maxQueuedFrames), 1, [](Scene& s, Words w) {
                s.output.maxQueuedFrames = parseInt(w[0], "--max-queued-frames", "an integer >= 0");
            });
        const std::string v = "Video (--out NAME.mp4|.mov|.mkv|.webm|.gif)";
        add("--fps", "Video frames per second, 1..1000", v, "N", msg(d.output.fps), 1,
            [](Scene& s, Words w) { s.output.fps = parseInt(w[0], "--fps"); });
        add("--crf", "Video constant quality, 0..63, lower is better (default: the codec's)", v,
            "Q", d.output.crf < 0 ? "" : msg(d.output.crf), 1,
            [](Scene& s, Words w) { s.output.crf = parseInt(w[0], "--crf", "an integer 0..63"); });
        add("--bitrate",
            "Video average bitrate, bits per second (k and M suffixes), not with --crf", v, "BPS",
            d.output.bitrate > 0 ? msg(d.output.bitrate) : "", 1,
            [](Scene& s, Words w) { s.output.bitrate = parseBitrate(w[0], "--bitrate"); });
        add("--video-codec",
            "h264, hevc, av1, vp9, gif, or an encoder (libx264, h264_nvenc, ...); default: by "
            "container (H.264; VP9 for .webm)",
            v, "NAME", d.output.videoCodec, 1,
            [](Scene& s, Words w) { s.output.videoCodec = w[0]; });
        add("--video-preset",
            "Encoder speed preset (libx264: ultrafast..veryslow, default veryfast; NVENC p1..p7)",
            v, "NAME", d.output.videoPreset, 1,
            [](Scene& s, Words w) { s.output.videoPreset = w[0]; });
    }

    if (groups & kDebugOptions) {
        const std::string g = "Debug";
        auto* debugOut = add("--debug-out", "ImGui debug snapshot PNG", g, "FILE.png",
                             d.output.debug, 1, [](Scene& s, Words w) { s.output.debug = w[0]; });
        auto* snapshot = add(
            "--snapshot", "ImGui debug snapshot PNG: the UI beside the frame (same as --debug-out)",
            g, "FILE.png", "", 1, [](Scene& s, Words w) { s.output.debug = w[0]; });
        addFlag("--no-debug", "Do not write the debug snapshot", g,
                [](Scene& s, Words) { s.output.debug.clear(); })
            ->excludes(debugOut)
            ->excludes(snapshot);
        add("--snapshot-only", "The debug UI alone on a plain background, as PNG", g, "FILE.png",
            "", 1, [](Scene& s, Words w) { s.output.snapshotOnly = w[0]; });
        add("--snapshot-every",
            "Sequences: a snapshot of every Nth frame (NAME_0000.png); 0 = the last only", g, "N",
            "0", 1,
            [](Scene& s, Words w) { s.output.snapshotEvery = parseInt(w[0], "--snapshot-every"); });
        addFlag("--snapshot-deterministic",
                "Snapshots show placeholders instead of measured times (golden images)", g,
                [](Scene& s, Words) { s.output.snapshotDeterministic = true; });
    }

    if (groups & kZoneOptions) {
        const std::string g = "Zones";
        add("--zones", "Zone tiles: auto (from height and slope) or a zone-map PNG", g,
            "auto|MAP.png", d.zones.map, 1, [](Scene& s, Words w) { s.zones.map = w[0]; });
        add("--palette", "Zone palette JSON (surface types, tiles, blend settings)", g, "P.json",
            d.zones.palette.empty() ? "assets/palettes/default.json" : d.zones.palette, 1,
            [](Scene& s, Words w) { s.zones.palette = w[0]; });
        add("--band", "Transition band width in zone-map pixels (0 = none; default: the palette's)",
            g, "W", d.zones.band < 0.0f ? "palette" : show(d.zones.band), 1,
            [](Scene& s, Words w) { s.zones.band = parseFloat(w[0], "--band"); });
        add("--zone-epsilon", "Borderline simplification distance, zone-map pixels", g, "E",
            show(d.zones.epsilon), 1,
            [](Scene& s, Words w) { s.zones.epsilon = parseFloat(w[0], "--zone-epsilon"); });
        // Auto-zoning thresholds (--zones auto).
        add("--deep-water", "Auto-zones: deep water below this fraction of the depth range, 0..1",
            g, "F", show(d.zones.deepWater), 1,
            [](Scene& s, Words w) { s.zones.deepWater = parseFloat(w[0], "--deep-water"); });
        add("--sand-top", "Auto-zones: sand up to this fraction of the land relief, 0..1", g, "F",
            show(d.zones.sandTop), 1,
            [](Scene& s, Words w) { s.zones.sandTop = parseFloat(w[0], "--sand-top"); });
        add("--zone-snow-line", "Auto-zones: snow above this fraction of the land relief, 0..1", g,
            "F", show(d.zones.snowLine), 1,
            [](Scene& s, Words w) { s.zones.snowLine = parseFloat(w[0], "--zone-snow-line"); });
        add("--rock-slope", "Auto-zones: rock steeper than this, degrees (0, 90)", g, "DEG",
            show(d.zones.rockSlope), 1,
            [](Scene& s, Words w) { s.zones.rockSlope = parseFloat(w[0], "--rock-slope"); });
    }

    if (groups & kZoneShadingOptions) {
        const std::string g = "Zones";
        add("--blend", "Blend across a band: linear (by distance) or height (tile heights move it)",
            g, "linear|height", d.zones.blend, 1, [](Scene& s, Words w) { s.zones.blend = w[0]; });
        addFlag("--triplanar", "Project tiles along the normal's axes on steep slopes", g,
                [](Scene& s, Words) { s.zones.triplanar = true; });
        addFlag("--no-tile-variation",
                "No slow warp of the tile coordinates against visible repetition", g,
                [](Scene& s, Words) { s.zones.variation = false; });
        add("--debug-view", "Flat zone colours (zones) or the band blend weight (bands)", g,
            "none|zones|bands", d.zones.debugView, 1,
            [](Scene& s, Words w) { s.zones.debugView = w[0]; });
    }

    if (groups & kStyleOptions) {
        addFlag("--wireframe", "Overlay the triangulation", "Style",
                [](Scene& s, Words) { s.style.wireframe = true; });
        add("--colour-by",
            "Colour the polygons by surface, level (SBT level) or error (screen-space error heat "
            "map)",
            "Style", "MODE", "surface", 1, [](Scene& s, Words w) { s.style.colourBy = w[0]; });
        add("--display", "What to draw: any of points, wireframe, polygons, comma-separated",
            "Style", "LIST", "polygons", 1, [](Scene& s, Words w) {
                s.style.points = s.style.wireframe = s.style.polygons = false;
                std::stringstream in(w[0]);
                for (std::string item; std::getline(in, item, ',');) {
                    if (item == "points")
                        s.style.points = true;
                    else if (item == "wireframe")
                        s.style.wireframe = true;
                    else if (item == "polygons")
                        s.style.polygons = true;
                    else
                        throw Error(
                            msg("--display: unknown item '", item,
                                "'; expected points, wireframe or polygons, comma-separated"));
                }
            });
        add("--tree-line", "Metric heights: metres above which rock replaces vegetation", "Style",
            "M", show(d.style.treeLine), 1,
            [](Scene& s, Words w) { s.style.treeLine = parseFloat(w[0], "--tree-line"); });
        add("--snow-line", "Metric heights: metres above which snow lies", "Style", "M",
            show(d.style.snowLine), 1,
            [](Scene& s, Words w) { s.style.snowLine = parseFloat(w[0], "--snow-line"); });
        // Curvature overlays (analysis/Style.h). Entries apply in this order,
        // so --preset comes first and the options after it override it.
        const std::string o = "Overlays";
        add("--preset",
            "Overlay style preset: fig3a..fig3n (line shading), fig4a..fig4h (hatch shading)", o,
            "NAME", "", 1, [](Scene& s, Words w) {
                s.style.overlay = loadPreset(w[0]);
                s.style.preset = w[0];
            });
        add("--style", "Layers: any of shaded,lines,hatch,contours (without shaded: plain paper)",
            o, "LIST", "shaded", 1, [](Scene& s, Words w) {
                analysis::StyleLayers layers{.shaded = false};
                std::string name;
                for (size_t k = 0; k <= w[0].size(); ++k) {
                    if (k < w[0].size() && w[0][k] != ',') {
                        name += w[0][k];
                        continue;
                    }
                    if (!layers.enable(name))
                        throw Error(msg("--style: unknown layer '", name, "' (expected ",
                                        analysis::kStyleLayerNames, ")"));
                    name.clear();
                }
                s.style.overlay.layers = layers;
            });
        add("--curvature", "Curvature method: two-normal, three-normal, three-vertex or edge-angle",
            o, "METHOD", analysis::curvatureMethodName(d.style.overlay.curvature.method), 1,
            [](Scene& s, Words w) {
                s.style.overlay.curvature.method = analysis::parseCurvatureMethod(w[0]);
            });
        add("--curvature-distance", "Curvature reinforcement distance in grid steps (1 = none)", o,
            "D", msg(d.style.overlay.curvature.distance), 1, [](Scene& s, Words w) {
                s.style.overlay.curvature.distance = parseInt(w[0], "--curvature-distance");
            });
        add("--curvature-scale",
            "Factor on every curvature value (>= 0), or 'auto': the top 5% of the samples reach "
            "the line threshold (hatches alone: full opacity)",
            o, "S|auto", show(d.style.overlay.curvature.scale), 1, [](Scene& s, Words w) {
                analysis::StyleParams& style = s.style.overlay;
                style.autoScale = w[0] == "auto";
                if (!style.autoScale)
                    style.curvature.scale =
                        parseFloat(w[0], "--curvature-scale", "a number or 'auto'");
            });
        add("--normals", "Vertex normals of the curvature: edge, triangle or quad", o, "KIND",
            analysis::normalMethodName(d.style.overlay.curvature.normals), 1,
            [](Scene& s, Words w) {
                s.style.overlay.curvature.normals = analysis::parseNormalMethod(w[0]);
            });
        addFlag("--signed", "Keep the sign of the curvature (ridges and valleys apart)", o,
                [](Scene& s, Words) { s.style.overlay.curvature.signedValues = true; });
        add("--levels", "Curvature level control: black point, white point, gamma", o, "B,W,G", "",
            1, [](Scene& s, Words w) {
                std::vector<std::string> parts(1);
                for (char ch : w[0]) {
                    if (ch == ',')
                        parts.emplace_back();
                    else
                        parts.back().push_back(ch);
                }
                if (parts.size() != 3)
                    throw Error(
                        msg("--levels '", w[0], "': expected BLACK,WHITE,GAMMA, e.g. 0.1,0.9,1.5"));
                s.style.overlay.curvature.levels = {.enabled = true,
                                                    .black = parseFloat(parts[0], "--levels"),
                                                    .white = parseFloat(parts[1], "--levels"),
                                                    .gamma = parseFloat(parts[2], "--levels")};
            });
        add("--line-width", "Curvature line width in pixels", o, "PX",
            show(d.style.overlay.lines.width), 1, [](Scene& s, Words w) {
                s.style.overlay.lines.width = parseFloat(w[0], "--line-width");
            });
        add("--min-length", "Shortest curvature line kept, in vertices (>= 2)", o, "N",
            msg(d.style.overlay.lines.minLength), 1, [](Scene& s, Words w) {
                s.style.overlay.lines.minLength = parseInt(w[0], "--min-length");
            });
        add("--line-threshold", "Curvature a vertex needs to be on a line", o, "K",
            show(d.style.overlay.lines.threshold), 1, [](Scene& s, Words w) {
                s.style.overlay.lines.threshold = parseFloat(w[0], "--line-threshold");
            });
        add("--hatch-length", "Hatch stroke length in grid units", o, "L",
            show(d.style.overlay.hatch.length), 1, [](Scene& s, Words w) {
                s.style.overlay.hatch.length = parseFloat(w[0], "--hatch-length");
            });
        add("--hatch-width", "Hatch stroke width in pixels", o, "PX",
            show(d.style.overlay.hatch.width), 1, [](Scene& s, Words w) {
                s.style.overlay.hatch.width = parseFloat(w[0], "--hatch-width");
            });
        add("--hatch-direction",
            "Hatch strokes along or across the direction of greatest curvature", o, "DIR",
            analysis::hatchDirectionName(d.style.overlay.hatch.direction), 1,
            [](Scene& s, Words w) {
                s.style.overlay.hatch.direction = analysis::parseHatchDirection(w[0]);
            });
        add("--cpt", "Colour the surface with a GMT .cpt table (absolute stored heights)", "Style",
            "FILE.cpt", "", 1, [](Scene& s, Words w) { s.style.cpt = w[0]; });
    }
}

void SceneOptions::apply() {
    apply({});
}

void SceneOptions::apply(const std::function<void(Scene&)>& program) {
    Scene scene = defaults_;
    if (configOption_->count() > 0) scene = sceneFromJson(readJsonFile(config_), config_, scene);
    const std::vector<std::string> noWords;
    for (const Entry& e : entries_)
        if (e.option->count() > 0) e.set(scene, e.words ? *e.words : noWords);
    if (program) program(scene);
    if (frameCountOption_ && frameCountOption_->count() > 0 && !scene.path.range)
        throw Error(
            "--frame-count goes with --frames A:B (a part of a sequence); --frames N alone gives "
            "the count");
    try {
        validateScene(scene);
    } catch (const Error& e) {
        // The message names the key and the option; say which file the key may come from.
        if (configOption_->count() > 0)
            throw Error(msg(config_, " with the command line: ", e.what()));
        throw;
    }
    scene_ = scene;
    if (printConfigRequested()) {
        std::string text = sceneToText(scene);
        std::fwrite(text.data(), 1, text.size(), stdout);
        std::fflush(stdout);
    }
}

bool SceneOptions::printConfigRequested() const {
    return printOption_->count() > 0;
}

}  // namespace sierra::scene
