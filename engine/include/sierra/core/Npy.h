#pragma once
// NumPy .npy encoding (format version 1.0) of 2-D float32 arrays: the one
// writer behind heightfield exports and depth images.

#include <cstdint>
#include <span>
#include <vector>

namespace sierra {

// The bytes of a .npy file holding `values` as a little-endian float32 array
// of shape (rows, cols) in C order. Any float is stored as is, NaN included.
std::vector<uint8_t> encodeNpyFloat32(int rows, int cols, std::span<const float> values);

}  // namespace sierra
