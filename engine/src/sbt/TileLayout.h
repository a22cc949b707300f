#pragma once
// What the tile file's builder (TileBuilder.cpp) and reader (TileFile.cpp)
// share: the header, the chunk layout of a tile, CRC-32 and byte packing.
#include <sierra/sbt/TileFile.h>

#include "sbt/Saturate.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

#include <zlib.h>

namespace sierra::sbt::detail {

static_assert(std::endian::native == std::endian::little,
              "the tile file is little-endian and read in place");

constexpr char kMagic[8] = {'S', 'I', 'E', 'R', 'R', 'A', 'T', 'F'};
constexpr uint32_t kVersion = 1;
constexpr uint64_t kNotStored = ~uint64_t(0);
// The finest tile levels whose interior errors and radii are recomputed on load.
constexpr int kRecomputedLevels = 3;
// Tiles a builder window writes side by side (it reads one more on each side).
constexpr int kWindowTiles = 16;
// The largest grid: 2^20 + 1 samples a side (vertex coordinates stay in 32 bits).
constexpr int kMaxLevels = 20;

// The fixed header, written as is.
struct Header {
    char magic[8];
    uint32_t version;
    uint32_t headerBytes;
    int32_t n, k;
    int64_t width, height;
    uint8_t heights, metres, hasNoData, reserved0;
    uint32_t reserved1;
    double heightScale, heightOffset;
    float spacingX, spacingZ, verticalScale;
    uint32_t chunks;
    uint64_t metaOffset, metaBytes;
    uint64_t indexOffset, indexBytes;
    uint64_t coarseOffset, coarseBytes;
    uint64_t tilesOffset, fileBytes;
    uint32_t metaCrc, indexCrc, coarseCrc;
    uint32_t headerCrc;  // of every byte before it
};
static_assert(sizeof(Header) % 8 == 0);

inline uint32_t crc(const void* data, size_t bytes) {
    uLong c = crc32(0L, Z_NULL, 0);
    const auto* p = static_cast<const Bytef*>(data);
    while (bytes > 0) {
        const uInt step = uInt(std::min<size_t>(bytes, 1u << 30));
        c = crc32(c, p, step);
        p += step;
        bytes -= step;
    }
    return uint32_t(c);
}

// What every tile of a file shares: the vertices of each tile level, how many
// of them lie on the tile's border, and the chunk layout.
struct Layout {
    int n = 1, k = 1, T = 2, P = 1;
    int heightBytes = 2;
    int recomputed = 0;  // finest tile levels recomputed on load
    int chunks = 1;
    std::vector<int> count, border;  // per tile level
    std::vector<uint64_t> chunkEnd;  // bytes from the tile's start

    Layout(int n_, int k_, TileHeights heights) : n(n_), k(k_), T(1 << k_), P(1 << (n_ - k_)) {
        heightBytes = heights == TileHeights::Int16 ? 2 : 4;
        recomputed = std::min(kRecomputedLevels, 2 * k);
        chunks = 2 * k - recomputed + 1;
        count.assign(size_t(2 * k), 0);
        border.assign(size_t(2 * k), 0);
        for (int t = 0; t < 2 * k; ++t)
            forTileLevel(0, 0, t, [&](int i, int j, bool onBorder) {
                (void)i, (void)j;
                ++count[size_t(t)];
                border[size_t(t)] += onBorder;
            });
        uint64_t at = 0;
        for (int t = 0; t < firstRecomputed(); ++t) {
            at += uint64_t(count[size_t(t)]) * (uint64_t(heightBytes) + 8);
            chunkEnd.push_back(at);
        }
        for (int t = firstRecomputed(); t < 2 * k; ++t)
            at += uint64_t(count[size_t(t)]) * uint64_t(heightBytes) +
                  uint64_t(border[size_t(t)]) * 8;
        chunkEnd.push_back(at);
    }
    int firstRecomputed() const { return 2 * k - recomputed; }
    int levelsAfter(int c) const { return c < chunks ? c : 2 * k; }
    uint64_t maskBytes() const { return (uint64_t(T + 1) * uint64_t(T + 1) + 7) / 8; }
    // The vertices of tile level t of tile (tx, ty) in stored order:
    // fn(i, j, onBorder), absolute coordinates.
    template <typename F>
    void forTileLevel(int tx, int ty, int t, F&& fn) const {
        const int x0 = tx * T, y0 = ty * T;
        forLevelVertices(n, 2 * (n - k) + t, x0, x0 + T, y0, y0 + T, SerialRows{},
                         [&](int i, int j, int, int, int, int) {
                             fn(i, j, i == x0 || i == x0 + T || j == y0 || j == y0 + T);
                         });
    }
    size_t entryWords() const { return size_t(2 * chunks + 3); }
};

template <typename T>
inline void put(std::vector<uint8_t>& out, T value) {
    const size_t at = out.size();
    out.resize(at + sizeof(T));
    std::memcpy(out.data() + at, &value, sizeof(T));
}

template <typename T>
inline T get(const uint8_t*& p) {
    T value;
    std::memcpy(&value, p, sizeof(T));
    p += sizeof(T);
    return value;
}

inline int levelsFor(int64_t width, int64_t height) {
    const int64_t side = std::max(width, height);
    int n = 1;
    while ((int64_t(1) << n) + 1 < side) ++n;
    return n;
}

}  // namespace sierra::sbt::detail
