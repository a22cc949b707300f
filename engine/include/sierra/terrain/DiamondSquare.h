#pragma once
// Diamond-square fractal terrain on a (2^n+1)^2 grid.

#include <sierra/terrain/Heightfield.h>

#include <cstdint>
#include <optional>

namespace sierra::terrain {

// The largest roughness: heights stay far inside float range at any size and
// Hurst exponent (each of at most 16 levels adds at most twice roughness). Larger
// values change nothing but the units: the picture's relief comes from the
// vertical scale.
constexpr float kMaxRoughness = 1e6f;

struct DiamondSquareDesc {
    int size = 513;          // samples per side, must be 2^n + 1 (3..16385)
    uint64_t seed = 1;       // same seed, same grid (on every platform and thread count)
    float roughness = 1.0f;  // amplitude factor of every random offset, in (0, kMaxRoughness]
    int threads = 0;         // worker threads, 0 = sierra::defaultThreadCount()
    // Hurst exponent H in (0, 2]: the offset range of a node is
    // roughness * dist^H, dist its distance to its parents in the unit domain, so
    // every level's range is 2^-H times the level above (smaller H: rougher).
    // Absent (std::nullopt, the default): the errata scaling below, which is the
    // H = 1 case computed without pow(). Finite values only.
    std::optional<float> hurst;
};

// With unit domain [0,1]^2 and 1/d the spacing of the nodes a step creates,
// the four corners are uniform in [-roughness, roughness], diamond-step nodes
// (square centres, diagonal to their 4 parents) are offset from their parents'
// mean uniformly within +-roughness * sqrt(2)/d and square-step nodes (edge
// midpoints, orthogonal to their 4 parents, 3 on the border) within
// +-roughness * 1/d (the corrected scaling of the "Fractal Errata"). With a
// Hurst exponent H these ranges become roughness * (sqrt(2)/d)^H and
// roughness * (1/d)^H.
// Heights are left unnormalised (typically within a few times roughness);
// spacing and vertical scale are 1. Each node's random number is a hash of
// (seed, node index) (splitmix64), so the grid does not depend on threads or on
// the standard library. Throws sierra::Error for a bad size or roughness.
Heightfield generateDiamondSquare(const DiamondSquareDesc& desc);

}  // namespace sierra::terrain
