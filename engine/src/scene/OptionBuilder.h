#pragma once
// The pieces the option table (OptionTable.h) is built from: the command
// line's value parsers and the entry factories by value type. Private to the
// scene module (OptionTable.cpp, OptionTableOutput.cpp).

#include <sierra/core/Error.h>
#include <sierra/scene/OptionTable.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sierra::scene::detail {

using Words = const std::vector<std::string>&;

inline int parseInt(const std::string& text, const std::string& option,
                    const char* expected = "an integer") {
    char* end = nullptr;
    errno = 0;
    long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE || v < std::numeric_limits<int>::min() ||
        v > std::numeric_limits<int>::max())
        throw Error(msg(option, " '", text, "': expected ", expected));
    return int(v);
}

inline uint64_t parseUnsigned(const std::string& text, const std::string& option) {
    char* end = nullptr;
    errno = 0;
    unsigned long long v = std::strtoull(text.c_str(), &end, 10);
    if (text.empty() || text[0] == '-' || text[0] == '+' || *end != '\0' || errno == ERANGE)
        throw Error(msg(option, " '", text, "': expected an integer 0..",
                        std::numeric_limits<uint64_t>::max()));
    return uint64_t(v);
}

// Bits per second: an integer, or a number with a k (1e3) or M (1e6) suffix.
inline int64_t parseBitrate(const std::string& text, const std::string& option) {
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

inline Vec3 parseVec3(Words words, const std::string& option) {
    if (words.size() != 3) throw Error(msg(option, ": expected 3 numbers X Y Z"));
    return {parseFloat(words[0], option, "a number (X)"),
            parseFloat(words[1], option, "a number (Y)"),
            parseFloat(words[2], option, "a number (Z)")};
}

inline std::vector<std::string> splitCommas(const std::string& text) {
    std::vector<std::string> parts(1);
    for (char ch : text) {
        if (ch == ',')
            parts.emplace_back();
        else
            parts.back() += ch;
    }
    return parts;
}

// "R,G,B", each a number.
inline Rgb parseRgb(const std::string& text, const std::string& option) {
    std::vector<std::string> parts = splitCommas(text);
    if (parts.size() != 3)
        throw Error(msg(option, " '", text, "': expected R,G,B, each 0..1, e.g. 0.62,0.74,0.86"));
    return {parseFloat(parts[0], option, "R,G,B numbers"),
            parseFloat(parts[1], option, "R,G,B numbers"),
            parseFloat(parts[2], option, "R,G,B numbers")};
}

// "on" or "off" (also true/false, yes/no, 1/0).
inline bool parseOnOff(const std::string& text, const std::string& option) {
    if (text == "on" || text == "true" || text == "yes" || text == "1") return true;
    if (text == "off" || text == "false" || text == "no" || text == "0") return false;
    throw Error(msg(option, " '", text, "': expected on or off"));
}

inline std::string show(const std::optional<float>& v, const char* absent = "auto") {
    return v ? msg(*v) : absent;
}

inline std::string show(const std::optional<Vec3>& v) {
    return v ? msg(v->x, " ", v->y, " ", v->z) : "auto";
}

inline Json vec3Json(const Vec3& v) {
    return Json::array({jsonNumber(v.x), jsonNumber(v.y), jsonNumber(v.z)});
}

inline Vec3 vec3FromJson(const JsonObject& r, const Json& v, const std::string& key) {
    if (!v.is_array() || v.size() != 3) r.wrongType(v, key, "an array of 3 numbers [x, y, z]");
    return {r.toFloat(v[0], key + "[0]"), r.toFloat(v[1], key + "[1]"),
            r.toFloat(v[2], key + "[2]")};
}

inline void clearSunTime(Scene& s) {
    s.lighting.sunTime.reset();
    s.lighting.latitude.reset();
    s.lighting.longitude.reset();
    s.lighting.sunStep = 0.0f;
}

// An entry's text: its flag and value words, key, docs type, help and docs meaning.
struct Text {
    const char* flag = "";
    const char* words = "";
    const char* key = "";
    const char* type = "";
    const char* help = "";
    const char* doc = "";
    const char* docOption = "";
};

// A field of the scene, as a function giving it (a captureless lambda).
template <typename T>
using Ref = T& (*)(Scene&);

// Reads a field through its Ref; the Ref only names the field, it does not change it.
template <typename T>
const T& get(Ref<T> ref, const Scene& s) {
    return ref(const_cast<Scene&>(s));
}

// Adds entries of one group and heading, one factory per value type; each
// factory fills the command line's and the scene file's sides alike.
class Builder {
  public:
    Builder(std::vector<OptionEntry>& out, unsigned group, std::string heading)
        : out_(out), group_(group), heading_(std::move(heading)) {}

    void heading(std::string h) { heading_ = std::move(h); }

    OptionEntry& entry(const Text& t, int count) {
        OptionEntry& e = out_.emplace_back();
        e.flag = t.flag;
        e.words = t.words;
        e.count = count;
        e.group = group_;
        e.heading = heading_;
        e.help = t.help;
        e.key = t.key;
        e.type = t.type;
        e.doc = t.doc;
        e.docOption = t.docOption;
        return e;
    }

    OptionEntry& number(const Text& t, Ref<float> ref, const char* expected = "a number") {
        OptionEntry& e = entry(t, 1);
        const std::string flag = t.flag;
        e.shown = [ref](const Scene& s) { return msg(get(ref, s)); };
        e.fromWords = [ref, flag, expected](Scene& s, Words w) {
            ref(s) = parseFloat(w[0], flag, expected);
        };
        e.toJson = [ref](const Scene& s) { return jsonNumber(get(ref, s)); };
        e.fromJson = [ref](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
            ref(s) = r.toFloat(v, k);
        };
        return e;
    }

    OptionEntry& optionalNumber(const Text& t, Ref<std::optional<float>> ref,
                                const char* absent = "auto") {
        OptionEntry& e = entry(t, 1);
        const std::string flag = t.flag;
        e.shown = [ref, absent](const Scene& s) { return show(get(ref, s), absent); };
        e.fromWords = [ref, flag](Scene& s, Words w) { ref(s) = parseFloat(w[0], flag); };
        e.toJson = [ref](const Scene& s) {
            return get(ref, s) ? jsonNumber(*get(ref, s)) : Json(nullptr);
        };
        e.fromJson = [ref](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
            if (v.is_null())
                ref(s).reset();
            else
                ref(s) = r.toFloat(v, k, "a number or null");
        };
        return e;
    }

    OptionEntry& integer(const Text& t, Ref<int> ref, const char* expected = "an integer") {
        OptionEntry& e = entry(t, 1);
        const std::string flag = t.flag;
        e.shown = [ref](const Scene& s) { return msg(get(ref, s)); };
        e.fromWords = [ref, flag, expected](Scene& s, Words w) {
            ref(s) = parseInt(w[0], flag, expected);
        };
        e.toJson = [ref](const Scene& s) { return Json(get(ref, s)); };
        e.fromJson = [ref](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
            ref(s) = r.toInt(v, k);
        };
        return e;
    }

    OptionEntry& string(const Text& t, Ref<std::string> ref) {
        OptionEntry& e = entry(t, 1);
        e.shown = [ref](const Scene& s) { return get(ref, s); };
        e.fromWords = [ref](Scene& s, Words w) { ref(s) = w[0]; };
        e.toJson = [ref](const Scene& s) { return Json(get(ref, s)); };
        e.fromJson = [ref](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
            ref(s) = r.toString(v, k);
        };
        return e;
    }

    // A boolean: "on|off" words on the command line, true or false in the file.
    OptionEntry& onOff(const Text& t, Ref<bool> ref) {
        OptionEntry& e = boolean(t, ref, 1);
        const std::string flag = t.flag;
        e.shown = [ref](const Scene& s) { return get(ref, s) ? "on" : "off"; };
        e.fromWords = [ref, flag](Scene& s, Words w) { ref(s) = parseOnOff(w[0], flag); };
        return e;
    }

    // A boolean set to `value` by a flag (--alpha, --no-cull).
    OptionEntry& flag(const Text& t, Ref<bool> ref, bool value) {
        OptionEntry& e = boolean(t, ref, 0);
        e.fromWords = [ref, value](Scene& s, Words) { ref(s) = value; };
        return e;
    }

    // A named choice: parse(text, what) throws naming `what` and the names.
    template <typename E>
    OptionEntry& choice(const Text& t, Ref<E> ref,
                        E (*parse)(const std::string&, const std::string&),
                        const char* (*name)(E)) {
        OptionEntry& e = entry(t, 1);
        const std::string flag = t.flag;
        e.shown = [ref, name](const Scene& s) { return std::string(name(get(ref, s))); };
        e.fromWords = [ref, parse, flag](Scene& s, Words w) { ref(s) = parse(w[0], flag); };
        e.toJson = [ref, name](const Scene& s) { return Json(name(get(ref, s))); };
        e.fromJson = [ref, parse](Scene& s, const JsonObject& r, const Json& v,
                                  const std::string& k) {
            ref(s) = parse(r.toString(v, k), msg(r.source(), ": ", k));
        };
        return e;
    }

  private:
    OptionEntry& boolean(const Text& t, Ref<bool> ref, int count) {
        OptionEntry& e = entry(t, count);
        e.toJson = [ref](const Scene& s) { return Json(get(ref, s)); };
        e.fromJson = [ref](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
            ref(s) = r.toBool(v, k);
        };
        return e;
    }

    std::vector<OptionEntry>& out_;
    unsigned group_;
    std::string heading_;
};

// The entries of each part, appended in command-line order.
void terrainEntries(std::vector<OptionEntry>& out);
void cameraEntries(std::vector<OptionEntry>& out);
void pathEntries(std::vector<OptionEntry>& out);
void lightingEntries(std::vector<OptionEntry>& out);
void lodEntries(std::vector<OptionEntry>& out);
void frameEntries(std::vector<OptionEntry>& out);
void outputEntries(std::vector<OptionEntry>& out);
void debugEntries(std::vector<OptionEntry>& out);
void zoneEntries(std::vector<OptionEntry>& out);
void styleEntries(std::vector<OptionEntry>& out);
void overlayEntries(std::vector<OptionEntry>& out);
void layerEntries(std::vector<OptionEntry>& out);

}  // namespace sierra::scene::detail
