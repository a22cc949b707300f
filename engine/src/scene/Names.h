#pragma once
// Enum names <-> values for the scene's command line and JSON form (internal).

#include <sierra/core/Error.h>

#include <string>
#include <utility>

namespace sierra::scene::detail {

// The value named `text`; throws sierra::Error naming `what` and every accepted name.
template <typename E, size_t N>
E parseName(const std::string& text, const std::string& what,
            const std::pair<const char*, E> (&names)[N]) {
    std::string accepted;
    for (const auto& [name, value] : names) {
        if (text == name) return value;
        accepted += msg(accepted.empty() ? "" : ", ", name);
    }
    throw Error(msg(what, ": '", text, "' is not one of ", accepted));
}

}  // namespace sierra::scene::detail
