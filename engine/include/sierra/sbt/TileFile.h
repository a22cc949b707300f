#pragma once
// The tiled SBT file (.sierra): a grid larger than memory, cut into the
// tiles TiledRefiner.h refines over, with every vertex's saturated error and
// radius of the whole grid, so that refining the file is the in-memory
// refinement (VertexErrors.h) triangle for triangle.
//
// Layout (little-endian):
//   header      fixed, with its CRC-32: grid levels n, tile levels k, the real
//               extent (the rest of the (2^n+1)^2 grid is padding by edge
//               clamping, as terrain::padToPowerOfTwoPlusOne does, and is not
//               stored), height encoding, spacing, vertical scale
//   metadata    the georeference and geographic centre
//   tile index  per tile: offset, the end of each chunk, each chunk's CRC-32,
//               the no-data mask's size and CRC-32; tiles wholly in the
//               padding have none
//   coarse      the tile corners (every vertex of levels < 2(n-k) and the
//               grid's corners): height, error, radius, in level order
//   tiles       row-major; each a run of chunks in refinement order, so a
//               distant view reads only a tile's first pages
// A tile's vertices are its (2^k+1)^2 samples but its 4 corners, levels
// 2(n-k) .. 2n-1 ("tile levels" 0 .. 2k-1); a vertex on a border with a
// neighbour is stored in both. Chunk t < 2k-3 holds tile level t: the
// heights, then error and radius (float32) of each vertex. The last chunk
// holds the 3 finest levels (half, a quarter and an eighth of the samples)
// whose interior vertices' errors and radii are recomputed on load from the
// heights with the builder's formula, bit for bit; their border vertices,
// whose descendants reach into the neighbour, are stored. Then, when the tile
// has no-data samples, a bit mask over its samples (1 = real data).
//
// Size: int16 heights take about 3.1 bytes a sample, float32 heights 5.1.

#include <sierra/sbt/TiledRefiner.h>
#include <sierra/terrain/GridReader.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sierra::sbt {

enum class TileHeights : uint8_t {
    Int16 = 0,    // stored = offset + scale * q, q an int16
    Float32 = 1,  // stored as given
};

struct TileFileInfo {
    int n = 1, k = 1;               // grid side 2^n + 1, tiles of 2^k cells
    int64_t width = 0, height = 0;  // real samples, from (0, 0)
    TileHeights heights = TileHeights::Int16;
    double heightScale = 1.0, heightOffset = 0.0;  // Int16 only
    float spacingX = 1.0f, spacingZ = 1.0f, verticalScale = 1.0f;
    bool metres = false;
    bool hasNoData = false;
    std::optional<terrain::Heightfield::GeoPoint> geoCentre;
    std::optional<terrain::Heightfield::Georeference> georeference;

    int tilesPerSide() const { return 1 << (n - k); }
    int tileSide() const { return (1 << k) + 1; }  // samples
    int64_t gridSide() const { return (int64_t(1) << n) + 1; }
    TiledGridDesc desc() const { return {n, k, spacingX, spacingZ, verticalScale}; }
};

// The stored height of an Int16 sample q: one formula for the builder (which
// computes every error from these heights) and the reader.
inline float dequantizeHeight(int16_t q, double scale, double offset) {
    return float(offset + scale * double(q));
}

struct TileBuildOptions {
    // Tiles of 2^k cells; 1..n (larger than n: one tile). 0: autoTileLevels.
    int k = 0;
    TileHeights heights = TileHeights::Int16;
    float verticalScale = 1.0f;  // world height = stored height * verticalScale
    int threads = 0;             // 0 = sierra::defaultThreadCount()
    bool progress = false;       // a progress line on stderr (sierra::Progress)
};

struct TileBuildReport {
    TileFileInfo info;
    int64_t storedTiles = 0;
    uint64_t fileBytes = 0;
    double bytesPerSample = 0.0;  // file bytes over the real samples
};

// Builds the tile file `path` from `input`, streaming through it a band of
// tiles at a time (a band's windows reach one tile beyond the tiles they
// write: the descendants of a tile's vertices lie within one tile of it).
// The file appears complete or not at all (written beside it and renamed).
// Int16 heights take integer inputs (bytes, int16, uint16) exactly and
// quantise any other over the input's range (a first pass finds it); no-data
// samples get the lowest real height and are marked in the mask. Throws
// sierra::Error naming the input or the output.
// The tile size a build takes by default for a width x height grid: the k
// in 4..8 (at most n) whose file is smallest, the larger k among sizes within
// 5% (fewer tiles to manage). Large grids get 8; a small grid's partly
// padded edge tiles make smaller tiles pay (403x344: k 6, 4.5 bytes a sample
// instead of 6.1 with k 8).
int autoTileLevels(int64_t width, int64_t height, TileHeights heights, bool noData);

TileBuildReport buildTileFile(const terrain::GridReader& input, const std::string& path,
                              const TileBuildOptions& options = {});

// One tile's samples, local (x, y) in [0, 2^k]^2, row-major (2^k + 1 a row).
struct TileData {
    int levels = 0;             // tile levels decoded (0..2k); the rest are zero
    std::vector<float> height;  // stored heights
    std::vector<float> error;   // world height units
    std::vector<float> radius;  // world units
    std::vector<uint8_t> mask;  // 1 = real sample; empty = all real
};

// Where a tile's vertices lie in level order (the order the file stores
// them in): tile level of local sample (x, y), x, y in [0, 2^k], not a
// corner, and its index among the tile's non-corner vertices.
class TileAddressing {
  public:
    explicit TileAddressing(int k);
    int k() const { return k_; }
    int level(int x, int y) const;  // 0 .. 2k-1
    size_t index(int x, int y) const;
    // The index of (x, y) among the vertices of its tile level t alone. Level
    // t = 2m or 2m + 1 has half-step h = 2^k >> (m + 1) and step 2h: all
    // powers of two, so the lattice coordinates are shifts.
    static size_t indexInLevel(uint32_t x, uint32_t y, int t, int k) {
        const int half = t >> 1, hs = k - half - 1, ss = hs + 1;
        const uint32_t h = uint32_t(1) << hs;
        const size_t rowLength = size_t(1) << half;
        if ((t & 1) == 0) return size_t((y - h) >> ss) * rowLength + size_t((x - h) >> ss);
        const uint32_t r = y >> hs;  // row of the level's lattice
        const size_t before = size_t((r + 1) >> 1) * rowLength + size_t(r >> 1) * (rowLength + 1);
        return before + size_t((r & 1) == 0 ? (x - h) >> ss : x >> ss);
    }
    // Vertices of tile levels 0 .. levels-1.
    size_t countBelow(int levels) const { return start_[size_t(levels)]; }

  private:
    int k_;
    std::vector<size_t> start_;  // per tile level, 2k + 1 entries
};

// A tile's records in level order, only the levels read: what the caches
// keep, so a far tile's few levels take a few hundred bytes, not the whole
// (2^k+1)^2 grid.
struct PackedTile {
    int levels = 0;
    std::vector<VertexRecord> records;  // TileAddressing::index order, levels 0 .. levels-1
    std::vector<uint8_t> mask;          // (2^k+1)^2, 1 = real; empty = all real or not read
    uint64_t bytes() const { return records.size() * sizeof(VertexRecord) + mask.size(); }
};

// A tile file open for reading: header, index and coarse section read and
// checked at open; tiles read on request with pread (safe from several
// threads), never mapped, so what is resident is what the caller keeps.
class TileFile {
  public:
    // Throws sierra::Error naming `path`: missing, not a tile file, truncated,
    // a CRC that does not match, an index that points outside the file.
    explicit TileFile(const std::string& path);
    ~TileFile();
    TileFile(const TileFile&) = delete;
    TileFile& operator=(const TileFile&) = delete;

    const std::string& path() const { return path_; }
    const TileFileInfo& info() const { return info_; }
    uint64_t fileBytes() const { return fileBytes_; }

    // False for a tile wholly in the padding (nothing stored, never refined).
    bool stored(int tx, int ty) const;
    // Chunks per tile, and the tile levels decoded after the first c chunks.
    int chunkCount() const { return chunks_; }
    int levelsAfterChunks(int c) const;
    // The fewest chunks that give at least `levels` tile levels.
    int chunksForLevels(int levels) const;
    // Bytes of tile (tx, ty)'s first c chunks (and its mask with all of them).
    uint64_t tileBytes(int tx, int ty, int c) const;

    // Reads and decodes the first `chunks` chunks of a stored tile into `out`
    // (arrays sized and zeroed; corners from the coarse section). Throws
    // sierra::Error on a read error or a CRC that does not match.
    void readTile(int tx, int ty, int chunks, TileData& out) const;

    // The same, in level order and only the levels read.
    void readPacked(int tx, int ty, int chunks, PackedTile& out) const;
    // Bytes a PackedTile of the first c chunks takes.
    uint64_t packedBytes(int c) const;

    // The record of a tile corner (i, j multiples of 2^k).
    VertexRecord corner(int64_t i, int64_t j) const;

  private:
    struct Entry;
    std::string path_;
    int fd_ = -1;
    uint64_t fileBytes_ = 0;
    TileFileInfo info_;
    int chunks_ = 0;
    std::vector<uint64_t> index_;  // per tile: offset, then chunk ends, CRCs, mask bytes, mask CRC
    std::vector<VertexRecord> corners_;  // (tiles + 1)^2, row-major
    size_t entryWords() const;
};

// The terrain at every stride-th sample (stride = 2^k / 2^c, the smallest
// that keeps both sides within maxSide), read from the tiles' first levels
// only: an overview for what needs a grid in memory (2D maps, the in-memory
// renderer, a scripting front end). World heights (the file's vertical
// scale applied, the overview's 1), spacing times the stride, the
// georeference's pixel scaled likewise; the real extent only. No-data
// samples keep the builder's fill (the lowest real height). Reads the tiles
// on `threads` (0 = every core). Throws sierra::Error when even the tile
// corners exceed maxSide.
terrain::Heightfield readOverview(const TileFile& file, int maxSide, int threads = 0,
                                  int* stride = nullptr);

// The file's samples [i0, i0 + width) x [j0, j0 + height) at full
// resolution, from the tiles they lie in, read whole: world heights (the
// overview's conventions), the no-data mask where the window has no-data
// samples, the georeference moved to the window (the geographic centre
// stays the file's). Throws sierra::Error for a window not inside the real
// samples.
terrain::Heightfield readWindow(const TileFile& file, int64_t i0, int64_t j0, int width, int height,
                                int threads = 0);

// TiledVertices over a TileFile: tiles read on request, whole or in part,
// and kept until dropped. The streaming cache builds on it.
class FileTiles : public TiledVertices {
  public:
    explicit FileTiles(const TileFile& file);
    int residentLevels(int tx, int ty) const override;
    const VertexRecord* tileRecords(int tx, int ty) const override {
        const auto& t = tiles_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)];
        return t ? t->records.data() : nullptr;
    }
    VertexRecord corner(uint32_t i, uint32_t j) const override { return file_.corner(i, j); }
    // Vertex (i, j) of a resident level (tests and tools).
    VertexRecord vertex(uint32_t i, uint32_t j) const;

    // Reads tile (tx, ty) to at least `levels` tile levels (no-op when it has
    // them, or when it is not stored).
    void load(int tx, int ty, int levels);
    void loadAll(int levels);
    void drop(int tx, int ty);
    // Bytes of decoded tiles held.
    uint64_t residentBytes() const { return residentBytes_; }

  private:
    const TileFile& file_;
    TileAddressing address_;
    std::vector<std::unique_ptr<PackedTile>> tiles_;
    uint64_t residentBytes_ = 0;
};

// The record of vertex (i, j) from packed tiles: a corner from the file's
// coarse section, else from a containing tile that has its level (`tile`
// gives a tile's packed data or null). Zero when none has it: a vertex of a
// tile wholly in the padding, never refined.
template <typename TileAt>
VertexRecord packedVertex(const TileFile& file, const TileAddressing& address, uint32_t i,
                          uint32_t j, TileAt&& tile) {
    const int k = address.k(), T = 1 << k, P = file.info().tilesPerSide();
    const uint32_t mask = uint32_t(T - 1);
    if ((i & mask) == 0 && (j & mask) == 0) return file.corner(i, j);
    const int tx0 = std::min(int(i >> k), P - 1), ty0 = std::min(int(j >> k), P - 1);
    const int txs[2] = {tx0, (i & mask) == 0 && tx0 > 0 ? tx0 - 1 : tx0};
    const int tys[2] = {ty0, (j & mask) == 0 && ty0 > 0 ? ty0 - 1 : ty0};
    for (int tx : txs)
        for (int ty : tys) {
            const PackedTile* t = tile(tx, ty);
            if (!t) continue;
            const int x = int(i) - tx * T, y = int(j) - ty * T;
            if (address.level(x, y) >= t->levels) continue;
            return t->records[address.index(x, y)];
        }
    return {};
}

}  // namespace sierra::sbt
