#include <sierra/core/Npy.h>

#include <sierra/core/Error.h>

#include <algorithm>
#include <bit>

namespace sierra {

std::vector<uint8_t> encodeNpyFloat32(int rows, int cols, std::span<const float> values) {
    const int shape[] = {rows, cols};
    return encodeNpyFloat32(shape, values);
}

std::vector<uint8_t> encodeNpyFloat32(std::span<const int> shape, std::span<const float> values) {
    std::string dims;  // "2, 3" or, for one dimension, "2," as Python writes a 1-tuple
    size_t count = 1;
    bool positive = !shape.empty();
    for (int extent : shape) {
        positive = positive && extent > 0;
        count *= size_t(std::max(extent, 0));
        dims += dims.empty() ? msg(extent) : msg(", ", extent);
    }
    if (shape.size() == 1) dims += ",";
    std::string extents;
    for (int extent : shape) extents += extents.empty() ? msg(extent) : msg("x", extent);
    SIERRA_CHECK(positive && values.size() == count, "a .npy array of ",
                 extents.empty() ? "no shape" : extents, " needs ", count, " values, got ",
                 values.size());
    std::string header = msg("{'descr': '<f4', 'fortran_order': False, 'shape': (", dims, "), }");
    // Pad with spaces so the data starts on a 64-byte boundary, as numpy does.
    const size_t unpadded = 10 + header.size() + 1;
    header.append((64 - unpadded % 64) % 64, ' ');
    header.push_back('\n');
    std::vector<uint8_t> bytes;
    bytes.reserve(10 + header.size() + values.size() * 4);
    for (uint8_t b :
         {uint8_t(0x93), uint8_t('N'), uint8_t('U'), uint8_t('M'), uint8_t('P'), uint8_t('Y'),
          uint8_t(1), uint8_t(0), uint8_t(header.size()), uint8_t(header.size() >> 8)})
        bytes.push_back(b);
    for (char c : header) bytes.push_back(uint8_t(c));
    for (float v : values) {
        uint32_t u = std::bit_cast<uint32_t>(v);
        for (int b = 0; b < 4; ++b) bytes.push_back(uint8_t(u >> (8 * b)));
    }
    return bytes;
}

}  // namespace sierra
