#include <sierra/core/Npy.h>

#include <sierra/core/Error.h>

#include <bit>

namespace sierra {

std::vector<uint8_t> encodeNpyFloat32(int rows, int cols, std::span<const float> values) {
    SIERRA_CHECK(rows > 0 && cols > 0 && values.size() == size_t(rows) * size_t(cols),
                 "a .npy array of ", rows, "x", cols, " needs ", int64_t(rows) * cols, " values, got ",
                 values.size());
    std::string header = msg("{'descr': '<f4', 'fortran_order': False, 'shape': (", rows, ", ", cols, "), }");
    // Pad with spaces so the data starts on a 64-byte boundary, as numpy does.
    const size_t unpadded = 10 + header.size() + 1;
    header.append((64 - unpadded % 64) % 64, ' ');
    header.push_back('\n');
    std::vector<uint8_t> bytes = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, uint8_t(header.size()),
                                  uint8_t(header.size() >> 8)};
    bytes.insert(bytes.end(), header.begin(), header.end());
    bytes.reserve(bytes.size() + values.size() * 4);
    for (float v : values) {
        uint32_t u = std::bit_cast<uint32_t>(v);
        for (int b = 0; b < 4; ++b) bytes.push_back(uint8_t(u >> (8 * b)));
    }
    return bytes;
}

}  // namespace sierra
