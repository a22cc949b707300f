#include <sierra/core/Error.h>

#include <sierra/core/Log.h>

namespace sierra::detail {

void throwCheckFailed(const char* condition, const char* file, int line,
                      const std::string& message) {
    // The user sees the message; where the check sits is for developers.
    log::debug("check '", condition, "' failed at ", file, ":", line);
    if (message.empty())
        throw Error(msg("internal check failed: ", condition, " at ", file, ":", line));
    throw Error(message);
}

}  // namespace sierra::detail
