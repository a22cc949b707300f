#pragma once
// Progress of long work on stderr. On a terminal one line is rewritten in place
// (carriage return); redirected to a file or a pipe, plain lines are written,
// at most one per tenth of the work (and the last), so a log stays readable.

#include <cstdint>
#include <cstdio>
#include <string>

namespace sierra {

class Progress {
  public:
    // `what`: a short label ("frames"); `total`: the number of steps, > 0.
    // `out` defaults to stderr; `terminal` defaults to isatty(out).
    Progress(std::string what, int64_t total, std::FILE* out = nullptr, int terminalOverride = -1);
    // Step `done` (1..total) finished; `detail` is appended to the line.
    void update(int64_t done, const std::string& detail = {});
    // Ends the line on a terminal; nothing otherwise.
    void finish();
    bool terminal() const { return terminal_; }

  private:
    std::string what_;
    int64_t total_;
    std::FILE* out_;
    bool terminal_;
    int64_t lastDecile_ = -1;
    bool open_ = false;
};

// `value` with `decimals` digits after the point, never in scientific notation:
// log lines such as "draw (GL timer) 0.031 ms".
std::string fixed(double value, int decimals = 3);

}  // namespace sierra
