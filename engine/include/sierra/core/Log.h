#pragma once
// Logging to stderr with a level filter. SIERRA_LOG=debug|info|warn|error
// sets the level at start-up (default info).

#include <sierra/core/Error.h>

#include <string>

namespace sierra::log {

enum class Level { Debug = 0, Info = 1, Warn = 2, Error = 3, Off = 4 };

void setLevel(Level level);
Level level();
void write(Level level, const std::string& text);

template <typename... Args>
void debug(const Args&... args) {
    if (level() <= Level::Debug) write(Level::Debug, msg(args...));
}
template <typename... Args>
void info(const Args&... args) {
    if (level() <= Level::Info) write(Level::Info, msg(args...));
}
template <typename... Args>
void warn(const Args&... args) {
    if (level() <= Level::Warn) write(Level::Warn, msg(args...));
}
template <typename... Args>
void error(const Args&... args) {
    if (level() <= Level::Error) write(Level::Error, msg(args...));
}

}  // namespace sierra::log
