// docs/scene.md from the option table (OptionTable.h): the hand-written text
// of docs/scene.md.in with each "@table PART@" line replaced by that part's
// keys.
#include <sierra/scene/OptionTable.h>

#include <sstream>

namespace sierra::scene {
namespace {

// A table cell: '|' would end it.
std::string cell(const std::string& text) {
    std::string out;
    for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

std::string code(const std::string& text) {
    return "`" + text + "`";
}

std::string defaultText(const Json& value) {
    return value.is_string() ? code(value.dump()) : value.dump();
}

// The option column: the entry's flag and words, or the options that set a
// file-only key.
std::string optionText(const OptionEntry& e) {
    if (e.flag.empty()) {
        std::string out;
        std::istringstream in(e.docOption);
        for (std::string option; std::getline(in, option, ',');) {
            if (option.starts_with(" ")) option.erase(0, 1);
            out += (out.empty() ? "" : ", ") + code(option);
        }
        return out;
    }
    return code(e.words.empty() ? e.flag : e.flag + " " + e.words);
}

std::string meaning(const OptionEntry& e) {
    if (!e.doc.empty()) return e.doc;
    std::string text = e.help;
    if (!text.empty() && text[0] >= 'A' && text[0] <= 'Z' &&
        !(text.size() > 1 && text[1] >= 'A' && text[1] <= 'Z'))
        text[0] = char(text[0] - 'A' + 'a');
    return text;
}

std::string partTable(const std::string& part) {
    const Scene defaults;
    std::string out = "| key | type | default | option | meaning |\n|---|---|---|---|---|\n";
    for (const OptionEntry& e : optionTable()) {
        if (!e.key.starts_with(part + ".")) continue;
        out += "| " + code(e.key.substr(part.size() + 1)) + " | " + cell(e.type) + " | " +
               cell(defaultText(e.toJson(defaults))) + " | " + cell(optionText(e)) + " | " +
               cell(meaning(e)) + " |\n";
    }
    return out;
}

}  // namespace

std::string sceneDocsMarkdown(const std::string& templateText) {
    std::string out;
    std::istringstream in(templateText);
    for (std::string line; std::getline(in, line);) {
        if (line.starts_with("@table ") && line.ends_with("@"))
            out += partTable(line.substr(7, line.size() - 8));
        else
            out += line + "\n";
    }
    return out;
}

}  // namespace sierra::scene
