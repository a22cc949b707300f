#include <sierra/core/Progress.h>

#include <sierra/core/Error.h>

#include <unistd.h>

#include <cmath>
#include <utility>

namespace sierra {

Progress::Progress(std::string what, int64_t total, std::FILE* out, int terminalOverride)
    : what_(std::move(what)), total_(total), out_(out ? out : stderr) {
    SIERRA_CHECK(total > 0, "progress of ", what_, " needs a positive total, got ", total);
    terminal_ = terminalOverride >= 0 ? terminalOverride != 0 : isatty(fileno(out_)) != 0;
}

void Progress::update(int64_t done, const std::string& detail) {
    std::string line = msg(what_, " ", done, "/", total_, detail.empty() ? "" : ": ", detail);
    if (terminal_) {
        std::fprintf(out_, "\r%s\033[K", line.c_str());
        open_ = true;
    } else {
        int64_t decile = done * 10 / total_;
        if (decile == lastDecile_ && done != total_) return;
        lastDecile_ = decile;
        std::fprintf(out_, "%s\n", line.c_str());
    }
    std::fflush(out_);
}

void Progress::finish() {
    if (terminal_ && open_) std::fprintf(out_, "\n");
    open_ = false;
    std::fflush(out_);
}

std::string fixed(double value, int decimals) {
    if (!std::isfinite(value)) return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    return buffer;
}

}  // namespace sierra
