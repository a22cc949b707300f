#pragma once
// The one command-line registrar of Sierra's apps: every program gets the
// scene's options from here, with the same names, types, checks and help, and
// picks the groups it needs. The options are the rows of the option table
// (OptionTable.h) that have a flag.
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

#include <sierra/scene/OptionTable.h>
#include <sierra/scene/Scene.h>

#include <CLI/CLI.hpp>

#include <deque>
#include <functional>
#include <string>
#include <vector>

namespace sierra::scene {

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

    // Registers one table entry (OptionTable.h).
    CLI::Option* add(const OptionEntry& entry);

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
