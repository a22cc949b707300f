#include <sierra/terrain/FileIO.h>

#include <sierra/core/Error.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <random>

namespace sierra::terrain {
namespace {

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// Eight hex digits unique within the process and very likely across processes,
// so two writers of the same path never share a temporary name.
std::string tempSuffix() {
    static std::atomic<uint64_t> counter{0};
    static const uint64_t base = [] {
        std::random_device device;
        return (uint64_t(device()) << 32) ^ uint64_t(device()) ^
               uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
    }();
    uint64_t x = base + 0x9e3779b97f4a7c15ull * ++counter;
    x ^= x >> 31;
    char text[9];
    std::snprintf(text, sizeof text, "%08x", unsigned(x & 0xffffffffu));
    return text;
}

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

std::vector<uint8_t> readFileBytes(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error(msg("cannot open ", path, ": Is a directory; expected a file"));
    FilePtr file(std::fopen(path.c_str(), "rb"));
    if (!file) throw Error(msg("cannot open ", path, ": ", std::strerror(errno)));
    std::vector<uint8_t> bytes;
    std::array<uint8_t, 1 << 16> buffer;
    for (;;) {
        size_t n = std::fread(buffer.data(), 1, buffer.size(), file.get());
        bytes.insert(bytes.end(), buffer.data(), buffer.data() + n);
        if (n < buffer.size()) break;
    }
    if (std::ferror(file.get())) throw Error(msg("cannot read ", path, ": ", std::strerror(errno)));
    return bytes;
}

void writeFileAtomic(const std::string& path, std::span<const uint8_t> bytes) {
    const std::string temp = path + ".tmp-" + tempSuffix();
    auto fail = [&](const char* what, int err) {
        std::remove(temp.c_str());
        throw Error(msg("cannot write ", path, ": ", what, " failed (", std::strerror(err),
                        "); check that the directory exists and is writable"));
    };
    std::FILE* file = std::fopen(temp.c_str(), "wb");
    if (!file) fail("creating the temporary file", errno);
    size_t written = bytes.empty() ? 0 : std::fwrite(bytes.data(), 1, bytes.size(), file);
    int writeErr = errno;
    bool closedOk = std::fclose(file) == 0;
    if (written != bytes.size()) fail("writing", writeErr);
    if (!closedOk) fail("closing", errno);
    if (std::rename(temp.c_str(), path.c_str()) != 0) fail("renaming the temporary file", errno);
}

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
