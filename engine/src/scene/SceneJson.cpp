#include <sierra/scene/SceneJson.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/scene/OptionTable.h>
#include <sierra/scene/StyleJson.h>

#include <string>

namespace sierra::scene {
namespace {

// The table's entries of one part ("camera"), with their keys inside it.
template <typename F>
void forEachKey(const std::string& part, F f) {
    for (const OptionEntry& e : optionTable())
        if (e.key.size() > part.size() && e.key.compare(0, part.size(), part) == 0 &&
            e.key[part.size()] == '.')
            f(e, e.key.substr(part.size() + 1));
}

// The style part's overlay keys, beside the table's: a preset first, then the
// style keys of StyleJson.h over it.
void readOverlay(JsonObject& r, StyleDesc& s) {
    bool preset = false;
    r.field("preset", [&](const Json& v, const std::string& k) {
        s.preset = r.toString(v, k);
        preset = true;
    });
    Json keys = Json::object();
    for (const char* key : kStyleJsonKeys)
        r.field(key, [&, key](const Json& v, const std::string&) { keys[key] = v; });
    if (preset) s.overlay = loadPreset(s.preset);
    if (!keys.empty()) {
        Json merged = preset ? styleToJson(s.overlay) : Json::object();
        merged.merge_patch(keys);
        s.overlay = styleFromJson(merged, r.source());
    }
}

}  // namespace

Scene sceneFromJson(const Json& json, const std::string& source, const Scene& base) {
    Scene scene = base;
    JsonObject top(json, "", source);
    for (const char* part : kSceneParts) {
        top.field(part, [&](const Json& v, const std::string& path) {
            JsonObject r(v, path, source);
            forEachKey(part, [&](const OptionEntry& e, const std::string& leaf) {
                r.field(leaf.c_str(), [&](const Json& value, const std::string& k) {
                    e.fromJson(scene, r, value, k);
                });
            });
            if (std::string(part) == "style") readOverlay(r, scene.style);
            r.finish();
        });
    }
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
    Json out = Json::object();
    for (const char* part : kSceneParts) {
        Json object = Json::object();
        forEachKey(part, [&](const OptionEntry& e, const std::string& leaf) {
            object[leaf] = e.toJson(s);
        });
        if (std::string(part) == "style") {
            if (!s.style.preset.empty()) object["preset"] = s.style.preset;
            object.update(styleToJson(s.style.overlay));
        }
        out[part] = std::move(object);
    }
    return out;
}

std::string sceneToText(const Scene& scene) {
    return sceneToJson(scene).dump(2) + "\n";
}

void saveScene(const std::string& path, const Scene& scene) {
    writeFileAtomic(path, sceneToText(scene));
}

}  // namespace sierra::scene
