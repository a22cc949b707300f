#pragma once
// Directed rounding of a double to float, for the SBT's conservative bounds
// (radii that must still nest, key slacks that must still cover).

#include <cmath>
#include <limits>

namespace sierra::sbt {

// The smallest float >= x.
inline float roundUp(double x) {
    const float f = float(x);
    return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

// The largest float <= x.
inline float roundDown(double x) {
    const float f = float(x);
    return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

}  // namespace sierra::sbt
