#pragma once
// The one strict JSON reading layer of Sierra's files: scenes (SceneJson.h),
// styles and presets (StyleJson.h) and palettes (PaletteJson.h) follow the
// same rules and give the same messages.
//
// - Keys are snake_case. A key no reader asks for is an error naming its path
//   and the allowed keys (the nearest first when one is close); a camelCase
//   key whose snake_case form is allowed is named with that form.
// - One number rule: an integer field takes a JSON number only when it is
//   integral (5 and 5.0 alike; 5.5 is refused); a float field takes any finite
//   number within float range. NaN and infinities are refused (the parser
//   refuses them as text, the readers in a document built in memory).
// - Messages are one line: "SOURCE: KEY.PATH: expected WHAT, got WHAT".

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sierra::scene {

// Keys keep their order (terrain first, as in Scene), which plain nlohmann::json
// would sort alphabetically.
using Json = nlohmann::ordered_json;

// Parses JSON text; throws sierra::Error naming `source` for text that is not
// JSON (with the parser's line and column) or holds a number out of range.
Json parseJson(std::string_view text, const std::string& source);
// Reads and parses a JSON file the same way (unreadable files named too).
Json readJsonFile(const std::string& path);

// "an integer", "a string", ... for messages.
const char* jsonTypeName(const Json& value);

// "tileSize" -> "tile_size".
std::string snakeCase(std::string_view key);

// One JSON object being read: each known key is read by field() (or marked by
// allow()); finish() rejects any key that none of them named.
class JsonObject {
  public:
    // `path` is the object's key path ("" for the top level); `source` names
    // the file in messages and must outlive this object.
    JsonObject(const Json& json, std::string path, const std::string& source);

    // Calls read(value, keyPath) when `key` is present.
    template <typename F>
    void field(const std::string& key, F read) {
        allow(key);
        auto it = json_.find(key);
        if (it != json_.end()) read(*it, keyPath(key));
    }
    // Marks `key` as known; the value, or null when absent.
    const Json* allow(const std::string& key);
    bool has(const std::string& key) const { return json_.contains(key); }

    // Throws for the first key no field() or allow() named.
    void finish() const;

    [[noreturn]] void wrongType(const Json& value, const std::string& key,
                                const char* expected) const;
    [[noreturn]] void badValue(const std::string& key, const std::string& what) const;

    const std::string& source() const { return source_; }
    const std::string& path() const { return path_; }
    std::string keyPath(const std::string& key) const;

    // Typed values under the number rule above; each throws naming the key and
    // the expected type.
    float toFloat(const Json& v, const std::string& key, const char* expected = "a number") const;
    int toInt(const Json& v, const std::string& key, const char* expected = "an integer") const;
    uint64_t toUnsigned(const Json& v, const std::string& key) const;
    bool toBool(const Json& v, const std::string& key) const;
    std::string toString(const Json& v, const std::string& key) const;

  private:
    const Json& json_;
    std::string path_;
    const std::string& source_;
    std::vector<std::string> known_;
};

}  // namespace sierra::scene
