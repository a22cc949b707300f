#include <sierra/scene/Options.h>

#include <sierra/core/Error.h>
#include <sierra/scene/SceneJson.h>

#include <cstdio>

namespace sierra::scene {

CLI::Option* SceneOptions::add(const OptionEntry& e) {
    CLI::Option* option = nullptr;
    const std::vector<std::string>* words = nullptr;
    if (e.count == 0) {
        option = app_.add_flag(e.flag)->description(e.help);
    } else {
        std::vector<std::string>& storage = values_.emplace_back();
        words = &storage;
        option = app_.add_option(e.flag, storage, e.help);
        // Given twice, the last one counts (as a later word overrides an earlier one),
        // unless each occurrence adds one (--drape a --drape b).
        option->expected(e.count)->multi_option_policy(
            e.repeatable ? CLI::MultiOptionPolicy::TakeAll : CLI::MultiOptionPolicy::TakeLast);
        option->type_name(e.words);
        const std::string shown = e.shown ? e.shown(defaults_) : std::string();
        if (!shown.empty()) option->default_str(shown);
        // The check alone, without its "FILE" appended to the type name in --help.
        if (e.existingFile) option->check(CLI::Validator(CLI::ExistingFile).description(""));
    }
    option->group(e.heading);
    entries_.push_back({option, words, e.fromWords});
    return option;
}

SceneOptions::SceneOptions(CLI::App& app, Scene& scene, unsigned groups)
    : app_(app), scene_(scene), defaults_(scene) {
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
    std::vector<std::pair<CLI::Option*, const OptionEntry*>> added;
    for (const OptionEntry& e : optionTable()) {
        if (e.flag.empty() || !(groups & e.group)) continue;
        added.emplace_back(add(e), &e);
        if (e.flag == "--frame-count") frameCountOption_ = added.back().first;
    }
    // Exclusions once every option exists (an entry may name a later one).
    for (auto [option, e] : added)
        for (const std::string& other : e->excludes)
            if (CLI::Option* o = app_.get_option_no_throw(other)) option->excludes(o);
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
