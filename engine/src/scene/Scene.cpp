#include <sierra/scene/Scene.h>

#include <sierra/scene/Assets.h>
#include <sierra/scene/StyleJson.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/terrain/SunPosition.h>

#include "scene/Names.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <tuple>

namespace sierra::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string show(const Vec3& v) {
    return msg(v.x, " ", v.y, " ", v.z);
}

// Throws "KEY (OPTION) ...": the same message serves a JSON file and a command line.
[[noreturn]] void fail(const char* key, const char* option, const std::string& what) {
    throw Error(msg(key, " (", option, ") ", what));
}

void validateTerrain(const TerrainSource& t) {
    if (t.heightmap.empty() && t.generateSize < 3)
        fail("terrain.generate", "--generate",
             msg("must be 2^n + 1 samples, at least 3, got ", t.generateSize));
    if (!(t.roughness > 0.0f) || !(t.roughness <= terrain::kMaxRoughness))
        fail("terrain.roughness", "--roughness",
             msg("must be a number in (0, ", terrain::kMaxRoughness,
                 "] (it sets the generated heights' units; the relief comes from the vertical "
                 "scale), got ",
                 t.roughness));
    if (t.hurst && !std::isfinite(*t.hurst))
        fail("terrain.hurst", "--hurst", msg("must be a finite number, got ", *t.hurst));
    if ((t.rawWidth == 0) != (t.rawHeight == 0) || t.rawWidth < 0 || t.rawHeight < 0 ||
        t.rawWidth > 65537 || t.rawHeight > 65537)
        fail("terrain.raw_width/raw_height", "--raw-size",
             msg("must both be 1..65537 or both 0 (guess a square), got ", t.rawWidth, "x",
                 t.rawHeight));
    if (!(t.spacing >= 0.0f) || !std::isfinite(t.spacing))
        fail("terrain.spacing", "--spacing",
             msg("must be >= 0 world units (0 = the file's), got ", t.spacing));
    if (!(t.verticalScale >= 0.0f) || !std::isfinite(t.verticalScale))
        fail("terrain.vertical_scale", "--vertical-scale",
             msg("must be >= 0 (0 = automatic), got ", t.verticalScale));
    if (t.seaLevel.mode == SeaLevel::Mode::Value && !std::isfinite(t.seaLevel.value))
        fail("terrain.sea_level", "--sea-level",
             msg("must be a finite height, 'auto' or 'none', got ", t.seaLevel.value));
}

void validateCamera(const CameraDesc& c) {
    if (c.position && !finite(*c.position))
        fail("camera.position", "--camera-pos", msg("must be finite, got ", show(*c.position)));
    if (c.target && !finite(*c.target))
        fail("camera.target", "--camera-target", msg("must be finite, got ", show(*c.target)));
    if (c.position && c.target && *c.position == *c.target)
        fail("camera.position", "--camera-pos",
             msg("equals camera.target (--camera-target) ", show(*c.target),
                 ": the camera must look somewhere"));
    if (c.position && (c.azimuth || c.elevation || c.distance))
        fail("camera.position", "--camera-pos",
             "excludes camera.azimuth/elevation/distance (--azimuth/--elevation/--distance): give "
             "one or the other");
    if (c.azimuth && !std::isfinite(*c.azimuth))
        fail("camera.azimuth", "--azimuth", msg("must be finite degrees, got ", *c.azimuth));
    if (c.elevation && !(*c.elevation >= -90.0f && *c.elevation <= 90.0f))
        fail("camera.elevation", "--elevation", msg("must be -90..90 degrees, got ", *c.elevation));
    if (c.distance && !(*c.distance > 0.0f && std::isfinite(*c.distance)))
        fail("camera.distance", "--distance", msg("must be > 0 world units, got ", *c.distance));
    if (!(c.fov > 0.0f && c.fov < 180.0f))
        fail("camera.fov", "--fov", msg("must be in (0, 180) degrees, got ", c.fov));
}

void validatePath(const PathDesc& p, const CameraDesc& c) {
    if (p.frames < 1) fail("path.frames", "--frames", msg("must be >= 1, got ", p.frames));
    if (p.range &&
        (p.range->first < 0 || p.range->first > p.range->last || p.range->last >= p.frames))
        fail("path.range", "--frames A:B",
             msg(p.range->first, ":", p.range->last, " must satisfy 0 <= A <= B < ", p.frames,
                 " (the sequence's frame count, path.frames / --frame-count)"));
    if (p.frames > 1 && p.type == PathType::None &&
        (c.position || c.azimuth || c.elevation || c.distance))
        fail("path.type", "--path",
             msg("is none with ", p.frames,
                 " frames and a fixed camera: every frame would be the same; use "
                 "--path keyframes (keyframes in a --config file) or --path orbit|flyover"));
    if (p.type == PathType::Keyframes) {
        if (p.keyframes.size() < 2)
            fail(
                "path.keyframes", "--path keyframes",
                msg("needs at least 2 keyframes (from a --config file), got ", p.keyframes.size()));
        for (size_t k = 0; k < p.keyframes.size(); ++k) {
            const Keyframe& f = p.keyframes[k];
            std::string key = msg("path.keyframes[", k, "]");
            if (!std::isfinite(f.time) || !finite(f.position) || !finite(f.target))
                throw Error(msg(key, " must have finite time, position and target"));
            if (f.position == f.target)
                throw Error(msg(key, ": position equals target ", show(f.target)));
            if (k > 0 && !(f.time > p.keyframes[k - 1].time))
                throw Error(msg(key, ".time ", f.time,
                                " must be greater than the previous keyframe's ",
                                p.keyframes[k - 1].time));
        }
    }
}

void validateLighting(const LightingDesc& l) {
    if (!std::isfinite(l.sunAzimuth))
        fail("lighting.sun_azimuth", "--sun-azimuth",
             msg("must be finite degrees, got ", l.sunAzimuth));
    if (!(l.sunAltitude >= -90.0f && l.sunAltitude <= 90.0f))
        fail("lighting.sun_altitude", "--sun-altitude",
             msg("must be -90..90 degrees, got ", l.sunAltitude));
    if (!(l.ambient >= 0.0f && l.ambient <= 1.0f))
        fail("lighting.ambient", "--ambient", msg("must be 0..1, got ", l.ambient));
    if (l.fog && !(*l.fog >= 0.0f && std::isfinite(*l.fog)))
        fail("lighting.fog", "--fog", msg("must be >= 0 per world unit (0 = off), got ", *l.fog));
    for (float v : {l.sky.r, l.sky.g, l.sky.b})
        if (!(v >= 0.0f && v <= 1.0f))
            fail("lighting.sky", "--sky",
                 msg("channels must be 0..1, got ", l.sky.r, ",", l.sky.g, ",", l.sky.b));
    if (!(l.sunSize > 0.0f && l.sunSize <= kMaxSunSize))
        fail("lighting.sun_size", "--sun-size",
             msg("must be an angular diameter in (0, ", kMaxSunSize,
                 "] degrees (the sun seen from the Earth: 0.53), got ", l.sunSize));
    if (!(l.horizonRadius >= 0.0f && std::isfinite(l.horizonRadius)))
        fail("lighting.horizon_radius", "--horizon-radius",
             msg("must be >= 0 world units (0 = the whole grid), got ", l.horizonRadius));
    if (l.sunTime) terrain::parseUtcTime(*l.sunTime, "lighting.sun_time (--sun-time)");
    if (l.latitude && !(*l.latitude >= -90.0f && *l.latitude <= 90.0f))
        fail("lighting.latitude", "--latitude", msg("must be -90..90 degrees, got ", *l.latitude));
    if (l.longitude && !(*l.longitude >= -180.0f && *l.longitude <= 360.0f))
        fail("lighting.longitude", "--longitude",
             msg("must be -180..360 degrees east, got ", *l.longitude));
    if (!l.sunTime && (l.latitude || l.longitude))
        fail(l.latitude ? "lighting.latitude" : "lighting.longitude",
             l.latitude ? "--latitude" : "--longitude",
             "places the sun only with a time: give lighting.sun_time (--sun-time) too");
    if (!std::isfinite(l.sunStep))
        fail("lighting.sun_step", "--sun-step", msg("must be finite seconds, got ", l.sunStep));
    if (!l.sunTime && l.sunStep != 0.0f)
        fail("lighting.sun_step", "--sun-step",
             "moves the sun from lighting.sun_time (--sun-time): give that too");
}

void validateStyle(const StyleDesc& s) {
    if (!(s.treeLine > 0.0f) || !std::isfinite(s.treeLine))
        fail("style.tree_line", "--tree-line",
             msg("must be a finite height > 0 m, got ", s.treeLine));
    if (!(s.snowLine >= s.treeLine) || !std::isfinite(s.snowLine))
        fail("style.snow_line", "--snow-line",
             msg("must be finite and at least the tree line (", s.treeLine, " m), got ",
                 s.snowLine));
    if (s.colourBy != "surface" && s.colourBy != "level" && s.colourBy != "error")
        fail("style.colour_by", "--colour-by",
             msg("must be surface, level or error, got '", s.colourBy, "'"));
    if (!s.polygons && !s.points && !s.wireframe)
        fail("style.polygons", "--display",
             "draws nothing: name at least one of points, wireframe, polygons");
    // Overlay parameters: the analysis module's own checks and messages.
    analysis::validate(s.overlay.curvature);
    analysis::validate(analysis::lineOptions(s.overlay));
    if (s.overlay.autoScale && s.overlay.curvature.levels.enabled)
        fail("style.curvature.scale", "--curvature-scale",
             "is auto, which picks the scale from the values; with level control (--levels) give "
             "the scale as a number");
    if (!(s.overlay.lines.width > 0.0f) || !std::isfinite(s.overlay.lines.width))
        fail("style.lines.width", "--line-width",
             msg("must be a finite number of pixels > 0, got ", s.overlay.lines.width));
    if (!(s.overlay.hatch.length > 0.0f) || !std::isfinite(s.overlay.hatch.length))
        fail("style.hatch.length", "--hatch-length",
             msg("must be a finite number of grid units > 0, got ", s.overlay.hatch.length));
    if (!(s.overlay.hatch.width > 0.0f) || !std::isfinite(s.overlay.hatch.width))
        fail("style.hatch.width", "--hatch-width",
             msg("must be a finite number of pixels > 0, got ", s.overlay.hatch.width));
}

void validateZones(const ZonesDesc& z) {
    if (z.blend != "linear" && z.blend != "height")
        fail("zones.blend", "--blend", msg("must be linear or height, got '", z.blend, "'"));
    if (z.debugView != "none" && z.debugView != "zones" && z.debugView != "bands")
        fail("zones.debug_view", "--debug-view",
             msg("must be none, zones or bands, got '", z.debugView, "'"));
    if (!std::isfinite(z.band) || z.band > 1000.0f)
        fail("zones.band", "--band",
             msg("must be a width in zone-map pixels (< 0 = the palette's), got ", z.band));
    if (!(z.epsilon >= 0.0f) || !std::isfinite(z.epsilon))
        fail("zones.epsilon", "--zone-epsilon",
             msg("must be >= 0 zone-map pixels, got ", z.epsilon));
    for (auto [value, key, option] :
         {std::tuple{z.deepWater, "zones.deep_water", "--deep-water"},
          std::tuple{z.sandTop, "zones.sand_top", "--sand-top"},
          std::tuple{z.snowLine, "zones.snow_line", "--zone-snow-line"}})
        if (!(value >= 0.0f && value <= 1.0f))
            fail(key, option, msg("must be a fraction 0..1, got ", value));
    if (!(z.rockSlope > 0.0f && z.rockSlope < 90.0f))
        fail("zones.rock_slope", "--rock-slope", msg("must be 0..90 degrees, got ", z.rockSlope));
    if (z.map.empty() && z.debugView != "none")
        fail("zones.debug_view", "--debug-view", "needs zones (--zones auto or a zone map)");
}

void validateLod(const LodDesc& l) {
    if (!(l.tau > 0.0f) || !std::isfinite(l.tau))
        fail("lod.tau", "--tau", msg("must be a finite number of pixels > 0, got ", l.tau));
    if (l.threads < 0 || l.threads > 256)
        fail("lod.threads", "--threads", msg("must be 0..256 (0 = all cores), got ", l.threads));
}

void validateVideo(const OutputDesc& o) {
    if (o.fps < 1 || o.fps > 1000)
        fail("output.fps", "--fps", msg("must be 1..1000 frames per second, got ", o.fps));
    if (o.crf < -1 || o.crf > 63)
        fail("output.crf", "--crf",
             msg("must be 0..63 (lower is better; -1 = the codec's default), got ", o.crf));
    if (o.bitrate < 0)
        fail("output.bitrate", "--bitrate",
             msg("must be >= 0 bits per second (0 = constant quality), got ", o.bitrate));
    if (o.crf >= 0 && o.bitrate > 0)
        fail("output.crf", "--crf",
             "excludes output.bitrate (--bitrate): give constant quality or a bitrate");
    if (o.alpha && isVideoOutput(o.frame))
        fail("output.alpha", "--alpha",
             msg("makes a transparent sky, which video frames cannot hold; write PNG frames for "
                 "it (got '",
                 o.frame, "')"));
}

// The dataset outputs: each file type by its extension (only the normals
// take .exr: float images), their settings, and the frame image's name kept
// apart from them.
void validateDataset(const OutputDesc& o) {
    if (!o.normals.empty() && lowerExtension(o.normals) != ".npy" &&
        lowerExtension(o.normals) != ".exr")
        fail("output.normals", "--normals-out",
             msg("must be a .npy or .exr file (float images), got '", o.normals, "'"));
    if (o.normalsSpace != "camera" && o.normalsSpace != "world")
        fail("output.normals_space", "--normals-space",
             msg("must be camera or world, got '", o.normalsSpace, "'"));
    if (o.normalsPrecision != "float32" && o.normalsPrecision != "float16")
        fail("output.normals_precision", "--normals-precision",
             msg("must be float32 or float16, got '", o.normalsPrecision, "'"));
    auto png = [](const std::string& path, const char* key, const char* option, const char* what) {
        if (!path.empty() && lowerExtension(path) != ".png")
            fail(key, option,
                 msg("must be a .png file (", what, " are 8-bit grey PNG), got '", path,
                     lowerExtension(path) == ".exr" ? "'; .exr holds float images, the normals"
                                                    : "'"));
    };
    png(o.zoneIds, "output.zone_ids", "--zones-out", "zone ids");
    png(o.mask, "output.mask", "--mask-out", "masks");
    for (auto [path, key, option] :
         {std::tuple{&o.camera, "output.camera", "--camera-out"},
          std::tuple{&o.transforms, "output.transforms", "--transforms-out"}})
        if (!path->empty() && lowerExtension(*path) != ".json")
            fail(key, option, msg("must be a .json file, got '", *path, "'"));
    if (!o.transforms.empty() && isVideoOutput(o.frame))
        fail("output.transforms", "--transforms-out",
             msg("names frame images, and --out '", o.frame,
                 "' is a video; give a .png or .jpg frame name"));
    // Two outputs of one name would overwrite each other frame by frame.
    const std::pair<const std::string*, const char*> named[] = {
        {&o.frame, "--out"},
        {&o.depth, "--depth-out"},
        {&o.normals, "--normals-out"},
        {&o.zoneIds, "--zones-out"},
        {&o.mask, "--mask-out"},
        {&o.camera, "--camera-out"},
        {&o.transforms, "--transforms-out"}};
    for (size_t a = 0; a < std::size(named); ++a)
        for (size_t b = a + 1; b < std::size(named); ++b)
            if (!named[a].first->empty() && *named[a].first == *named[b].first)
                throw Error(msg(named[a].second, " and ", named[b].second, " both name '",
                                *named[a].first, "'; each output needs its own file"));
}

void validateOutput(const OutputDesc& o) {
    if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
        fail("output.width/height", "--size",
             msg("must each be 1..16384, got ", o.width, "x", o.height));
    if (o.snapshotEvery < 0)
        fail("output.snapshot_every", "--snapshot-every",
             msg("must be >= 0 (0 = the last frame only), got ", o.snapshotEvery));
    if (o.msaa != 0 && o.msaa != 2 && o.msaa != 4 && o.msaa != 8)
        fail("output.msaa", "--msaa", msg("must be 0 (off), 2, 4 or 8, got ", o.msaa));
    if (o.frame.empty()) fail("output.frame", "--out", "must name a PNG or JPEG file or a video");
    // Images are written as PNG (frames also as JPEG or video) by their name:
    // a name that promises another format (frame.tif) is refused rather than
    // silently mislabelled.
    auto png = [&](const std::string& path, const char* key, const char* option) {
        if (!path.empty() && lowerExtension(path) != ".png")
            fail(key, option,
                 msg("must be a .png file (images are written as PNG), got '", path, "'"));
    };
    const std::string frameExtension = lowerExtension(o.frame);
    const bool jpeg = frameExtension == ".jpg" || frameExtension == ".jpeg";
    if (frameExtension != ".png" && !jpeg && !isVideoOutput(o.frame))
        fail("output.frame", "--out",
             msg("must be a .png, .jpg or .jpeg file or a video (.mp4, .mov, .mkv, .webm, .gif; "
                 "the format follows the name), got '",
                 o.frame, "'"));
    if (jpeg && o.alpha)
        fail("output.alpha", "--alpha",
             msg("JPEG has no alpha channel: a transparent sky needs a .png frame, got '", o.frame,
                 "'"));
    if (o.jpegQuality < 1 || o.jpegQuality > 100)
        fail("output.jpeg_quality", "--jpeg-quality", msg("must be 1..100, got ", o.jpegQuality));
    if (o.maxQueuedFrames < 0)
        fail("output.max_queued_frames", "--max-queued-frames",
             msg("must be >= 0 (0 = from the memory available), got ", o.maxQueuedFrames));
    validateVideo(o);
    png(o.debug, "output.debug", "--debug-out");
    png(o.snapshotOnly, "output.snapshot_only", "--snapshot-only");
    if (!o.depth.empty() && lowerExtension(o.depth) != ".npy")
        fail("output.depth", "--depth-out", msg("must be a .npy file, got '", o.depth, "'"));
    validateDataset(o);
}

}  // namespace

bool isVideoOutput(const std::string& path) {
    const std::string ext = lowerExtension(path);
    for (const char* video : kVideoExtensions)
        if (ext == video) return true;
    return false;
}

Vec3 directionFromAngles(float azimuthDegrees, float altitudeDegrees) {
    const double a = double(azimuthDegrees) * kPi / 180.0,
                 e = double(altitudeDegrees) * kPi / 180.0;
    return {float(std::sin(a) * std::cos(e)), float(std::sin(e)),
            float(-std::cos(a) * std::cos(e))};
}

const char* toString(Projection projection) {
    return projection == Projection::Orthographic ? "orthographic" : "perspective";
}

const char* toString(PathType type) {
    switch (type) {
        case PathType::Orbit:
            return "orbit";
        case PathType::Flyover:
            return "flyover";
        case PathType::Keyframes:
            return "keyframes";
        case PathType::None:
            break;
    }
    return "none";
}

const char* toString(LodMode mode) {
    return mode == LodMode::Full ? "full" : "sbt";
}

Projection parseProjection(const std::string& text, const std::string& what) {
    static const std::pair<const char*, Projection> kNames[] = {
        {"perspective", Projection::Perspective}, {"orthographic", Projection::Orthographic}};
    return detail::parseName(text, what, kNames);
}

PathType parsePathType(const std::string& text, const std::string& what) {
    static const std::pair<const char*, PathType> kNames[] = {{"none", PathType::None},
                                                              {"orbit", PathType::Orbit},
                                                              {"flyover", PathType::Flyover},
                                                              {"keyframes", PathType::Keyframes}};
    return detail::parseName(text, what, kNames);
}

LodMode parseLodMode(const std::string& text, const std::string& what) {
    static const std::pair<const char*, LodMode> kNames[] = {{"sbt", LodMode::Sbt},
                                                             {"full", LodMode::Full}};
    return detail::parseName(text, what, kNames);
}

const char* toString(PngCompression level) {
    switch (level) {
        case PngCompression::Default:
            return "default";
        case PngCompression::Best:
            return "best";
        case PngCompression::Fast:
            break;
    }
    return "fast";
}

PngCompression parsePngCompression(const std::string& text, const std::string& what) {
    static const std::pair<const char*, PngCompression> kNames[] = {
        {"fast", PngCompression::Fast},
        {"default", PngCompression::Default},
        {"best", PngCompression::Best}};
    return detail::parseName(text, what, kNames);
}

void validateScene(const Scene& scene) {
    validateMapLayers(scene.layers);
    validateTerrain(scene.terrain);
    validateCamera(scene.camera);
    validatePath(scene.path, scene.camera);
    validateLighting(scene.lighting);
    validateLod(scene.lod);
    validateStyle(scene.style);
    validateZones(scene.zones);
    validateOutput(scene.output);
    if (!scene.output.zoneIds.empty() && scene.zones.map.empty())
        fail("output.zone_ids", "--zones-out",
             "needs zones (--zones auto or a zone map): the ids are the zone map's");
}

SunAngles sceneSun(const Scene& scene, const terrain::Heightfield& field, int frame) {
    const LightingDesc& l = scene.lighting;
    SunAngles sun{.azimuth = l.sunAzimuth, .altitude = l.sunAltitude};
    if (!l.sunTime) return sun;
    const std::optional<terrain::Heightfield::GeoPoint>& centre = field.geoCentre();
    if (!centre && !(l.latitude && l.longitude))
        throw Error(
            "lighting.sun_time (--sun-time) places the sun over the terrain's latitude and "
            "longitude, but this terrain has no georeference (SRTM .hgt, GeoTIFF and .npz with "
            "geographic bounds have one): give --latitude and --longitude (lighting.latitude, "
            "lighting.longitude), or --sun-azimuth and --sun-altitude instead");
    sun.latitude = l.latitude ? double(*l.latitude) : centre->latitude;
    sun.longitude = l.longitude ? double(*l.longitude) : centre->longitude;
    sun.time = terrain::parseUtcTime(*l.sunTime, "lighting.sun_time (--sun-time)") +
               double(frame) * double(l.sunStep);
    const terrain::SunPosition p = terrain::sunPosition(*sun.time, sun.latitude, sun.longitude);
    sun.azimuth = float(p.azimuth);
    sun.altitude = float(p.altitude);
    return sun;
}

std::string presetPath(const std::string& name) {
    const bool line =
        name.size() == 5 && name.rfind("fig3", 0) == 0 && name[4] >= 'a' && name[4] <= 'n';
    const bool hatch =
        name.size() == 5 && name.rfind("fig4", 0) == 0 && name[4] >= 'a' && name[4] <= 'h';
    SIERRA_CHECK(line || hatch, "unknown preset '", name,
                 "' (expected fig3a..fig3n for line shading or fig4a..fig4h for hatch shading)");
    return assetPath("presets/" + name + ".json");
}

analysis::StyleParams loadPreset(const std::string& name) {
    return loadStyleFile(presetPath(name));
}

zones::AutoZoneDesc autoZoneDesc(const ZonesDesc& zones, float seaLevel,
                                 const terrain::Heightfield& field) {
    zones::AutoZoneDesc desc;
    desc.seaLevel = std::isnan(seaLevel) ? field.range().first - 1.0f : seaLevel;
    desc.deepWater = zones.deepWater;
    desc.sandTop = zones.sandTop;
    desc.snowLine = zones.snowLine;
    desc.rockSlope = zones.rockSlope;
    return desc;
}

}  // namespace sierra::scene
