#include <sierra/core/Npy.h>

#include <sierra/core/Error.h>

#include <algorithm>
#include <bit>

namespace sierra {

std::vector<uint8_t> encodeNpyFloat32(int rows, int cols, std::span<const float> values) {
    const int shape[] = {rows, cols};
    return encodeNpyFloat32(shape, values);
}

namespace {

// The .npy header and the 10 bytes before it for an array of `descr` values
// of `shape`, checking that `count` values fill it.
std::vector<uint8_t> npyHeader(const char* descr, std::span<const int> shape, size_t count,
                               size_t valueBytes) {
    std::string dims;  // "2, 3" or, for one dimension, "2," as Python writes a 1-tuple
    size_t expected = 1;
    bool positive = !shape.empty();
    for (int extent : shape) {
        positive = positive && extent > 0;
        expected *= size_t(std::max(extent, 0));
        dims += dims.empty() ? msg(extent) : msg(", ", extent);
    }
    if (shape.size() == 1) dims += ",";
    std::string extents;
    for (int extent : shape) extents += extents.empty() ? msg(extent) : msg("x", extent);
    SIERRA_CHECK(positive && count == expected, "a .npy array of ",
                 extents.empty() ? "no shape" : extents, " needs ", expected, " values, got ",
                 count);
    std::string header =
        msg("{'descr': '", descr, "', 'fortran_order': False, 'shape': (", dims, "), }");
    // Pad with spaces so the data starts on a 64-byte boundary, as numpy does.
    const size_t unpadded = 10 + header.size() + 1;
    header.append((64 - unpadded % 64) % 64, ' ');
    header.push_back('\n');
    std::vector<uint8_t> bytes;
    bytes.reserve(10 + header.size() + count * valueBytes);
    for (uint8_t b :
         {uint8_t(0x93), uint8_t('N'), uint8_t('U'), uint8_t('M'), uint8_t('P'), uint8_t('Y'),
          uint8_t(1), uint8_t(0), uint8_t(header.size()), uint8_t(header.size() >> 8)})
        bytes.push_back(b);
    for (char c : header) bytes.push_back(uint8_t(c));
    return bytes;
}

}  // namespace

std::vector<uint8_t> encodeNpyFloat32(std::span<const int> shape, std::span<const float> values) {
    std::vector<uint8_t> bytes = npyHeader("<f4", shape, values.size(), 4);
    for (float v : values) {
        uint32_t u = std::bit_cast<uint32_t>(v);
        for (int b = 0; b < 4; ++b) bytes.push_back(uint8_t(u >> (8 * b)));
    }
    return bytes;
}

uint16_t floatToHalf(float value) {
    const uint32_t u = std::bit_cast<uint32_t>(value);
    const uint16_t sign = uint16_t((u >> 16) & 0x8000u);
    const uint32_t exponent = (u >> 23) & 0xffu;
    uint32_t mantissa = u & 0x7fffffu;
    if (exponent == 0xffu)  // infinity, or NaN kept quiet
        return uint16_t(sign | 0x7c00u | (mantissa ? 0x200u | (mantissa >> 13) : 0u));
    const int e = int(exponent) - 127 + 15;
    if (e >= 31) return uint16_t(sign | 0x7c00u);  // too large: infinity
    if (e <= 0) {
        // A subnormal half (or zero): the implicit bit shifted into the mantissa.
        if (e < -10) return sign;
        mantissa |= 0x800000u;
        const int shift = 14 - e;
        uint32_t half = mantissa >> shift;
        const uint32_t rest = mantissa & ((1u << shift) - 1u), halfway = 1u << (shift - 1);
        if (rest > halfway || (rest == halfway && (half & 1u))) ++half;
        return uint16_t(sign | half);
    }
    uint32_t half = (uint32_t(e) << 10) | (mantissa >> 13);
    const uint32_t rest = mantissa & 0x1fffu;
    // Round to nearest, ties to even; a carry into the exponent is right
    // (up to infinity).
    if (rest > 0x1000u || (rest == 0x1000u && (half & 1u))) ++half;
    return uint16_t(sign | half);
}

std::vector<uint8_t> encodeNpyFloat16(std::span<const int> shape, std::span<const float> values) {
    std::vector<uint8_t> bytes = npyHeader("<f2", shape, values.size(), 2);
    for (float v : values) {
        const uint16_t h = floatToHalf(v);
        bytes.push_back(uint8_t(h));
        bytes.push_back(uint8_t(h >> 8));
    }
    return bytes;
}

}  // namespace sierra
