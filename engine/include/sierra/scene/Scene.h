#pragma once
// A render job described without GL: where the terrain comes from, the camera
// and its path, lighting, level of detail, outputs and style. Every app fills
// one Scene (from its defaults, a --config JSON file and its command line, see
// SceneJson.h and Options.h) and the renderer reads it.
//
// Coordinates: world units, y up, x east, z south (north = -z); the grid's
// sample (i, j) lies at (i * spacingX, height, j * spacingZ).
// Angles are degrees. Compass bearings (azimuths) are measured clockwise from
// north (-z) seen from above: 0 = north (-z), 90 = east (+x), 180 = south (+z),
// 270 = west (-x). A direction of bearing a and altitude e (above the
// horizon) is (sin a cos e, sin e, -cos a cos e).

#include <sierra/analysis/Style.h>
#include <sierra/scene/MapLayers.h>
#include <sierra/scene/Terrain.h>
#include <sierra/zones/ZoneMap.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sierra::scene {

struct Vec3 {
    float x = 0.0f, y = 0.0f, z = 0.0f;
    bool operator==(const Vec3&) const = default;
};

// Linear colour, each channel 0..1.
struct Rgb {
    float r = 0.0f, g = 0.0f, b = 0.0f;
    bool operator==(const Rgb&) const = default;
};

enum class Projection {
    Perspective,   // fov is the vertical field of view
    Orthographic,  // map-like; the view's height covers the framed terrain
};

struct CameraDesc {
    std::optional<Vec3> position;  // world units; absent = automatic (fits the whole terrain)
    std::optional<Vec3> target;    // world units; absent = the terrain's centre
    // Alternative to `position`: the camera at `distance` from the target, at
    // compass bearing `azimuth` and `elevation` above the horizon, both seen
    // from the target (degrees). Any one absent = automatic (the default
    // camera's value for it). Not given together with `position`.
    std::optional<float> azimuth;    // degrees clockwise from north (-z)
    std::optional<float> elevation;  // degrees above the horizon, -90..90
    std::optional<float> distance;   // world units, > 0
    float fov = 45.0f;  // vertical field of view in degrees, (0, 180); perspective only
    Projection projection = Projection::Perspective;
    bool operator==(const CameraDesc&) const = default;
};

enum class PathType {
    None,       // every frame uses `camera`
    Orbit,      // a full turn around the terrain over the frames, each frame fitting the terrain
    Flyover,    // a pass over the terrain
    Keyframes,  // `keyframes`, interpolated smoothly over time
};

struct Keyframe {
    float time =
        0.0f;  // any unit, increasing along the list; frames are spread evenly first..last time
    Vec3 position;  // world units
    Vec3 target;    // world units
    bool operator==(const Keyframe&) const = default;
};

// Frames first..last (0-based, inclusive) of a sequence: the files and bytes
// are those of the whole run, so a farm can split one job.
struct FrameRange {
    int first = 0;
    int last = 0;
    bool operator==(const FrameRange&) const = default;
};

struct PathDesc {
    PathType type = PathType::None;
    int frames = 1;                   // frames in the whole sequence, >= 1
    std::optional<FrameRange> range;  // absent = all frames
    std::vector<Keyframe> keyframes;  // for PathType::Keyframes, at least 2
    bool operator==(const PathDesc&) const = default;
};

// The default sun is the direction normalize(-0.45, 0.75, 0.35) Sierra always
// used (bearing 232.125, altitude 52.7609 degrees: south-west, fairly high).
inline constexpr float kDefaultSunAzimuth = 232.125f;
inline constexpr float kDefaultSunAltitude = 52.7609f;
// The largest sun diameter taken, degrees: a disc wider than this is no sun.
inline constexpr float kMaxSunSize = 20.0f;

struct LightingDesc {
    float sunAzimuth = kDefaultSunAzimuth;    // bearing of the sun seen from the ground, degrees
    float sunAltitude = kDefaultSunAltitude;  // degrees above the horizon, -90..90
    // The terrain's ambient term (the sky) as a fraction of full light, 0..1;
    // with the sky light on it is scaled by the share of the sky each point sees.
    float ambient = 0.32f;
    std::optional<float> fog;  // density per world unit; absent = automatic (aerial
                               // perspective over the framed terrain, see docs/scene.md); 0 = off
    Rgb sky{0.62f, 0.74f, 0.86f};  // background and fog colour
    // Relief lighting (analysis/Relief.h), computed on the CPU once per
    // terrain and sun and sampled per fragment at full resolution:
    bool shadows = true;    // soft shadows the terrain casts (the visible share of the sun's disc)
    bool skyLight = true;   // the ambient term times the sky light (darker valleys)
    float sunSize = 0.53f;  // the sun's angular diameter, degrees, (0, 20]: the penumbra
    float horizonRadius = 0.0f;  // horizon search radius, world units, >= 0; 0 = the whole grid
    // The sun from a place and a time instead of sunAzimuth / sunAltitude: an
    // ISO 8601 time with its zone (2026-06-21T17:30:00Z, ...+02:00), the
    // place the georeferenced DEM's centre unless latitude / longitude say
    // otherwise (terrain/SunPosition.h). Frame k of a sequence is at
    // sunTime + k * sunStep seconds.
    std::optional<std::string> sunTime;
    std::optional<float> latitude;   // degrees north, -90..90
    std::optional<float> longitude;  // degrees east, -180..360
    float sunStep = 0.0f;            // seconds between frames; 0 = the same sun in every frame
    bool operator==(const LightingDesc&) const = default;
};

enum class LodMode {
    Sbt,   // view-dependent SBT refinement
    Full,  // every grid cell
};

struct LodDesc {
    LodMode mode = LodMode::Sbt;
    float tau = 1.0f;      // SBT screen-space error threshold in pixels, > 0
    bool geomorph = true;  // blend newly active vertices in, so none pops
    bool cull = true;      // frustum culling during refinement
    int threads = 0;       // CPU threads; 0 = sierra::defaultThreadCount()
    // A TIN (an OBJ from sierra-tin, made with the same terrain options) drawn
    // instead of the SBT or the full grid; "" = none.
    std::string mesh;
    bool operator==(const LodDesc&) const = default;
};

// How hard PNG frames are compressed: fast (zlib level 1, run-length
// matches, the Sub filter on every row: several times quicker than the
// others), default (level 6) or best (level 9), the filter chosen per row.
enum class PngCompression { Fast, Default, Best };

struct OutputDesc {
    int width = 1280;  // frame size in pixels, 1..16384
    int height = 720;
    int msaa = 4;  // samples per pixel: 0 (off), 2, 4 or 8
    // Frame PNG (sequences: NAME_0000.png, ...), or a video: one file of all
    // frames (a slice --frames A:B: NAME_AAAA.EXT, a segment of the whole).
    std::string frame = "out/frame.png";
    std::string debug =
        "out/debug.png";       // ImGui debug snapshot PNG (UI over the frame); empty = none
    std::string snapshotOnly;  // the debug UI alone on a plain background; empty = none
    int snapshotEvery =
        0;  // sequences: a snapshot of every Nth frame (NAME_0000.png); 0 = last only
    bool snapshotDeterministic = false;  // snapshots show placeholders instead of measured times
    std::string depth;   // linear eye-space depth .npy (float32, NaN = no terrain); empty = none
    bool alpha = false;  // RGBA PNG with a transparent sky
    // Video output (frame ending in a kVideoExtensions name; render/Video.h):
    int fps = 30;             // frames per second, 1..1000
    std::string videoCodec;   // "" = by container; h264, hevc, av1, vp9, gif or an encoder name
    int crf = -1;             // constant quality, 0..63 (lower is better); -1 = the codec's default
    int64_t bitrate = 0;      // bits per second; 0 = none (constant quality); not with crf
    std::string videoPreset;  // the encoder's speed preset; "" = Sierra's default for it
    // Frames: PNG, or JPEG for a frame named .jpg / .jpeg.
    PngCompression pngCompression = PngCompression::Fast;
    int jpegQuality = 90;  // libjpeg quality 1..100
    // Sequences: frames read back but not yet written, at most; 0 = automatic
    // (render::defaultQueuedFrames: from the memory available, 2..16).
    int maxQueuedFrames = 0;
    // Dataset outputs per frame (sequences: NAME_0000.EXT, as the depth);
    // empty = none. docs/dataset.md describes the files.
    std::string normals;  // unit normals, height x width x 3, .npy or .exr; NaN = no terrain
    std::string normalsSpace =
        "camera";  // camera (OpenCV axes: x right, y down, z forward) or world
    std::string normalsPrecision = "float32";  // float32 or float16
    std::string zoneIds;  // zone ids as a uint8 grey .png (255 = no terrain) and NAME.json beside
                          // it (id -> name, colour); needs zones
    std::string mask;     // terrain 255 against sky 0, a uint8 grey .png
    std::string camera;   // the camera JSON of each frame (K, R|t, GL matrices, georeference)
    std::string transforms;  // one NeRF / instant-ngp transforms.json for the frames rendered
    bool operator==(const OutputDesc&) const = default;
};

// The extensions of the video containers output.frame may name (any case).
inline constexpr const char* kVideoExtensions[] = {".mp4", ".mov", ".mkv", ".webm", ".gif"};
// True when `path` ends in one of kVideoExtensions: the frames go to one video file.
bool isVideoOutput(const std::string& path);

struct StyleDesc {
    bool wireframe = false;  // overlay the triangulation
    bool polygons = true;    // the shaded surface (--display polygons)
    bool points = false;     // the mesh's vertices as points (--display points)
    std::string colourBy =
        "surface";  // polygons coloured by: surface, level (SBT) or error (split vertex, px)
    // Metric heights are coloured by absolute elevation (metres): vegetation up
    // to the tree line, rock above it, snow above the snow line. Unitless
    // heights use a ramp over their own range instead.
    float treeLine = 2000.0f;  // metres, > 0
    float snowLine = 3000.0f;  // metres, >= treeLine
    // Curvature overlays (analysis/Style.h, docs/presets.md): the layers
    // (shaded, lines, hatch, contours) and their parameters. A preset loads
    // assets/presets/NAME.json (see presetPath) first; keys and options given
    // beside it override it. Default: the shaded terrain, no overlay.
    std::string preset;  // "" or fig3a .. fig3n, fig4a .. fig4h
    analysis::StyleParams overlay;
    std::string
        cpt;  // GMT .cpt colour table of the surface (absolute stored heights); empty = none
    bool operator==(const StyleDesc&) const = default;
};

// The file of a preset: NAME.json in $SIERRA_ASSETS/presets when that is set,
// else in the source tree's assets/presets (compiled in). Throws
// sierra::Error for a name other than fig3a..fig3n / fig4a..fig4h (listing
// them) or a missing file.
std::string presetPath(const std::string& name);
// The style of a preset (analysis::loadStyleFile of presetPath(name)).
analysis::StyleParams loadPreset(const std::string& name);

// Zone tiles with blended transition bands (the terrain pass's zone surface).
struct ZonesDesc {
    std::string map;      // "" = no zones (colour ramp), "auto" = from height and slope bands, or a
                          // zone-map PNG
    std::string palette;  // palette JSON; "" = the default (assets/palettes/default.json)
    float band = -1.0f;   // transition band width in zone-map pixels; < 0 = the palette's; 0 = none
    float epsilon = 0.5f;  // borderline simplification, zone-map pixels, >= 0
    std::string blend =
        "height";            // linear (by distance) or height (tile heights move the transition)
    bool triplanar = false;  // project tiles along the normal's axes on steep slopes
    bool variation = true;   // warp the tile coordinates slowly against visible tile repetition
    std::string debugView = "none";  // none, zones (flat zone colours) or bands (the blend weight)
    // Auto-zoning thresholds (fractions of the depth and land relief; slope in degrees).
    float deepWater = 0.35f;
    float sandTop = 0.04f;
    float snowLine = 0.75f;
    float rockSlope = 25.0f;
    bool operator==(const ZonesDesc&) const = default;
};

// The auto-zoning of `zones` for `field`, as every program zones "auto": its
// thresholds, and the sea at `seaLevel` (stored height units, as
// resolveSeaLevel gives it); NaN = no water, every sample is land and the sea
// lies below the lowest height.
zones::AutoZoneDesc autoZoneDesc(const ZonesDesc& zones, float seaLevel,
                                 const terrain::Heightfield& field);

struct Scene {
    TerrainSource terrain;
    CameraDesc camera;
    PathDesc path;
    LightingDesc lighting;
    LodDesc lod;
    OutputDesc output;
    StyleDesc style;
    ZonesDesc zones;
    MapLayersDesc layers;  // drapes, vector layers, labels, map furniture
    bool operator==(const Scene&) const = default;
};

// The unit vector towards a direction of compass bearing `azimuth` and
// `altitude` above the horizon (degrees), in world coordinates (see above).
Vec3 directionFromAngles(float azimuthDegrees, float altitudeDegrees);

// The sun of one frame: where it stands (degrees) and, with a time, when and
// from where it is seen.
struct SunAngles {
    float azimuth = kDefaultSunAzimuth;      // compass bearing, degrees
    float altitude = kDefaultSunAltitude;    // degrees above the horizon (refraction included)
    std::optional<double> time;              // seconds since 1970 (UTC), with lighting.sunTime
    double latitude = 0.0, longitude = 0.0;  // degrees, with lighting.sunTime
};

// The sun of frame `frame` (0-based) of the scene's sequence: lighting's
// azimuth and altitude, or with lighting.sunTime the sun at that time plus
// frame * sunStep seconds over lighting.latitude / longitude, each defaulting
// to the centre of `field`'s georeference (terrain::Heightfield::geoCentre).
// Throws sierra::Error when a time has no place (a DEM without a
// georeference and no latitude and longitude).
SunAngles sceneSun(const Scene& scene, const terrain::Heightfield& field, int frame);

// Names used by the command line and the JSON form (the terrains are in
// Terrain.h); parse* throw sierra::Error
// naming `what` (an option or key) and the accepted names.
const char* toString(Projection projection);  // "perspective" "orthographic"
const char* toString(PathType type);          // "none" "orbit" "flyover" "keyframes"
const char* toString(LodMode mode);           // "sbt" "full"
const char* toString(PngCompression level);   // "fast" "default" "best"
Projection parseProjection(const std::string& text, const std::string& what);
PathType parsePathType(const std::string& text, const std::string& what);
LodMode parseLodMode(const std::string& text, const std::string& what);
PngCompression parsePngCompression(const std::string& text, const std::string& what);

// Checks the scene as a whole (ranges, and fields that exclude each other);
// throws sierra::Error with one line saying what is wrong and what would be
// right, naming the JSON key and the option (e.g. "lod.tau (--tau)").
void validateScene(const Scene& scene);

}  // namespace sierra::scene
