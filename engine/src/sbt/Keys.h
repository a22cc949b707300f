#pragma once
// The 16-bit keys the refiner decides most splits from (private to the sbt
// module). Split keys (fixed mode, Refiner::splitKeys_) and view keys (view
// mode, Refiner::viewKeys_) are built by RefinerKeys.cpp and read by the walks
// (SplitKeyWalk.h, KeyedWalk.h); the encodings here are what both sides agree on.

#include <bit>
#include <cmath>
#include <cstdint>

namespace sierra::sbt {

// Split keys: the top 16 bits of a non-negative float's bit pattern (sign 0,
// 8 exponent bits, 7 mantissa bits: bfloat16 rounded towards zero). The map is
// monotone, so for e, eps >= 0:  key(e) > key(eps) implies e > eps and
// key(e) < key(eps) implies e <= eps; only equal keys need the exact float.
inline uint32_t floatKey(float x) {
    return std::bit_cast<uint32_t>(x) >> 16;
}

// View keys of lengths (errors and radii, >= 0): the float's bit pattern
// above a base, shifted right by kLengthKeyShift: 5 exponent and 11 mantissa
// bits, sixteen times finer than the top 16 bits of the float (on a rough
// 2049^2 fractal at tau = 1 the vertices the keys leave undecided per
// refinement fell from 6 738 of 1.1 M to 1 126 with 10 mantissa bits and to
// 660 with 11). The base lies 32 binades below the largest value keyed
// (lengthKeyBase): every value down to 2^-32 of the largest has a key (the
// radii of a 32769^2 grid span 15 binades); a value below the base's float
// gets key 0. The map is monotone: a value with key k lies in
// [float of (k << shift) + base, float of ((k + 1) << shift) + base), except
// with key 0, where it lies in [0, float of base): the walker's low bound
// subtracts the base's float (Walker::keyLowError).
inline constexpr int kLengthKeyShift = 12;
inline uint32_t lengthKeyBase(float largest) {
    const uint32_t top = std::bit_cast<uint32_t>(largest);
    constexpr uint32_t span = uint32_t(0xFFFF) << kLengthKeyShift;
    return top > span ? top - span : 0;
}
inline uint16_t lengthKey(float x, uint32_t base) {
    const uint32_t b = std::bit_cast<uint32_t>(x);
    return b < base ? 0 : uint16_t((b - base) >> kLengthKeyShift);
}

// The key epsilon is compared with, as a signed int so that "everything
// splits" (eps < 0) and "nothing splits" (eps NaN) need no special case in the
// hot loop: -1 is below every key, 0x10000 above every key.
inline int32_t epsilonKey(float eps) {
    if (std::isnan(eps)) return 0x10000;
    if (eps < 0.0f) return -1;
    return int32_t(floatKey(eps + 0.0f));  // + 0.0f: -0 becomes +0
}

}  // namespace sierra::sbt
