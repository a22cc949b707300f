#pragma once
// Errors in Sierra: one exception type whose message says what failed and why,
// and a check macro for preconditions that stays on in release builds.

#include <sstream>
#include <stdexcept>
#include <string>

namespace sierra {

// Thrown by every module for bad input and failed resources. what() is one
// line meant for the user: the file or call, what is wrong, what would be right.
class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

namespace detail {
[[noreturn]] void throwCheckFailed(const char* condition, const char* file, int line,
                                   const std::string& message);

// Concatenates any streamable values into one string.
template <typename... Args>
std::string concat(const Args&... args) {
    std::ostringstream out;
    (out << ... << args);
    return out.str();
}
}  // namespace detail

// Builds a message from streamable parts: sierra::msg("bad size ", w, "x", h).
template <typename... Args>
std::string msg(const Args&... args) {
    return detail::concat(args...);
}

}  // namespace sierra

// SIERRA_CHECK(cond, parts...): throws sierra::Error naming the condition when
// cond is false. Active in every build type: a violated precondition is a bug
// or bad input, never something to run past.
#define SIERRA_CHECK(cond, ...)                                             \
    do {                                                                    \
        if (!(cond)) [[unlikely]]                                           \
            ::sierra::detail::throwCheckFailed(#cond, __FILE__, __LINE__,   \
                                               ::sierra::msg(__VA_ARGS__)); \
    } while (0)
