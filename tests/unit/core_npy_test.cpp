// The .npy encoder: the header numpy reads (shape, dtype, 64-byte alignment)
// and the little-endian payload, for 2-D and 3-D shapes, and its checks.

#include <sierra/core/Error.h>
#include <sierra/core/Npy.h>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

using namespace sierra;

namespace {

// The header text between the 10-byte preamble and the payload.
std::string header(const std::vector<uint8_t>& bytes) {
    EXPECT_GE(bytes.size(), 10u);
    const size_t length = size_t(bytes[8]) | size_t(bytes[9]) << 8;
    return std::string(bytes.begin() + 10, bytes.begin() + 10 + std::ptrdiff_t(length));
}

float payload(const std::vector<uint8_t>& bytes, size_t index) {
    const size_t start = 10 + header(bytes).size() + index * 4;
    uint32_t u = 0;
    for (int b = 0; b < 4; ++b) u |= uint32_t(bytes[start + size_t(b)]) << (8 * b);
    return std::bit_cast<float>(u);
}

TEST(Npy, ThreeDimensionalShapeAndValuesInCOrder) {
    const int shape[] = {2, 3, 4};
    std::vector<float> values(24);
    for (size_t k = 0; k < values.size(); ++k) values[k] = float(k) * 0.5f - 3.0f;
    values[5] = std::numeric_limits<float>::quiet_NaN();
    const std::vector<uint8_t> bytes = encodeNpyFloat32(shape, values);
    ASSERT_EQ(std::memcmp(bytes.data(), "\x93NUMPY\x01\x00", 8), 0);
    const std::string h = header(bytes);
    EXPECT_NE(h.find("'shape': (2, 3, 4)"), std::string::npos) << h;
    EXPECT_NE(h.find("'descr': '<f4'"), std::string::npos) << h;
    EXPECT_EQ((10 + h.size()) % 64, 0u) << "payload not 64-byte aligned";
    EXPECT_EQ(h.back(), '\n');
    EXPECT_EQ(bytes.size(), 10 + h.size() + values.size() * 4);
    for (size_t k = 0; k < values.size(); ++k) {
        if (k == 5)
            EXPECT_TRUE(std::isnan(payload(bytes, k)));
        else
            EXPECT_EQ(payload(bytes, k), values[k]) << k;
    }
}

TEST(Npy, TwoDimensionalFormIsTheSameEncoding) {
    std::vector<float> values{1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f};
    const int shape[] = {3, 2};
    EXPECT_EQ(encodeNpyFloat32(3, 2, values), encodeNpyFloat32(shape, values));
    EXPECT_NE(header(encodeNpyFloat32(3, 2, values)).find("'shape': (3, 2)"), std::string::npos);
}

TEST(Npy, OneDimensionIsAPythonOneTuple) {
    const int shape[] = {3};
    std::vector<float> values{1.0f, 2.0f, 3.0f};
    EXPECT_NE(header(encodeNpyFloat32(shape, values)).find("'shape': (3,)"), std::string::npos);
}

TEST(Npy, RejectsAWrongValueCountOrAnEmptyExtent) {
    const int shape[] = {2, 3, 4};
    std::vector<float> values(23);
    try {
        encodeNpyFloat32(shape, values);
        FAIL() << "23 values for 2x3x4 were accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("2x3x4 needs 24 values, got 23"), std::string::npos)
            << e.what();
    }
    const int zero[] = {2, 0, 4};
    EXPECT_THROW(encodeNpyFloat32(zero, std::vector<float>{}), Error);
}

TEST(Npy, HalfFloatsRoundToNearestEven) {
    EXPECT_EQ(floatToHalf(1.0f), 0x3c00);
    EXPECT_EQ(floatToHalf(-2.0f), 0xc000);
    EXPECT_EQ(floatToHalf(0.1f), 0x2e66);                   // 0.0999756
    EXPECT_EQ(floatToHalf(65504.0f), 0x7bff);               // the largest half
    EXPECT_EQ(floatToHalf(65520.0f), 0x7c00);               // halfway to the next: infinity
    EXPECT_EQ(floatToHalf(2049.0f), 0x6800);                // a tie rounds to the even 2048
    EXPECT_EQ(floatToHalf(2051.0f), 0x6802);                // ... and to the even 2052
    EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -24)), 0x0001);  // the smallest subnormal
    EXPECT_EQ(floatToHalf(std::ldexp(3.0f, -16)), 0x0300);  // a subnormal with bits
    EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -26)), 0x0000);  // underflows to zero
    EXPECT_EQ(floatToHalf(-std::numeric_limits<float>::infinity()), 0xfc00);
    const uint16_t nan = floatToHalf(std::numeric_limits<float>::quiet_NaN());
    EXPECT_EQ(nan & 0x7c00, 0x7c00);
    EXPECT_NE(nan & 0x3ff, 0);
}

TEST(Npy, Float16ArrayHeaderAndPayload) {
    const int shape[] = {2, 1, 3};
    const std::vector<float> values = {1.0f, -2.0f,    0.5f,
                                       0.0f, 65504.0f, std::numeric_limits<float>::quiet_NaN()};
    const std::vector<uint8_t> bytes = encodeNpyFloat16(shape, values);
    const std::string h = header(bytes);
    EXPECT_NE(h.find("'descr': '<f2'"), std::string::npos);
    EXPECT_NE(h.find("'shape': (2, 1, 3)"), std::string::npos);
    EXPECT_EQ((10 + h.size()) % 64, 0u);
    ASSERT_EQ(bytes.size(), 10 + h.size() + 2 * values.size());
    const size_t start = 10 + h.size();
    auto half = [&](size_t k) {
        return uint16_t(bytes[start + 2 * k] | bytes[start + 2 * k + 1] << 8);
    };
    EXPECT_EQ(half(0), 0x3c00);
    EXPECT_EQ(half(1), 0xc000);
    EXPECT_EQ(half(2), 0x3800);
    EXPECT_EQ(half(3), 0x0000);
    EXPECT_EQ(half(4), 0x7bff);
    EXPECT_GT(half(5) & 0x3ff, 0);
    EXPECT_THROW(encodeNpyFloat16(shape, std::vector<float>(5)), Error);
}

}  // namespace
