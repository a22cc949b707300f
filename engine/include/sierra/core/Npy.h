#pragma once
// NumPy .npy encoding (format version 1.0) of float32 and float16 arrays:
// the one writer behind heightfield exports, depth images, normal images and
// curvature fields.

#include <cstdint>
#include <span>
#include <vector>

namespace sierra {

// The bytes of a .npy file holding `values` as a little-endian float32 array
// of shape (rows, cols) in C order. Any float is stored as is, NaN included.
std::vector<uint8_t> encodeNpyFloat32(int rows, int cols, std::span<const float> values);

// The same for any shape (C order: the last index varies fastest), e.g.
// {rows, cols, 4} for a curvature field. Every extent > 0; values.size() is
// their product.
std::vector<uint8_t> encodeNpyFloat32(std::span<const int> shape, std::span<const float> values);
// The same as little-endian IEEE half floats ('<f2'), each value rounded to
// the nearest half (ties to even; beyond 65504 infinity; NaN stays NaN).
std::vector<uint8_t> encodeNpyFloat16(std::span<const int> shape, std::span<const float> values);
// One float as an IEEE 754 binary16 bit pattern, rounded as above.
uint16_t floatToHalf(float value);

}  // namespace sierra
