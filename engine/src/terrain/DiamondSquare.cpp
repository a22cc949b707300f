#include <sierra/terrain/DiamondSquare.h>

#include <sierra/core/Error.h>
#include <sierra/core/Parallel.h>

#include <cmath>
#include <functional>

namespace sierra::terrain {
namespace {

constexpr int kMinSize = 3;
constexpr int kMaxSize = 16385;  // 2^14 + 1: 268M samples, 1 GiB of float32
// Below this many new nodes a step runs on the calling thread: starting
// threads would cost more than the work.
constexpr int64_t kParallelNodes = 1 << 16;

uint64_t splitmix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// Uniform in [-1, 1) from (seed, node index): 53 random bits, no std::
// distribution (whose output differs between standard libraries).
double uniformSigned(uint64_t seedHash, uint64_t node) {
    const uint64_t bits = splitmix64(seedHash ^ splitmix64(node));
    return double(bits >> 11) * 0x1.0p-52 - 1.0;
}

}  // namespace

Heightfield generateDiamondSquare(const DiamondSquareDesc& desc) {
    const int size = desc.size;
    SIERRA_CHECK(size >= kMinSize && size <= kMaxSize && ((size - 1) & (size - 2)) == 0,
                 "diamond-square size ", size, " is not 2^n + 1 in ", kMinSize, "..", kMaxSize,
                 " (e.g. 257, 513, 1025)");
    SIERRA_CHECK(
        std::isfinite(desc.roughness) && desc.roughness > 0.0f && desc.roughness <= kMaxRoughness,
        "diamond-square roughness ", desc.roughness, " must be in (0, ", kMaxRoughness,
        "] (default 1; it sets the height units only)");
    if (desc.hurst) {
        const float h = *desc.hurst;
        SIERRA_CHECK(std::isfinite(h) && h > 0.0f && h <= 2.0f, "diamond-square Hurst exponent ", h,
                     " must be in (0, 2] (1 = the default scaling, smaller = rougher)");
    }
    const uint64_t seedHash = splitmix64(desc.seed);
    const double roughness = desc.roughness;
    const int n = size - 1;

    Heightfield field(size, size);
    float* h = field.samples().data();
    auto at = [&](int i, int j) -> float& { return h[size_t(j) * size + i]; };
    auto offset = [&](int i, int j, double amplitude) {
        return float(amplitude * uniformSigned(seedHash, uint64_t(j) * size + i));
    };
    auto rows = [&](int rowCount, int64_t nodes, const std::function<void(int64_t)>& body) {
        parallelFor(0, rowCount, body, nodes < kParallelNodes ? 1 : desc.threads);
    };

    for (int j : {0, n})
        for (int i : {0, n}) at(i, j) = offset(i, j, roughness);

    for (int step = n; step > 1; step /= 2) {
        const int half = step / 2;
        // New nodes sit at multiples of half/n in the unit domain: 1/d = half/n.
        const double invD = double(half) / n;
        double diamondAmplitude = roughness * std::sqrt(2.0) * invD;
        double squareAmplitude = roughness * invD;
        if (desc.hurst) {
            const double h = *desc.hurst;
            diamondAmplitude = roughness * std::pow(std::sqrt(2.0) * invD, h);
            squareAmplitude = roughness * std::pow(invD, h);
        }
        const int cells = n / step;

        // Diamond step: the centre of each step x step square, from its 4 corners.
        rows(cells, int64_t(cells) * cells, [&](int64_t b) {
            const int y = half + int(b) * step;
            for (int x = half; x < n; x += step) {
                const float mean = (at(x - half, y - half) + at(x + half, y - half) +
                                    at(x - half, y + half) + at(x + half, y + half)) *
                                   0.25f;
                at(x, y) = mean + offset(x, y, diamondAmplitude);
            }
        });

        // Square step: edge midpoints, from the 4 (3 on the border) orthogonal
        // neighbours at distance half: corners and the diamond centres just made.
        rows(n / half + 1, int64_t(cells) * (2 * cells + 1) + cells, [&](int64_t r) {
            const int y = int(r) * half;
            for (int x = (r % 2 == 0) ? half : 0; x <= n; x += step) {
                float sum = 0.0f;
                int count = 0;
                if (x >= half) sum += at(x - half, y), ++count;
                if (x + half <= n) sum += at(x + half, y), ++count;
                if (y >= half) sum += at(x, y - half), ++count;
                if (y + half <= n) sum += at(x, y + half), ++count;
                at(x, y) = sum / float(count) + offset(x, y, squareAmplitude);
            }
        });
    }
    return field;
}

}  // namespace sierra::terrain
