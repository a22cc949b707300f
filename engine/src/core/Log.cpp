#include <sierra/core/Log.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace sierra::log {
namespace {

Level levelFromEnvironment() {
    const char* env = std::getenv("SIERRA_LOG");
    if (!env) return Level::Info;
    if (!std::strcmp(env, "debug")) return Level::Debug;
    if (!std::strcmp(env, "warn")) return Level::Warn;
    if (!std::strcmp(env, "error")) return Level::Error;
    if (!std::strcmp(env, "off")) return Level::Off;
    return Level::Info;
}

std::atomic<Level>& currentLevel() {
    static std::atomic<Level> level{levelFromEnvironment()};
    return level;
}

const char* tag(Level level) {
    switch (level) {
        case Level::Debug:
            return "debug";
        case Level::Info:
            return "info";
        case Level::Warn:
            return "warning";
        case Level::Error:
            return "error";
        default:
            return "";
    }
}

}  // namespace

void setLevel(Level level) {
    currentLevel() = level;
}
Level level() {
    return currentLevel();
}

void write(Level level, const std::string& text) {
    static std::mutex mutex;
    std::lock_guard lock(mutex);
    std::fprintf(stderr, "sierra %s: %s\n", tag(level), text.c_str());
}

}  // namespace sierra::log
