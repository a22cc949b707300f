#include <sierra/core/Timer.h>

#include <algorithm>
#include <cmath>

namespace sierra {

double quantile(std::vector<double> samples, double q) {
    if (samples.empty()) return 0.0;
    std::sort(samples.begin(), samples.end());
    double pos = std::clamp(q, 0.0, 1.0) * double(samples.size() - 1);
    size_t lo = size_t(std::floor(pos));
    size_t hi = std::min(lo + 1, samples.size() - 1);
    double t = pos - double(lo);
    return samples[lo] * (1.0 - t) + samples[hi] * t;
}

}  // namespace sierra
