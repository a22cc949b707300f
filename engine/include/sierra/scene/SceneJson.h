#pragma once
// The JSON form of a Scene (a "scene file"): one object per part, snake_case
// keys, every key optional (a missing key keeps the base scene's value):
//
//   {"terrain": {...}, "camera": {...}, "path": {...}, "lighting": {...},
//    "lod": {...}, "output": {...}, "style": {...}}
//
// docs/scene.md lists every key. null stands for an automatic value where the
// field is optional (camera.position, lighting.fog, ...). Keys are written in
// the structs' order. Floats are written as the shortest decimal that reads
// back as the same float, so save -> load -> save is byte-identical and a
// printed scene renders the same frame as the original.
//
// Errors (sierra::Error, one line): an unknown key or a value of the wrong type
// names the file, the key path (e.g. "camera.fov") and the expected type; text
// that is not JSON names the file and the parser's line and column.

#include <sierra/scene/Scene.h>

#include <sierra/scene/JsonRead.h>

#include <string>

namespace sierra::scene {

// The scene described by `json`, starting from `base` (keys absent from `json`
// keep base's values). `source` names the file in messages. Checks keys and
// types only; ranges are validateScene()'s (see Scene.h), so a command line may
// still override a value first.
Scene sceneFromJson(const Json& json, const std::string& source, const Scene& base = {});

// readJsonFile + sceneFromJson + validateScene.
Scene loadScene(const std::string& path, const Scene& base = {});

// Every field, absent optionals as null.
Json sceneToJson(const Scene& scene);

// The text saveScene writes and --print-config prints: sceneToJson indented by
// 2 spaces, ending with a newline.
std::string sceneToText(const Scene& scene);

// Writes sceneToText to `path` (a temporary name, then renamed).
void saveScene(const std::string& path, const Scene& scene);

}  // namespace sierra::scene
