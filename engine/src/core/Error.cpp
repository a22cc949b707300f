#include <sierra/core/Error.h>

namespace sierra::detail {

void throwCheckFailed(const char* condition, const char* file, int line,
                      const std::string& message) {
    std::string text = message.empty() ? std::string("check failed") : message;
    throw Error(text + " [" + condition + " at " + file + ":" + std::to_string(line) + "]");
}

}  // namespace sierra::detail
