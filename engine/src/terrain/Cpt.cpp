#include <sierra/terrain/Cpt.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>

namespace sierra::terrain {
namespace {

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::optional<double> number(const std::string& token) {
    if (token.empty()) return std::nullopt;
    char* end = nullptr;
    double v = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

struct LineError {
    std::string what;
};

uint8_t channel(const std::string& token) {
    auto v = number(token);
    if (!v || *v < 0.0 || *v > 255.0)
        throw LineError{msg("colour component '", token, "' is not a number in 0..255")};
    return uint8_t(std::lround(*v));
}

// Reads one colour starting at tokens[k]; advances k past it. "r g b" takes
// three tokens when the three are numbers and `allowTriple` (enough tokens
// remain for the rest of the line).
Rgb colour(const std::vector<std::string>& tokens, size_t& k, bool allowTriple) {
    if (k >= tokens.size()) throw LineError{"a colour is missing"};
    const std::string& t = tokens[k];
    if (t.size() == 7 && t[0] == '#') {
        auto hex = [&](int at) {
            std::string two = t.substr(size_t(at), 2);
            char* end = nullptr;
            long v = std::strtol(two.c_str(), &end, 16);
            if (end != two.c_str() + 2) throw LineError{msg("colour '", t, "' is not #rrggbb")};
            return uint8_t(v);
        };
        ++k;
        return {hex(1), hex(3), hex(5)};
    }
    if (t.find('/') != std::string::npos) {
        std::vector<std::string> parts;
        std::stringstream in(t);
        for (std::string p; std::getline(in, p, '/');) parts.push_back(p);
        if (parts.size() != 3) throw LineError{msg("colour '", t, "' is not r/g/b")};
        ++k;
        return {channel(parts[0]), channel(parts[1]), channel(parts[2])};
    }
    if (allowTriple && k + 2 < tokens.size() && number(tokens[k + 1]) && number(tokens[k + 2])) {
        Rgb c{channel(tokens[k]), channel(tokens[k + 1]), channel(tokens[k + 2])};
        k += 3;
        return c;
    }
    if (lower(t) == "black") return ++k, Rgb{0, 0, 0};
    if (lower(t) == "white") return ++k, Rgb{255, 255, 255};
    if (number(t)) {
        uint8_t g = channel(t);
        ++k;
        return {g, g, g};
    }
    throw LineError{msg("colour '", t, "' is not r g b, r/g/b, a grey value or #rrggbb")};
}

}  // namespace

ColourRamp CptTable::ramp(float lo, float hi) const {
    if (!(lo < hi)) lo = minHeight(), hi = maxHeight();
    if (!(lo < hi)) hi = lo + 1.0f;
    return ColourRamp(stops, lo, hi, outside);
}

CptTable parseCpt(const std::string& text, const std::string& name) {
    CptTable table;
    std::istringstream in(text);
    int lineNo = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNo;
        try {
            if (!line.empty() && line.back() == '\r') line.pop_back();
            const size_t hash = line.find('#');
            if (hash != std::string::npos) {
                std::string comment = lower(line.substr(hash + 1));
                const size_t model = comment.find("color_model");
                if (model != std::string::npos && hash == line.find_first_not_of(" \t")) {
                    const size_t eq = comment.find('=', model);
                    std::string value = eq == std::string::npos ? "" : comment.substr(eq + 1);
                    value.erase(0, value.find_first_not_of(" \t+"));
                    value.erase(value.find_last_not_of(" \t") + 1);
                    if (value != "rgb") {
                        for (char& ch : value)
                            ch = char(std::toupper(static_cast<unsigned char>(ch)));
                        throw LineError{
                            msg("colour model '", value, "' is not supported (only RGB)")};
                    }
                }
                // A '#' starting a token after the slice is part of "#rrggbb":
                // only a '#' at the start of the line or after white space and
                // not followed by 6 hex digits starts a comment.
                bool isHexColour =
                    hash + 7 <= line.size() &&
                    std::all_of(
                        line.begin() + long(hash) + 1, line.begin() + long(hash) + 7,
                        [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
                if (!isHexColour || hash == line.find_first_not_of(" \t")) line.erase(hash);
            }
            const size_t semi = line.find(';');  // ";label" annotations
            if (semi != std::string::npos) line.erase(semi);
            std::vector<std::string> tokens;
            std::istringstream words(line);
            for (std::string w; words >> w;) tokens.push_back(w);
            if (tokens.empty()) continue;
            const std::string key = tokens[0];
            if (key == "B" || key == "F" || key == "N") {
                size_t k = 1;
                if (tokens.size() == 2 && tokens[1] == "-") continue;  // "skip": keep clamping
                Rgb c = colour(tokens, k, true);
                if (k != tokens.size())
                    throw LineError{msg("unexpected '", tokens[k], "' after the ", key, " colour")};
                (key == "B"   ? table.outside.below
                 : key == "F" ? table.outside.above
                              : table.outside.noData) = c;
                continue;
            }
            auto z0 = number(key);
            if (!z0) throw LineError{msg("'", key, "' is neither a height nor B, F or N")};
            // "z0 r g b z1 r g b" has 8 tokens; "z0 c z1 c" 4 (+1 for L/U/B).
            const bool triple = tokens.size() >= 8;
            size_t k = 1;
            Rgb c0 = colour(tokens, k, triple);
            if (k >= tokens.size()) throw LineError{"the slice has no upper height"};
            auto z1 = number(tokens[k]);
            if (!z1) throw LineError{msg("upper height '", tokens[k], "' is not a number")};
            ++k;
            Rgb c1 = colour(tokens, k, triple);
            if (k < tokens.size() && (tokens[k] == "L" || tokens[k] == "U" || tokens[k] == "B"))
                ++k;
            if (k != tokens.size())
                throw LineError{msg("unexpected '", tokens[k], "' after the slice")};
            if (!(*z1 > *z0)) throw LineError{msg("slice ", *z0, " .. ", *z1, " does not ascend")};
            if (!table.stops.empty() && float(*z0) < table.stops.back().height)
                throw LineError{msg("slice starts at ", *z0,
                                    ", below the end of the previous slice (",
                                    table.stops.back().height, ")")};
            table.stops.push_back({float(*z0), c0});
            table.stops.push_back({float(*z1), c1});
        } catch (const LineError& e) {
            throw Error(msg(name, " line ", lineNo, ": ", e.what));
        }
    }
    if (table.stops.empty())
        throw Error(msg(name, ": no colour slices (lines 'z0 colour z1 colour')"));
    return table;
}

CptTable readCpt(const std::string& path) {
    std::vector<uint8_t> bytes = readFileBytes(path);
    return parseCpt(std::string(bytes.begin(), bytes.end()), path);
}

}  // namespace sierra::terrain
