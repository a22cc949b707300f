#include <sierra/terrain/FileIO.h>

#include <sierra/core/Error.h>

#include <algorithm>
#include <array>

namespace sierra::terrain {
namespace {

// CRC-32 (ISO 3309, polynomial 0xedb88320) as PNG chunks need it.
uint32_t crc32(const uint8_t* data, size_t size, uint32_t crc = 0) {
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> t{};
        for (uint32_t n = 0; n < 256; ++n) {
            uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    crc = ~crc;
    for (size_t k = 0; k < size; ++k) crc = table[(crc ^ data[k]) & 0xff] ^ (crc >> 8);
    return ~crc;
}

void putBe32(std::vector<uint8_t>& out, uint32_t v) {
    out.push_back(uint8_t(v >> 24));
    out.push_back(uint8_t(v >> 16));
    out.push_back(uint8_t(v >> 8));
    out.push_back(uint8_t(v));
}

void putChunk(std::vector<uint8_t>& out, const char type[4], const uint8_t* data, size_t size) {
    putBe32(out, uint32_t(size));
    size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data, data + size);
    putBe32(out, crc32(out.data() + start, size + 4));
}

}  // namespace

std::vector<uint8_t> encodePngGrey16(int width, int height, std::span<const uint16_t> samples) {
    SIERRA_CHECK(width > 0 && height > 0 && samples.size() == size_t(width) * size_t(height),
                 "encodePngGrey16: ", samples.size(), " samples for a ", width, "x", height,
                 " image; expected width * height > 0");
    // Filtered image data: per row a filter byte (0 = none), then big-endian samples.
    const size_t rowBytes = 1 + size_t(width) * 2;
    std::vector<uint8_t> raw(rowBytes * height);
    for (int j = 0; j < height; ++j) {
        uint8_t* row = raw.data() + rowBytes * j;
        row[0] = 0;
        for (int i = 0; i < width; ++i) {
            uint16_t v = samples[size_t(j) * width + i];
            row[1 + 2 * i] = uint8_t(v >> 8);
            row[2 + 2 * i] = uint8_t(v);
        }
    }

    // zlib stream: header (deflate, 32K window, no dictionary, check bits ok),
    // stored blocks of at most 65535 bytes, Adler-32 of the raw data.
    std::vector<uint8_t> zlib = {0x78, 0x01};
    zlib.reserve(raw.size() + raw.size() / 65535 * 5 + 16);
    size_t pos = 0;
    do {
        size_t len = std::min<size_t>(65535, raw.size() - pos);
        bool last = pos + len == raw.size();
        zlib.push_back(last ? 1 : 0);  // BFINAL, BTYPE = 00 (stored)
        zlib.push_back(uint8_t(len));
        zlib.push_back(uint8_t(len >> 8));
        zlib.push_back(uint8_t(~len));
        zlib.push_back(uint8_t(~len >> 8));
        zlib.insert(zlib.end(), raw.begin() + pos, raw.begin() + pos + len);
        pos += len;
    } while (pos < raw.size());
    uint32_t a = 1, b = 0;
    for (size_t k = 0; k < raw.size();) {
        // 5552 bytes is the most that cannot overflow b before the modulo.
        size_t end = std::min(raw.size(), k + 5552);
        for (; k < end; ++k) {
            a += raw[k];
            b += a;
        }
        a %= 65521;
        b %= 65521;
    }
    putBe32(zlib, (b << 16) | a);

    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<uint8_t> ihdr;
    putBe32(ihdr, uint32_t(width));
    putBe32(ihdr, uint32_t(height));
    ihdr.insert(ihdr.end(), {16, 0, 0, 0, 0});  // depth 16, grey, deflate, no filter, no interlace
    putChunk(png, "IHDR", ihdr.data(), ihdr.size());
    // IDAT chunks of at most 1 MiB: a chunk's length must stay below 2^31.
    constexpr size_t kIdatBytes = size_t(1) << 20;
    for (size_t at = 0; at < zlib.size(); at += kIdatBytes)
        putChunk(png, "IDAT", zlib.data() + at, std::min(kIdatBytes, zlib.size() - at));
    putChunk(png, "IEND", nullptr, 0);
    return png;
}

}  // namespace sierra::terrain
