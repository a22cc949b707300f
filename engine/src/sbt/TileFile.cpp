// The tile file's reader (TileFile.h) and FileTiles over it.
#include "sbt/TileLayout.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Parallel.h>
#include <sierra/sbt/VertexErrors.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstring>

#include <fcntl.h>
#include <unistd.h>

namespace sierra::sbt {

using namespace detail;

namespace {

// Whole ranges of the open file by pread, refusing one beyond its end.
struct FileRange {
    const std::string& path;
    int fd;
    uint64_t size;
    void read(uint64_t at, void* data, uint64_t bytes, const char* what) const {
        if (at > size || bytes > size - at)
            throw Error(msg(path, ": truncated tile file: its ", what, " (", bytes, " bytes at ",
                            at, ") lies beyond its ", size, " bytes"));
        auto* p = static_cast<uint8_t*>(data);
        while (bytes > 0) {
            const ssize_t got = ::pread(fd, p, size_t(bytes), off_t(at));
            if (got < 0 && errno == EINTR) continue;
            if (got <= 0)
                throw Error(msg("cannot read ", path, ": ", what, ": ",
                                got < 0 ? std::strerror(errno) : "unexpected end of file"));
            p += got, at += uint64_t(got), bytes -= uint64_t(got);
        }
    }
};

// The header, checked: magic, version, CRC, possible values, the file's size.
Header readHeader(const FileRange& f) {
    Header hd;
    if (f.size >= sizeof(Header)) f.read(0, &hd, sizeof(hd), "header");
    if (f.size < sizeof(Header) || std::memcmp(kMagic, hd.magic, 8) != 0)
        throw Error(msg(f.path, ": not a Sierra tile file (no SIERRATF magic)"));
    if (hd.version != kVersion)
        throw Error(msg(f.path, ": tile file version ", hd.version, "; this build reads version ",
                        kVersion, " (rebuild it with sierra-tile build)"));
    if (hd.headerBytes != sizeof(Header) || crc(&hd, offsetof(Header, headerCrc)) != hd.headerCrc)
        throw Error(msg(f.path, ": the tile file's header is corrupt (CRC mismatch)"));
    if (hd.n < 1 || hd.n > kMaxLevels || hd.k < 1 || hd.k > hd.n || hd.width < 2 || hd.height < 2 ||
        hd.width > (int64_t(1) << hd.n) + 1 || hd.height > (int64_t(1) << hd.n) + 1 ||
        hd.heights > 1 || !(hd.heightScale > 0.0) || !std::isfinite(hd.heightOffset) ||
        !(hd.spacingX > 0.0f) || !(hd.spacingZ > 0.0f) || !(hd.verticalScale > 0.0f) ||
        !std::isfinite(hd.spacingX) || !std::isfinite(hd.spacingZ) ||
        !std::isfinite(hd.verticalScale))
        throw Error(msg(f.path, ": the tile file's header holds impossible values"));
    if (hd.chunks != uint32_t(Layout(hd.n, hd.k, TileHeights(hd.heights)).chunks) ||
        hd.fileBytes != f.size)
        throw Error(msg(f.path, ": truncated or corrupt tile file: ", f.size,
                        " bytes, its header says ", hd.fileBytes));
    return hd;
}

TileFileInfo infoOf(const Header& hd) {
    TileFileInfo info;
    info.n = hd.n;
    info.k = hd.k;
    info.width = hd.width;
    info.height = hd.height;
    info.heights = TileHeights(hd.heights);
    info.heightScale = hd.heightScale;
    info.heightOffset = hd.heightOffset;
    info.spacingX = hd.spacingX;
    info.spacingZ = hd.spacingZ;
    info.verticalScale = hd.verticalScale;
    info.metres = hd.metres != 0;
    info.hasNoData = hd.hasNoData != 0;
    return info;
}

void readMetadata(const FileRange& f, const Header& hd, TileFileInfo& info) {
    if (hd.metaBytes > (uint64_t(1) << 24))
        throw Error(msg(f.path, ": the tile file's metadata is corrupt"));
    std::vector<uint8_t> meta(hd.metaBytes);
    f.read(hd.metaOffset, meta.data(), meta.size(), "metadata");
    if (crc(meta.data(), meta.size()) != hd.metaCrc || meta.size() < 1 + 16 + 1 + 48 + 4)
        throw Error(msg(f.path, ": the tile file's metadata is corrupt (CRC mismatch)"));
    const uint8_t* p = meta.data();
    const bool hasCentre = get<uint8_t>(p) != 0;
    const double lat = get<double>(p), lon = get<double>(p);
    if (hasCentre) info.geoCentre = terrain::Heightfield::GeoPoint{lat, lon};
    const bool hasRef = get<uint8_t>(p) != 0;
    terrain::Heightfield::Georeference ref;
    for (int c = 0; c < 6; ++c) ref.geoTransform[size_t(c)] = get<double>(p);
    const uint32_t wktBytes = get<uint32_t>(p);
    if (wktBytes != meta.size() - size_t(p - meta.data()))
        throw Error(msg(f.path, ": the tile file's metadata is corrupt"));
    ref.crsWkt.assign(reinterpret_cast<const char*>(p), wktBytes);
    if (hasRef) info.georeference = std::move(ref);
}

std::vector<uint64_t> readIndex(const FileRange& f, const Header& hd, const Layout& L) {
    std::vector<uint64_t> index;
    const size_t tiles = size_t(L.P) * size_t(L.P);
    if (hd.indexBytes != tiles * L.entryWords() * 8)
        throw Error(msg(f.path, ": the tile file's index has ", hd.indexBytes, " bytes, ",
                        tiles * L.entryWords() * 8, " expected"));
    index.resize(tiles * L.entryWords());
    f.read(hd.indexOffset, index.data(), hd.indexBytes, "tile index");
    if (crc(index.data(), hd.indexBytes) != hd.indexCrc)
        throw Error(msg(f.path, ": the tile file's index is corrupt (CRC mismatch)"));
    for (size_t t = 0; t < tiles; ++t) {
        const uint64_t* e = &index[t * L.entryWords()];
        if (e[0] == kNotStored) continue;
        const uint64_t maskBytes = e[1 + 2 * L.chunks];
        for (int c = 0; c < L.chunks; ++c)
            if (e[1 + c] != L.chunkEnd[size_t(c)])
                throw Error(msg(f.path, ": the tile file's index is corrupt (tile ", t, ")"));
        if ((maskBytes != 0 && maskBytes != L.maskBytes()) || e[0] < hd.tilesOffset ||
            e[0] > f.size || L.chunkEnd.back() + maskBytes > f.size - e[0])
            throw Error(msg(f.path, ": truncated tile file: tile ", t % size_t(L.P), ", ",
                            t / size_t(L.P), " lies beyond its ", f.size, " bytes"));
    }

    return index;
}

std::vector<VertexRecord> readCoarse(const FileRange& f, const Header& hd, const Layout& L,
                                     const TileFileInfo& info) {
    const size_t count = size_t(L.P + 1) * size_t(L.P + 1);
    const size_t cornerBytes = size_t(L.heightBytes) + 8;
    if (hd.coarseBytes != count * cornerBytes)
        throw Error(msg(f.path, ": the tile file's coarse section is corrupt"));
    std::vector<uint8_t> coarse(hd.coarseBytes);
    f.read(hd.coarseOffset, coarse.data(), coarse.size(), "coarse section");
    if (crc(coarse.data(), coarse.size()) != hd.coarseCrc)
        throw Error(msg(f.path, ": the tile file's coarse section is corrupt (CRC mismatch)"));
    std::vector<VertexRecord> corners(count);
    const int S = 1 << hd.n, T = L.T;
    const uint8_t* c = coarse.data();
    auto takeCorner = [&](int i, int j) {
        VertexRecord& r = corners[size_t(j / T) * size_t(L.P + 1) + size_t(i / T)];
        r.height = info.heights == TileHeights::Int16
                       ? dequantizeHeight(get<int16_t>(c), hd.heightScale, hd.heightOffset)
                       : get<float>(c);
        r.error = get<float>(c);
        r.radius = get<float>(c);
    };
    for (int l = 0; l < 2 * (hd.n - hd.k); ++l)
        detail::forLevelVertices(hd.n, l, 0, S, 0, S, detail::SerialRows{},
                                 [&](int i, int j, int, int, int, int) { takeCorner(i, j); });
    for (int j : {0, S})
        for (int i : {0, S}) takeCorner(i, j);
    for (const VertexRecord& r : corners)
        if (!std::isfinite(r.height) || !std::isfinite(r.error) || !std::isfinite(r.radius) ||
            r.error < 0.0f || r.radius < 0.0f)
            throw Error(msg(f.path, ": the tile file's coarse section holds impossible values"));
    return corners;
}

}  // namespace

TileFile::TileFile(const std::string& path) : path_(path) {
    fileBytes_ = regularFileSize(path);
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw Error(msg("cannot open ", path, ": ", std::strerror(errno)));
    try {
        const FileRange f{path_, fd_, fileBytes_};
        const Header hd = readHeader(f);
        const Layout L(hd.n, hd.k, TileHeights(hd.heights));
        info_ = infoOf(hd);
        chunks_ = L.chunks;
        readMetadata(f, hd, info_);
        index_ = readIndex(f, hd, L);
        corners_ = readCoarse(f, hd, L, info_);
    } catch (...) {
        ::close(fd_);
        throw;
    }
}

TileFile::~TileFile() {
    if (fd_ >= 0) ::close(fd_);
}

size_t TileFile::entryWords() const {
    return size_t(2 * chunks_ + 3);
}

bool TileFile::stored(int tx, int ty) const {
    const int P = info_.tilesPerSide();
    if (tx < 0 || ty < 0 || tx >= P || ty >= P) return false;
    return index_[(size_t(ty) * size_t(P) + size_t(tx)) * entryWords()] != kNotStored;
}

int TileFile::levelsAfterChunks(int c) const {
    return c <= 0 ? 0 : c < chunks_ ? c : 2 * info_.k;
}

int TileFile::chunksForLevels(int levels) const {
    for (int c = 0; c <= chunks_; ++c)
        if (levelsAfterChunks(c) >= levels) return c;
    return chunks_;
}

uint64_t TileFile::tileBytes(int tx, int ty, int c) const {
    if (!stored(tx, ty) || c <= 0) return 0;
    const uint64_t* e =
        &index_[(size_t(ty) * size_t(info_.tilesPerSide()) + size_t(tx)) * entryWords()];
    c = std::min(c, chunks_);
    return e[c] + (c == chunks_ ? e[1 + 2 * chunks_] : 0);
}

VertexRecord TileFile::corner(int64_t i, int64_t j) const {
    const int T = 1 << info_.k;
    return corners_[size_t(j / T) * size_t(info_.tilesPerSide() + 1) + size_t(i / T)];
}

void TileFile::readTile(int tx, int ty, int chunks, TileData& out) const {
    SIERRA_CHECK(stored(tx, ty), path_, ": tile ", tx, ", ", ty, " is not stored");
    chunks = std::clamp(chunks, 0, chunks_);
    const Layout L(info_.n, info_.k, info_.heights);
    const int T = L.T, side = T + 1;
    const uint64_t* e = &index_[(size_t(ty) * size_t(L.P) + size_t(tx)) * entryWords()];
    const uint64_t bytes = tileBytes(tx, ty, chunks);
    std::vector<uint8_t> blob(bytes);
    FileRange{path_, fd_, fileBytes_}.read(e[0], blob.data(), bytes, "a tile");
    for (int c = 0; c < chunks; ++c) {
        const uint64_t begin = c == 0 ? 0 : e[c], end = e[1 + c];
        if (crc(blob.data() + begin, end - begin) != uint32_t(e[1 + chunks_ + c]))
            throw Error(
                msg(path_, ": tile ", tx, ", ", ty, " is corrupt (chunk ", c, " CRC mismatch)"));
    }
    const uint64_t maskBytes = chunks == chunks_ ? e[1 + 2 * chunks_] : 0;
    if (maskBytes && crc(blob.data() + e[chunks_], maskBytes) != uint32_t(e[2 + 2 * chunks_]))
        throw Error(
            msg(path_, ": tile ", tx, ", ", ty, "'s no-data mask is corrupt (CRC mismatch)"));

    const size_t count = size_t(side) * size_t(side);
    out.levels = levelsAfterChunks(chunks);
    out.height.assign(count, 0.0f);
    out.error.assign(count, 0.0f);
    out.radius.assign(count, 0.0f);
    out.mask.clear();
    const int x0 = tx * T, y0 = ty * T;
    auto local = [&](int i, int j) { return size_t(j - y0) * size_t(side) + size_t(i - x0); };
    for (int cj = 0; cj <= 1; ++cj)
        for (int ci = 0; ci <= 1; ++ci) {
            const VertexRecord r = corner(x0 + ci * T, y0 + cj * T);
            const size_t m = local(x0 + ci * T, y0 + cj * T);
            out.height[m] = r.height, out.error[m] = r.error, out.radius[m] = r.radius;
        }
    const uint8_t* q = blob.data();
    const bool int16 = info_.heights == TileHeights::Int16;
    auto takeHeight = [&](int i, int j, bool) {
        out.height[local(i, j)] =
            int16 ? dequantizeHeight(get<int16_t>(q), info_.heightScale, info_.heightOffset)
                  : get<float>(q);
    };
    auto takeRecord = [&](int i, int j) {
        const size_t m = local(i, j);
        out.error[m] = get<float>(q);
        out.radius[m] = get<float>(q);
    };
    for (int t = 0; t < std::min(chunks, L.firstRecomputed()); ++t) {
        L.forTileLevel(tx, ty, t, takeHeight);
        L.forTileLevel(tx, ty, t, [&](int i, int j, bool) { takeRecord(i, j); });
    }
    if (chunks == chunks_) {
        for (int t = L.firstRecomputed(); t < 2 * L.k; ++t) L.forTileLevel(tx, ty, t, takeHeight);
        for (int t = L.firstRecomputed(); t < 2 * L.k; ++t)
            L.forTileLevel(tx, ty, t, [&](int i, int j, bool onBorder) {
                if (onBorder) takeRecord(i, j);
            });
        const detail::SampleWindow g{.n = info_.n,
                                     .i0 = x0,
                                     .j0 = y0,
                                     .w = side,
                                     .h = side,
                                     .height = out.height.data(),
                                     .error = out.error.data(),
                                     .radius = out.radius.data(),
                                     .sx = info_.spacingX,
                                     .sz = info_.spacingZ,
                                     .vs = info_.verticalScale};
        detail::saturateLevels(
            g, 2 * info_.n - 1, 2 * info_.n - L.recomputed, 1,
            [&](int i, int j) { return i == x0 || i == x0 + T || j == y0 || j == y0 + T; });
        if (maskBytes) {
            out.mask.assign(count, 0);
            const uint8_t* bits = blob.data() + e[chunks_];
            for (size_t b = 0; b < count; ++b) out.mask[b] = (bits[b >> 3] >> (b & 7)) & 1;
        }
    }
    for (size_t m = 0; m < count; ++m)
        if (!std::isfinite(out.height[m]) || !std::isfinite(out.error[m]) ||
            !std::isfinite(out.radius[m]) || out.error[m] < 0.0f || out.radius[m] < 0.0f)
            throw Error(msg(path_, ": tile ", tx, ", ", ty, " holds impossible values"));
}

// ---------------------------------------------------------------- FileTiles

TileAddressing::TileAddressing(int k) : k_(k) {
    const Layout L(k, k, TileHeights::Float32);  // the counts depend on k alone
    start_.assign(size_t(2 * k + 1), 0);
    for (int t = 0; t < 2 * k; ++t)
        start_[size_t(t + 1)] = start_[size_t(t)] + size_t(L.count[size_t(t)]);
}

int TileAddressing::level(int x, int y) const {
    return vertexLevel(x, y, k_);
}

size_t TileAddressing::index(int x, int y) const {
    const int t = level(x, y);
    return start_[size_t(t)] + indexInLevel(uint32_t(x), uint32_t(y), t, k_);
}

uint64_t TileFile::packedBytes(int c) const {
    const TileAddressing address(info_.k);
    const int levels = levelsAfterChunks(c);
    const uint64_t side = uint64_t(info_.tileSide());
    return address.countBelow(levels) * sizeof(VertexRecord) +
           (levels == 2 * info_.k && info_.hasNoData ? side * side : 0);
}

void TileFile::readPacked(int tx, int ty, int chunks, PackedTile& out) const {
    TileData grid;
    readTile(tx, ty, chunks, grid);
    const Layout L(info_.n, info_.k, info_.heights);
    const int T = L.T, side = T + 1;
    out.levels = grid.levels;
    out.records.clear();
    out.records.reserve(TileAddressing(info_.k).countBelow(grid.levels));
    for (int t = 0; t < grid.levels; ++t)
        L.forTileLevel(tx, ty, t, [&](int i, int j, bool) {
            const size_t m = size_t(j - ty * T) * size_t(side) + size_t(i - tx * T);
            out.records.push_back({grid.height[m], grid.error[m], grid.radius[m]});
        });
    out.mask = std::move(grid.mask);
}

namespace {

// Samples [i0, i0 + w) x [j0, j0 + h) of the grid at every stride-th sample,
// stride = 2^k / 2^c (region in those samples), from the tiles' first 2c
// levels; world heights. With c = k the tiles are read whole, and their
// no-data masks, when the file has any, become the field's mask.
terrain::Heightfield readRegion(const TileFile& file, int c, int64_t i0, int64_t j0, int64_t w,
                                int64_t h, int threads) {
    const TileFileInfo& info = file.info();
    const int k = info.k, T = 1 << k, P = info.tilesPerSide();
    const int stride = T >> c;
    const int per = T / stride;  // region samples a tile, per side
    terrain::Heightfield out{static_cast<int>(w), static_cast<int>(h)};
    const bool masked = c == k && info.hasNoData;
    std::vector<uint8_t> mask(masked ? size_t(w * h) : 0, 1);
    const int chunks = file.chunksForLevels(2 * c);
    const TileAddressing address(k);
    const float vs = info.verticalScale;
    const int tx0 = int(i0 / per), ty0 = int(j0 / per);
    const int tx1 = std::min(P - 1, int((i0 + w - 1) / per)),
              ty1 = std::min(P - 1, int((j0 + h - 1) / per));
    const int64_t across = tx1 - tx0 + 1;
    parallelFor(
        0, across * (ty1 - ty0 + 1),
        [&](int64_t t) {
            const int tx = tx0 + int(t % across), ty = ty0 + int(t / across);
            if (!file.stored(tx, ty)) return;
            PackedTile tile;
            if (chunks > 0) file.readPacked(tx, ty, chunks, tile);
            // A border sample is written by one tile: the last row and column
            // belong to the next tile when that one is stored.
            const int aEnd = tx + 1 < P && file.stored(tx + 1, ty) ? per - 1 : per;
            const int bEnd = ty + 1 < P && file.stored(tx, ty + 1) ? per - 1 : per;
            for (int b = 0; b <= bEnd; ++b)
                for (int a = 0; a <= aEnd; ++a) {
                    const int64_t oi = int64_t(tx) * per + a - i0, oj = int64_t(ty) * per + b - j0;
                    if (oi < 0 || oj < 0 || oi >= w || oj >= h) continue;
                    const int x = a * stride, y = b * stride;
                    const bool corner = (x == 0 || x == T) && (y == 0 || y == T);
                    const float height =
                        corner ? file.corner(int64_t(tx) * T + x, int64_t(ty) * T + y).height
                               : tile.records[address.index(x, y)].height;
                    out.at(int(oi), int(oj)) = height * vs;
                    if (masked && !tile.mask.empty() && !tile.mask[size_t(y) * (T + 1) + size_t(x)])
                        mask[size_t(oj * w + oi)] = 0;
                }
        },
        threads);
    if (masked && std::find(mask.begin(), mask.end(), uint8_t(0)) != mask.end())
        out.setMask(std::move(mask));
    return out;
}

// The file's georeference for a grid whose sample (0, 0) is the file's
// (i0, j0) and whose samples are `stride` of the file's apart: sample
// centres stay where they were, X = g0 + (i + 0.5) g1 + (j + 0.5) g2.
terrain::Heightfield::Georeference regionGeoreference(terrain::Heightfield::Georeference ref,
                                                      int64_t i0, int64_t j0, int stride) {
    auto& g = ref.geoTransform;
    const double half = 0.5 * (1.0 - double(stride));
    g[0] += (double(i0) + half) * g[1] + (double(j0) + half) * g[2];
    g[3] += (double(i0) + half) * g[4] + (double(j0) + half) * g[5];
    for (int e : {1, 2, 4, 5}) g[size_t(e)] *= double(stride);
    return ref;
}

}  // namespace

terrain::Heightfield readOverview(const TileFile& file, int maxSide, int threads, int* strideOut) {
    const TileFileInfo& info = file.info();
    const int k = info.k, T = 1 << k;
    int c = k;
    auto sideAt = [&](int cls) {
        const int stride = T >> cls;
        return std::max((info.width - 1) / stride + 1, (info.height - 1) / stride + 1);
    };
    while (c > 0 && sideAt(c) > maxSide) --c;
    SIERRA_CHECK(sideAt(c) <= maxSide, file.path(), ": even its tile corners (", sideAt(0), "x",
                 sideAt(0), ") exceed the ", maxSide, "-sample side asked for");
    const int stride = T >> c;
    const int64_t w = (info.width - 1) / stride + 1, h = (info.height - 1) / stride + 1;
    terrain::Heightfield out = readRegion(file, c, 0, 0, w, h, threads);
    // The overview's samples keep the builder's fill where there is no data.
    out.setMask({});
    out.setSpacing(info.spacingX * float(stride), info.spacingZ * float(stride));
    out.setMetres(info.metres);
    out.setGeoCentre(info.geoCentre);
    if (info.georeference)
        out.setGeoreference(regionGeoreference(*info.georeference, 0, 0, stride));
    if (strideOut) *strideOut = stride;
    return out;
}

terrain::Heightfield readWindow(const TileFile& file, int64_t i0, int64_t j0, int width, int height,
                                int threads) {
    const TileFileInfo& info = file.info();
    SIERRA_CHECK(width > 0 && height > 0 && i0 >= 0 && j0 >= 0 && i0 + width <= info.width &&
                     j0 + height <= info.height,
                 file.path(), ": the window of ", width, "x", height, " samples at ", i0, ", ", j0,
                 " is not inside its ", info.width, "x", info.height, " samples");
    terrain::Heightfield out = readRegion(file, info.k, i0, j0, width, height, threads);
    out.setSpacing(info.spacingX, info.spacingZ);
    out.setMetres(info.metres);
    out.setGeoCentre(info.geoCentre);
    if (info.georeference) out.setGeoreference(regionGeoreference(*info.georeference, i0, j0, 1));
    return out;
}

FileTiles::FileTiles(const TileFile& file)
    : TiledVertices(file.info().desc()),
      file_(file),
      address_(file.info().k),
      tiles_(size_t(file.info().tilesPerSide()) * size_t(file.info().tilesPerSide())) {}

int FileTiles::residentLevels(int tx, int ty) const {
    // A tile wholly in the padding is never refined (its vertices' records are
    // zero), so it never holds its neighbours back.
    if (!file_.stored(tx, ty)) return 2 * desc().k;
    const auto& t = tiles_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)];
    return t ? t->levels : 0;
}

VertexRecord FileTiles::vertex(uint32_t i, uint32_t j) const {
    return packedVertex(file_, address_, i, j, [&](int tx, int ty) {
        return tiles_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)].get();
    });
}

void FileTiles::load(int tx, int ty, int levels) {
    if (!file_.stored(tx, ty)) return;
    auto& t = tiles_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)];
    if (t && t->levels >= levels) return;
    auto data = std::make_unique<PackedTile>();
    file_.readPacked(tx, ty, file_.chunksForLevels(levels), *data);
    if (t) residentBytes_ -= t->bytes();
    residentBytes_ += data->bytes();
    t = std::move(data);
}

void FileTiles::loadAll(int levels) {
    for (int ty = 0; ty < tilesPerSide(); ++ty)
        for (int tx = 0; tx < tilesPerSide(); ++tx) load(tx, ty, levels);
}

void FileTiles::drop(int tx, int ty) {
    auto& t = tiles_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)];
    if (t) residentBytes_ -= t->bytes();
    t.reset();
}

}  // namespace sierra::sbt
