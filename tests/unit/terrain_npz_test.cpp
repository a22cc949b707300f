// NumPy .npz archives built byte by byte: a stored member decodes like the
// .npy it holds, and malformed archives (found by fuzzing among them) are
// refused with one sierra::Error, never undefined behaviour.

#include <sierra/core/Error.h>
#include <sierra/terrain/HeightfieldIO.h>

#include <gtest/gtest.h>
#include <zlib.h>

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

namespace sierra::terrain {
namespace {

using Bytes = std::vector<uint8_t>;

void put16(Bytes& b, uint32_t v) {
    b.push_back(uint8_t(v)), b.push_back(uint8_t(v >> 8));
}
void put32(Bytes& b, uint32_t v) {
    put16(b, v & 0xffffu), put16(b, v >> 16);
}

// A float32 .npy of `rows` x `cols` values 0, 1, 2, ...
Bytes npy(int rows, int cols) {
    Bytes out = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0};
    std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" +
                         std::to_string(rows) + ", " + std::to_string(cols) + "), }";
    header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ');
    header.push_back('\n');
    put16(out, uint32_t(header.size()));
    out.insert(out.end(), header.begin(), header.end());
    for (int k = 0; k < rows * cols; ++k) put32(out, std::bit_cast<uint32_t>(float(k)));
    return out;
}

// A zip archive of stored (uncompressed) members; `sizes` overrides the size
// the central directory declares for a member (-1: the true size).
Bytes zipOf(const std::vector<std::pair<std::string, Bytes>>& members,
            const std::vector<int64_t>& sizes = {}) {
    Bytes zip, central;
    for (size_t m = 0; m < members.size(); ++m) {
        const auto& [name, data] = members[m];
        const uint32_t crc = uint32_t(crc32(0, data.data(), uInt(data.size())));
        const uint32_t size =
            m < sizes.size() && sizes[m] >= 0 ? uint32_t(sizes[m]) : uint32_t(data.size());
        const uint32_t offset = uint32_t(zip.size());
        put32(zip, 0x04034b50u), put16(zip, 20), put16(zip, 0), put16(zip, 0), put32(zip, 0);
        put32(zip, crc), put32(zip, size), put32(zip, size), put16(zip, uint32_t(name.size())),
            put16(zip, 0);
        zip.insert(zip.end(), name.begin(), name.end());
        zip.insert(zip.end(), data.begin(), data.end());
        put32(central, 0x02014b50u), put16(central, 20), put16(central, 20), put16(central, 0),
            put16(central, 0);
        put32(central, 0), put32(central, crc), put32(central, size), put32(central, size);
        put16(central, uint32_t(name.size())), put16(central, 0), put16(central, 0),
            put16(central, 0);
        put16(central, 0), put32(central, 0), put32(central, offset);
        central.insert(central.end(), name.begin(), name.end());
    }
    const uint32_t centralOffset = uint32_t(zip.size());
    zip.insert(zip.end(), central.begin(), central.end());
    put32(zip, 0x06054b50u), put16(zip, 0), put16(zip, 0), put16(zip, uint32_t(members.size()));
    put16(zip, uint32_t(members.size())), put32(zip, uint32_t(central.size())),
        put32(zip, centralOffset);
    put16(zip, 0);
    return zip;
}

std::string errorOf(const Bytes& bytes) {
    try {
        decodeHeightfield("t.npz", bytes);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(TerrainNpz, StoredMemberDecodesLikeItsNpy) {
    const Heightfield field = decodeHeightfield("t.npz", zipOf({{"elevation.npy", npy(2, 3)}}));
    ASSERT_EQ(field.width(), 3);
    ASSERT_EQ(field.height(), 2);
    EXPECT_EQ(field.at(2, 1), 5.0f);
}

TEST(TerrainNpz, TheFirstTwoDimensionalMemberIsTaken) {
    const Heightfield field =
        decodeHeightfield("t.npz", zipOf({{"a.npy", Bytes{}}, {"b.npy", npy(3, 2)}}));
    EXPECT_EQ(field.width(), 2);
    EXPECT_EQ(field.height(), 3);
}

// Found by scripts/fuzz.sh (npz): an empty stored member reached memcpy with a
// null destination. Now it is an empty member like any other.
TEST(TerrainNpz, EmptyMemberIsNotAnArray) {
    EXPECT_NE(errorOf(zipOf({{"elevation.npy", Bytes{}}})), "");
    // The fuzzer's own input, as it found it.
    const std::string hex =
        "504b03041400000000003543765d4fe9002a98000000980000000d000000656c65766174696f6e2e6e7079934e"
        "554d50"
        "59010076007b276465736372273a20273c6634272c2027666f727472616e5f6f72646572273a2046616c73652c"
        "202773"
        "68617065273a2028322c2033292c207d2020202020202020202020202020202020202020202020202020202020"
        "202020"
        "20202020202020202020202020202020202020202020202020200a000000000000803f00000040000040400000"
        "804000"
        "00a040504b010214031400000000003543765d4fe9020000000000000000000d00000000000000000000008001"
        "000000"
        "00656c65766174696f6e2e6e7079504b050600000000010001003b000000c30000000000";
    Bytes input;
    for (size_t k = 0; k + 1 < hex.size(); k += 2)
        input.push_back(uint8_t(std::stoi(hex.substr(k, 2), nullptr, 16)));
    EXPECT_NE(errorOf(input), "");
}

TEST(TerrainNpz, MalformedArchivesAreRefused) {
    const Bytes good = zipOf({{"elevation.npy", npy(2, 3)}});
    EXPECT_NE(errorOf(Bytes(good.begin(), good.begin() + good.size() / 2)), "");
    EXPECT_NE(errorOf(Bytes{'P', 'K', 5, 6}), "");
    EXPECT_NE(errorOf(Bytes{}), "");
    EXPECT_NE(errorOf(zipOf({{"x.txt", Bytes{'h', 'i'}}})), "");
    Bytes badLocal = good;
    badLocal[0] ^= 0xff;  // the local header's signature
    EXPECT_NE(errorOf(badLocal), "");
}

}  // namespace
}  // namespace sierra::terrain
