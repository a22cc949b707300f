#pragma once
// The one command-line registrar of Sierra's apps: every program gets the
// scene's options from here, with the same names, types, checks and help, and
// picks the groups it needs.
//
//   scene::Scene scene;                    // the app's defaults, e.g.
//   scene.output.msaa = 0;                 //   shown by --help as [0]
//   CLI::App app{"..."};
//   scene::SceneOptions options(app, scene, scene::kTerrainOptions | scene::kOutputOptions);
//   app.parse(argc, argv);                 // CLI::ParseError -> app.exit(e)
//   options.apply();                       // sierra::Error on bad values
//   if (options.printConfigRequested()) return 0;
//
// apply() starts from the scene as it was at registration (the app's
// defaults), loads --config FILE.json over it (keys absent from the file keep
// the defaults), then applies only the options given on the command line, then
// checks the whole scene (validateScene). With --print-config it prints the
// result as JSON (sceneToText) to stdout; the app then exits 0 without
// rendering. Relative paths in a config file are relative to the working
// directory, as on the command line.

#include <sierra/scene/Scene.h>

#include <CLI/CLI.hpp>

#include <deque>
#include <functional>
#include <string>
#include <vector>

namespace sierra::scene {

// Option groups (bits): each registers the options listed and shows them under
// its own heading in --help. --config and --print-config are always registered.
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
    // --lod sbt|full, --tau PX, --no-geomorph, --no-cull, --threads N
    kLodOptions = 1u << 4,
    // --out FILE.png|.jpg, --depth-out FILE.npy, --alpha, --png-compression fast|default|best,
    // --jpeg-quality Q, --max-queued-frames N
    kOutputOptions = 1u << 5,
    // --debug-out FILE.png, --no-debug
    kDebugOptions = 1u << 6,
    // --wireframe
    kStyleOptions = 1u << 7,
    // --size WxH, --msaa 0|2|4|8
    kFrameOptions = 1u << 8,
    // --zones auto|MAP.png, --palette P.json, --band W, --zone-epsilon E, and the auto-zoning
    // thresholds --deep-water F, --sand-top F, --zone-snow-line F, --rock-slope DEG
    kZoneOptions = 1u << 9,
    // How a renderer shades zones: --blend linear|height, --triplanar, --no-tile-variation,
    // --debug-view none|zones|bands
    kZoneShadingOptions = 1u << 10,
    kAllOptions = (1u << 11) - 1,
};

// A finite float option value, or sierra::Error "OPTION 'TEXT': expected
// EXPECTED" (empty, trailing characters, out of float range, NaN or inf):
// the registrar's parser, for an app's own options too.
float parseFloat(const std::string& text, const std::string& option,
                 const char* expected = "a number");

class SceneOptions {
  public:
    // Registers the options of `groups` on `app`. `scene` holds the app's
    // defaults (shown in --help) and receives the result in apply(); both
    // `app` and `scene` must outlive this object.
    SceneOptions(CLI::App& app, Scene& scene, unsigned groups);
    SceneOptions(const SceneOptions&) = delete;
    SceneOptions& operator=(const SceneOptions&) = delete;

    // Call after app.parse() (in a subcommand's callback, or after parse
    // returns): builds the scene as described above and stores it in `scene`.
    // Throws sierra::Error naming the option (or the config file and key).
    void apply();
    // As apply(), with `program` run on the scene after the registrar's options
    // and before the check and --print-config: a program's own options that are
    // part of the scene (sierra-tin's zone options) are then printed by
    // --print-config, and read back by --config, like the registrar's.
    void apply(const std::function<void(Scene&)>& program);

    // --print-config was given: apply() printed the scene; the app exits 0.
    bool printConfigRequested() const;

  private:
    using Setter = std::function<void(Scene&, const std::vector<std::string>&)>;
    struct Entry {
        CLI::Option* option = nullptr;
        const std::vector<std::string>* words = nullptr;  // null for flags
        Setter set;
    };

    CLI::Option* add(const char* name, const std::string& help, const std::string& group,
                     const char* typeName, const std::string& defaultText, int values, Setter set);
    CLI::Option* addFlag(const char* name, const std::string& help, const std::string& group,
                         Setter set);

    CLI::App& app_;
    Scene& scene_;
    Scene defaults_;                               // the scene at registration
    std::deque<std::vector<std::string>> values_;  // CLI11 writes each option's words here
    std::vector<Entry> entries_;                   // in registration order
    std::string config_;                           // --config FILE
    CLI::Option* configOption_ = nullptr;
    CLI::Option* printOption_ = nullptr;
    CLI::Option* frameCountOption_ = nullptr;
};

}  // namespace sierra::scene
