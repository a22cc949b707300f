#include <sierra/scene/JsonRead.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sierra::scene {
namespace {

// Levenshtein distance, for the nearest allowed key of a misspelt one.
size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = up;
        }
    }
    return row[b.size()];
}

// The largest integral double that converts to int64_t exactly (2^63 is not).
constexpr double kInt64Limit = 9223372036854775808.0;

}  // namespace

Json parseJson(std::string_view text, const std::string& source) {
    try {
        return Json::parse(text.begin(), text.end());
    } catch (const Json::exception& e) {
        // Parse errors and numbers out of range alike; what() is
        // "[json.exception.parse_error.101] parse error at line L, column C: ...".
        std::string_view what = e.what();
        size_t start = what.find("] ");
        throw Error(
            msg(source, ": not a JSON file: ", start == what.npos ? what : what.substr(start + 2)));
    }
}

Json readJsonFile(const std::string& path) {
    const std::vector<uint8_t> bytes = readFileBytes(path);
    return parseJson(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                     path);
}

const char* jsonTypeName(const Json& j) {
    switch (j.type()) {
        case Json::value_t::null:
            return "null";
        case Json::value_t::object:
            return "an object";
        case Json::value_t::array:
            return "an array";
        case Json::value_t::string:
            return "a string";
        case Json::value_t::boolean:
            return "a boolean";
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
            return "an integer";
        case Json::value_t::number_float:
            return "a number with a fraction";
        default:
            return "something else";
    }
}

std::string snakeCase(std::string_view key) {
    std::string out;
    for (char c : key) {
        if (c >= 'A' && c <= 'Z') {
            if (!out.empty()) out += '_';
            out += char(c - 'A' + 'a');
        } else {
            out += c;
        }
    }
    return out;
}

JsonObject::JsonObject(const Json& json, std::string path, const std::string& source)
    : json_(json), path_(std::move(path)), source_(source) {
    if (!json_.is_object()) wrongType(json_, path_.empty() ? "the top level" : path_, "an object");
}

const Json* JsonObject::allow(const std::string& key) {
    known_.push_back(key);
    auto it = json_.find(key);
    return it == json_.end() ? nullptr : &*it;
}

void JsonObject::finish() const {
    for (auto it = json_.begin(); it != json_.end(); ++it) {
        const std::string& key = it.key();
        if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
        const std::string snake = snakeCase(key);
        if (snake != key && std::find(known_.begin(), known_.end(), snake) != known_.end())
            throw Error(msg(source_, ": unknown key ", keyPath(key), ": keys are snake_case, use ",
                            keyPath(snake)));
        // The nearest allowed key first when it is a likely typo (at most a
        // third of its letters differ), then every allowed key.
        const std::string* nearest = nullptr;
        size_t best = std::numeric_limits<size_t>::max();
        for (const std::string& k : known_) {
            size_t d = editDistance(key, k);
            if (d < best) best = d, nearest = &k;
        }
        std::string names;
        for (const std::string& k : known_) names += msg(names.empty() ? "" : ", ", k);
        std::string hint = nearest && best * 3 <= std::max<size_t>(key.size(), 3)
                               ? msg("did you mean ", *nearest, "? ")
                               : std::string();
        throw Error(msg(source_, ": unknown key ", keyPath(key), " (", hint,
                        "expected one of: ", names, ")"));
    }
}

void JsonObject::wrongType(const Json& value, const std::string& key, const char* expected) const {
    throw Error(msg(source_, ": ", key, ": expected ", expected, ", got ", jsonTypeName(value),
                    value.is_number() ? msg(" ", value.dump()) : std::string()));
}

void JsonObject::badValue(const std::string& key, const std::string& what) const {
    throw Error(msg(source_, ": ", key, ": ", what));
}

std::string JsonObject::keyPath(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
}

float JsonObject::toFloat(const Json& v, const std::string& key, const char* expected) const {
    if (!v.is_number()) wrongType(v, key, expected);
    double d = v.get<double>();
    // A document built in memory (not parsed text) may hold NaN or an infinity.
    if (!std::isfinite(d)) badValue(key, msg("expected a finite number, got ", d));
    if (std::abs(d) > double(std::numeric_limits<float>::max()))
        badValue(key, msg("number ", v.dump(), " is out of the float range"));
    return float(d);
}

int JsonObject::toInt(const Json& v, const std::string& key, const char* expected) const {
    if (!v.is_number()) wrongType(v, key, expected);
    if (v.is_number_unsigned()) {
        if (v.get<uint64_t>() > uint64_t(std::numeric_limits<int>::max()))
            badValue(key, msg("integer ", v.dump(), " is out of range"));
        return int(v.get<uint64_t>());
    }
    if (v.is_number_float()) {
        const double d = v.get<double>();
        if (d != std::floor(d)) wrongType(v, key, expected);
        if (d < double(std::numeric_limits<int>::min()) ||
            d > double(std::numeric_limits<int>::max()))
            badValue(key, msg("integer ", v.dump(), " is out of range"));
        return int(d);
    }
    const int64_t i = v.get<int64_t>();
    if (i < std::numeric_limits<int>::min() || i > std::numeric_limits<int>::max())
        badValue(key, msg("integer ", v.dump(), " is out of range"));
    return int(i);
}

uint64_t JsonObject::toUnsigned(const Json& v, const std::string& key) const {
    const char* expected = "an integer >= 0";
    if (!v.is_number()) wrongType(v, key, expected);
    if (v.is_number_unsigned()) return v.get<uint64_t>();
    if (v.is_number_integer()) {
        if (v.get<int64_t>() < 0) wrongType(v, key, expected);
        return uint64_t(v.get<int64_t>());
    }
    const double d = v.get<double>();
    if (d != std::floor(d) || d < 0.0) wrongType(v, key, expected);
    // Doubles from 2^63 on are beyond the integers JSON writers keep exact.
    if (d >= kInt64Limit) badValue(key, msg("integer ", v.dump(), " is out of range"));
    return uint64_t(d);
}

bool JsonObject::toBool(const Json& v, const std::string& key) const {
    if (!v.is_boolean()) wrongType(v, key, "true or false");
    return v.get<bool>();
}

std::string JsonObject::toString(const Json& v, const std::string& key) const {
    if (!v.is_string()) wrongType(v, key, "a string");
    return v.get<std::string>();
}

}  // namespace sierra::scene
