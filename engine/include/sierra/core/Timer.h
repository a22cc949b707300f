#pragma once
// Wall-clock timing and simple order statistics for benchmark reports.

#include <chrono>
#include <vector>

namespace sierra {

class Stopwatch {
  public:
    Stopwatch() : start_(Clock::now()) {}
    void restart() { start_ = Clock::now(); }
    // Milliseconds since construction or the last restart().
    double ms() const {
        return std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
    }

  private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point start_;
};

// The q-quantile (0..1) of samples by linear interpolation; 0 for no samples.
double quantile(std::vector<double> samples, double q);
inline double median(const std::vector<double>& samples) {
    return quantile(samples, 0.5);
}

}  // namespace sierra
