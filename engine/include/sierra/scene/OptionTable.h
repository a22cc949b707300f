#pragma once
// The one table of Sierra's scene options: for each, the command-line flag,
// the scene file's key path, the types, the help and docs text, and how it is
// read from and written to a Scene. SceneOptions (Options.h) registers the
// command line from it, SceneJson reads and writes every key it lists, and
// docs/scene.md is generated from it (sceneDocsMarkdown).
//
// An entry has a flag, a key or both: "--fov" <-> "camera.fov" share one entry;
// "--size WxH" is command-line only (it sets output.width and output.height,
// which are file-only entries naming it in `docOption`).

#include <sierra/scene/JsonRead.h>
#include <sierra/scene/Scene.h>

#include <functional>
#include <string>
#include <vector>

namespace sierra::scene {

// Option groups (bits): each registers its options and shows them under its
// own heading in --help. --config and --print-config are always registered.
enum OptionGroup : unsigned {
    // --heightmap FILE, --generate N, --seed S, --roughness R, --hurst H, --raw-size WxH,
    // --spacing S, --vertical-scale V, --sea-level H|auto|none, --height-units auto|m|none,
    // --channel grey|luminance|r|g|b
    kTerrainOptions = 1u << 0,
    // --camera-pos X Y Z, --camera-target X Y Z, --azimuth DEG, --elevation DEG,
    // --distance D, --fov DEG, --ortho
    kCameraOptions = 1u << 1,
    // --path none|orbit|flyover|keyframes, --frames N|A:B, --frame-count N
    kPathOptions = 1u << 2,
    // --sun-azimuth DEG, --sun-altitude DEG, --ambient A, --fog D|auto, --sky R,G,B,
    // --shadows on|off, --sky-light on|off, --sun-size DEG, --horizon-radius D,
    // --sun-time TIME, --latitude DEG, --longitude DEG, --sun-step S
    kLightingOptions = 1u << 3,
    // --lod sbt|full, --tau PX, --no-geomorph, --no-cull, --threads N, --mesh MESH.obj
    kLodOptions = 1u << 4,
    // --out FILE.png|.jpg, --depth-out FILE.npy, --alpha, --png-compression fast|default|best,
    // --jpeg-quality Q, --max-queued-frames N, and the video options
    kOutputOptions = 1u << 5,
    // --debug-out FILE.png, --no-debug, the snapshot options
    kDebugOptions = 1u << 6,
    // --wireframe, --display, --colour-by, --tree-line, --snow-line, --cpt and the overlays
    kStyleOptions = 1u << 7,
    // --size WxH, --msaa 0|2|4|8
    kFrameOptions = 1u << 8,
    // --zones auto|MAP.png, --palette P.json, --band W, --zone-epsilon E, and the auto-zoning
    // thresholds --deep-water F, --sand-top F, --zone-snow-line F, --rock-slope DEG
    kZoneOptions = 1u << 9,
    // How a renderer shades zones: --blend linear|height, --triplanar, --no-tile-variation,
    // --debug-view none|zones|bands
    kZoneShadingOptions = 1u << 10,
    // --drape IMAGE[:OPACITY][:multiply], --drape-bounds, --drape-bounds-units,
    // --vector FILE[:STYLE], --vector-where, --label-field
    kLayerOptions = 1u << 11,
    // --label TEXT@X,Z, --scale-bar, --north-arrow, --title, --legend, --text-size: 3D frames
    // and 2D maps (sierra-gen map) alike
    kFurnitureOptions = 1u << 12,
    kAllOptions = (1u << 13) - 1,
};

// A finite float option value, or sierra::Error "OPTION 'TEXT': expected
// EXPECTED" (empty, trailing characters, out of float range, NaN or inf):
// the registrar's parser, for an app's own options too.
float parseFloat(const std::string& text, const std::string& option,
                 const char* expected = "a number");

struct OptionEntry {
    // Command line; flag "" = scene file only.
    std::string flag;                   // "--fov"
    std::string words;                  // what --help shows for the values ("DEG"); "" for a flag
    int count = 1;                      // values taken: 0 (a flag), 1, or 3 (X Y Z)
    bool repeatable = false;            // given again, adds a value (--drape a --drape b)
    unsigned group = 0;                 // the OptionGroup registering it
    std::string heading;                // its --help heading
    std::string help;                   // its --help text
    std::vector<std::string> excludes;  // flags it cannot be given with
    bool existingFile = false;          // the value must name an existing file
    // Scene file; key "" = command line only.
    std::string key;        // "camera.fov"
    std::string type;       // docs: the JSON type ("number", "integer >= 0", ...)
    std::string doc;        // docs: the meaning; "" = the help text
    std::string docOption;  // docs: the options that set a file-only key

    // The value --help shows as the default, for the app's scene (null or "" = none).
    std::function<std::string(const Scene&)> shown;
    // Applies the option's words (`count` of them; none for a flag).
    std::function<void(Scene&, const std::vector<std::string>&)> fromWords;
    // The key's JSON value, and reading it back (`path` names it in messages).
    std::function<Json(const Scene&)> toJson;
    std::function<void(Scene&, const JsonObject&, const Json&, const std::string& path)> fromJson;
};

// Every entry, in the order the command line applies them (a later option
// overrides an earlier one's side effects, e.g. --display after --wireframe)
// and, within each part of the scene, the order the scene file is written in.
const std::vector<OptionEntry>& optionTable();

// The parts of a scene file, in the order they are written.
inline constexpr const char* kSceneParts[] = {"terrain", "camera", "path",  "lighting", "lod",
                                              "output",  "style",  "zones", "layers"};

// The shortest decimal (at most 9 significant digits) that reads back as `f`;
// null for a value that is not finite.
Json jsonNumber(float f);

// docs/scene.md: `templateText` with each line "@table PART@" replaced by the
// table of that part's keys (key, type, default, option, meaning).
std::string sceneDocsMarkdown(const std::string& templateText);

}  // namespace sierra::scene
