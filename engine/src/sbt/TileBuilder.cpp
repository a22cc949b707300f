// The tile file's builder (TileFile.h): a band of tiles at a time, each
// window read with one tile of margin, saturated with the whole grid's
// formula (Saturate.h), cut into tiles; then the coarse levels over the tile
// corners and centres.
#include "sbt/TileLayout.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Parallel.h>
#include <sierra/core/Progress.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>

namespace sierra::sbt {
namespace {

using namespace detail;

// How input heights become stored heights.
struct Encoding {
    TileHeights heights = TileHeights::Int16;
    double scale = 1.0, offset = 0.0;
    float fill = 0.0f;  // stored height of a no-data sample
    int16_t quantize(float h) const {
        const double q = std::nearbyint((double(h) - offset) / scale);
        return int16_t(std::clamp(q, -32767.0, 32767.0));
    }
};

// The band of tiles one builder window covers, read and saturated.
// Kept per thread from window to window: a window is tens of megabytes,
// whose first touch of fresh pages cost more than the work.
struct Window {
    detail::SampleWindow g;
    std::vector<float> height, error, radius;
    std::vector<int16_t> q;      // Int16 only
    std::vector<uint8_t> valid;  // 1 = real sample
    std::vector<float> real;     // the input's samples of the window
    std::vector<uint8_t> realValid;
};

void readWindow(const terrain::GridReader& input, const Encoding& enc, int n, int wx0, int wy0,
                int wx1, int wy1, float sx, float sz, float vs, Window& w) {
    const int64_t W = input.info().width, H = input.info().height;
    const int ww = wx1 - wx0 + 1, wh = wy1 - wy0 + 1;
    const int rw = int(std::min<int64_t>(wx1, W - 1) - wx0 + 1);
    const int rh = int(std::min<int64_t>(wy1, H - 1) - wy0 + 1);
    std::vector<float>& real = w.real;
    std::vector<uint8_t>& realValid = w.realValid;
    real.resize(size_t(rw) * size_t(rh));
    realValid.resize(real.size());
    input.read(wx0, wy0, rw, rh, real.data(), realValid.data());
    const size_t count = size_t(ww) * size_t(wh);
    w.height.assign(count, 0.0f);
    w.error.assign(count, 0.0f);
    w.radius.assign(count, 0.0f);
    w.valid.assign(count, 0);
    if (enc.heights == TileHeights::Int16) w.q.assign(count, 0);
    for (int y = 0; y < wh; ++y) {
        const int sy = std::min(y, rh - 1);  // padding: the nearest real row
        for (int x = 0; x < ww; ++x) {
            const int sx_ = std::min(x, rw - 1);
            const size_t s = size_t(sy) * size_t(rw) + size_t(sx_);
            const size_t d = size_t(y) * size_t(ww) + size_t(x);
            const bool ok = realValid[s] != 0;
            float h = ok ? real[s] : enc.fill;
            if (enc.heights == TileHeights::Int16) {
                w.q[d] = enc.quantize(h);
                h = dequantizeHeight(w.q[d], enc.scale, enc.offset);
            }
            w.height[d] = h;
            w.valid[d] = ok && y < rh && x < rw;
        }
    }
    w.g = detail::SampleWindow{.n = n,
                               .i0 = wx0,
                               .j0 = wy0,
                               .w = ww,
                               .h = wh,
                               .height = w.height.data(),
                               .error = w.error.data(),
                               .radius = w.radius.data(),
                               .sx = sx,
                               .sz = sz,
                               .vs = vs};
}

// One tile's bytes from a saturated window, and its mask.
void encodeTile(const Layout& L, const Encoding& enc, const Window& w, int tx, int ty,
                std::vector<uint8_t>& blob, std::vector<uint32_t>& crcs,
                std::vector<uint8_t>& mask) {
    blob.clear();
    crcs.clear();
    auto putHeight = [&](size_t at) {
        if (enc.heights == TileHeights::Int16)
            put<int16_t>(blob, w.q[at]);
        else
            put<float>(blob, w.height[at]);
    };
    size_t chunkStart = 0;
    auto endChunk = [&] {
        crcs.push_back(crc(blob.data() + chunkStart, blob.size() - chunkStart));
        chunkStart = blob.size();
    };
    for (int t = 0; t < L.firstRecomputed(); ++t) {
        L.forTileLevel(tx, ty, t, [&](int i, int j, bool) { putHeight(w.g.index(i, j)); });
        L.forTileLevel(tx, ty, t, [&](int i, int j, bool) {
            const size_t at = w.g.index(i, j);
            put<float>(blob, w.error[at]);
            put<float>(blob, w.radius[at]);
        });
        endChunk();
    }
    for (int t = L.firstRecomputed(); t < 2 * L.k; ++t)
        L.forTileLevel(tx, ty, t, [&](int i, int j, bool) { putHeight(w.g.index(i, j)); });
    for (int t = L.firstRecomputed(); t < 2 * L.k; ++t)
        L.forTileLevel(tx, ty, t, [&](int i, int j, bool onBorder) {
            if (!onBorder) return;
            const size_t at = w.g.index(i, j);
            put<float>(blob, w.error[at]);
            put<float>(blob, w.radius[at]);
        });
    endChunk();
    // The mask, only when some sample of the tile is not real.
    mask.clear();
    bool all = true;
    std::vector<uint8_t> bits(L.maskBytes(), 0);
    for (int y = 0; y <= L.T; ++y)
        for (int x = 0; x <= L.T; ++x) {
            const size_t bit = size_t(y) * size_t(L.T + 1) + size_t(x);
            if (w.valid[w.g.index(tx * L.T + x, ty * L.T + y)])
                bits[bit >> 3] |= uint8_t(1u << (bit & 7));
            else
                all = false;
        }
    if (!all) mask = std::move(bits);
}

// How stored heights come from the input: int16 inputs exactly; anything else
// quantised over the real heights' range, found by a first pass (which also
// gives the no-data fill, the lowest real height).
Encoding chooseEncoding(const terrain::GridReader& input, const TileBuildOptions& options,
                        int threads) {
    const terrain::GridInfo& in = input.info();
    Encoding enc;
    enc.heights = options.heights;
    const bool exactInt16 = options.heights == TileHeights::Int16 && in.int16Offset.has_value();
    if (exactInt16) enc.offset = *in.int16Offset;
    if (exactInt16 && !in.hasNoData) return enc;
    const int64_t W = in.width, H = in.height, rows = 64, strips = (H + rows - 1) / rows;
    std::vector<float> lo(size_t(strips), std::numeric_limits<float>::infinity());
    std::vector<float> hi(size_t(strips), -std::numeric_limits<float>::infinity());
    parallelFor(
        0, strips,
        [&](int64_t s) {
            const int64_t y0 = s * rows, h = std::min(rows, H - y0);
            std::vector<float> v(size_t(W) * size_t(h));
            std::vector<uint8_t> ok(v.size());
            input.read(0, y0, int(W), int(h), v.data(), ok.data());
            for (size_t i = 0; i < v.size(); ++i)
                if (ok[i]) {
                    lo[size_t(s)] = std::min(lo[size_t(s)], v[i]);
                    hi[size_t(s)] = std::max(hi[size_t(s)], v[i]);
                }
        },
        threads);
    const float mn = *std::min_element(lo.begin(), lo.end());
    const float mx = *std::max_element(hi.begin(), hi.end());
    SIERRA_CHECK(mn <= mx, "tile build: the input has no real sample (all no-data)");
    enc.fill = mn;
    if (options.heights == TileHeights::Int16 && !exactInt16) {
        enc.offset = 0.5 * (double(mn) + double(mx));
        enc.scale = mx > mn ? (double(mx) - double(mn)) / 65534.0 : 1.0;
    }
    return enc;
}

std::vector<uint8_t> metadata(const TileFileInfo& info) {
    std::vector<uint8_t> meta;
    put<uint8_t>(meta, info.geoCentre.has_value());
    put<double>(meta, info.geoCentre ? info.geoCentre->latitude : 0.0);
    put<double>(meta, info.geoCentre ? info.geoCentre->longitude : 0.0);
    put<uint8_t>(meta, info.georeference.has_value());
    for (int c = 0; c < 6; ++c)
        put<double>(meta, info.georeference ? info.georeference->geoTransform[size_t(c)] : 0.0);
    const std::string wkt = info.georeference ? info.georeference->crsWkt : std::string();
    put<uint32_t>(meta, uint32_t(wkt.size()));
    meta.insert(meta.end(), wkt.begin(), wkt.end());
    return meta;
}

// One build: the file's sections, then the tiles band by band, then the
// coarse levels over what the tiles left.
class Builder {
  public:
    Builder(const terrain::GridReader& input, const TileFileInfo& info, const Encoding& enc,
            const TileBuildOptions& options, int threads)
        : input_(input),
          info_(info),
          enc_(enc),
          options_(options),
          threads_(threads),
          L_(info.n, info.k, info.heights),
          T_(L_.T),
          P_(L_.P),
          S_(1 << info.n),
          cw_(2 * P_ + 1) {
        // Tiles with a real sample not on their last row or column (those are
        // the next tile's first): the rest lie wholly in the padding.
        storedX_ = int((info.width - 2) / T_) + 1;
        storedY_ = int((info.height - 2) / T_) + 1;
        meta_ = metadata(info);
        index_.assign(size_t(P_) * size_t(P_) * L_.entryWords(), 0);
        for (size_t t = 0; t < size_t(P_) * size_t(P_); ++t)
            index_[t * L_.entryWords()] = kNotStored;
        coarseH_.assign(size_t(cw_) * size_t(cw_), 0.0f);
        coarseE_.assign(coarseH_.size(), 0.0f);
        coarseR_.assign(coarseH_.size(), 0.0f);
        cornerQ_.assign(size_t(P_ + 1) * size_t(P_ + 1), 0);
        header();
    }

    int64_t storedTiles() const { return written_; }
    uint64_t fileBytes() const { return hd_.fileBytes; }

    void write(std::FILE* f) {
        f_ = f;
        std::vector<uint8_t> zeros(hd_.tilesOffset, 0);
        writeAt(0, zeros.data(), zeros.size());
        at_ = hd_.tilesOffset;
        tiles();
        const std::vector<uint8_t> coarse = coarseSection();
        hd_.fileBytes = at_;
        hd_.metaCrc = crc(meta_.data(), meta_.size());
        hd_.indexCrc = crc(index_.data(), hd_.indexBytes);
        hd_.coarseCrc = crc(coarse.data(), coarse.size());
        hd_.headerCrc = crc(&hd_, offsetof(Header, headerCrc));
        writeAt(hd_.metaOffset, meta_.data(), meta_.size());
        writeAt(hd_.indexOffset, index_.data(), hd_.indexBytes);
        writeAt(hd_.coarseOffset, coarse.data(), coarse.size());
        writeAt(0, &hd_, sizeof(hd_));
    }

  private:
    struct Out {
        std::vector<uint8_t> blob, mask;
        std::vector<uint32_t> crcs;
    };

    void header() {
        std::memcpy(hd_.magic, kMagic, 8);
        hd_.version = kVersion;
        hd_.headerBytes = sizeof(Header);
        hd_.n = info_.n;
        hd_.k = info_.k;
        hd_.width = info_.width;
        hd_.height = info_.height;
        hd_.heights = uint8_t(info_.heights);
        hd_.metres = info_.metres;
        hd_.hasNoData = info_.hasNoData;
        hd_.heightScale = enc_.scale;
        hd_.heightOffset = enc_.offset;
        hd_.spacingX = info_.spacingX;
        hd_.spacingZ = info_.spacingZ;
        hd_.verticalScale = info_.verticalScale;
        hd_.chunks = uint32_t(L_.chunks);
        hd_.metaOffset = sizeof(Header);
        hd_.metaBytes = meta_.size();
        hd_.indexOffset = (hd_.metaOffset + hd_.metaBytes + 7) / 8 * 8;
        hd_.indexBytes = index_.size() * 8;
        hd_.coarseOffset = hd_.indexOffset + hd_.indexBytes;
        hd_.coarseBytes = cornerQ_.size() * size_t(L_.heightBytes + 8);
        hd_.tilesOffset = (hd_.coarseOffset + hd_.coarseBytes + 4095) / 4096 * 4096;
    }

    void writeAt(uint64_t at, const void* data, size_t bytes) {
        if (std::fseek(f_, long(at), SEEK_SET) != 0 || std::fwrite(data, 1, bytes, f_) != bytes)
            throw Error(msg("tile build: cannot write: ", std::strerror(errno)));
    }

    // The window of tiles tx0..tx1 of row ty, saturated, cut into `out`.
    void band(int ty, int tx0, int tx1, Out* out) {
        thread_local Window w;
        readWindow(input_, enc_, info_.n, std::max(0, (tx0 - 1) * T_), std::max(0, (ty - 1) * T_),
                   std::min(S_, (tx1 + 2) * T_), std::min(S_, (ty + 2) * T_), info_.spacingX,
                   info_.spacingZ, info_.verticalScale, w);
        saturateLevels(w.g, 2 * info_.n - 1, 2 * (info_.n - info_.k), 1,
                       [](int, int) { return false; });
        for (int tx = tx0; tx <= tx1; ++tx) {
            Out& o = out[tx];
            encodeTile(L_, enc_, w, tx, ty, o.blob, o.crcs, o.mask);
            const size_t c = size_t(2 * ty + 1) * size_t(cw_) + size_t(2 * tx + 1);
            const size_t m = w.g.index(tx * T_ + T_ / 2, ty * T_ + T_ / 2);
            coarseH_[c] = w.height[m];
            coarseE_[c] = w.error[m];
            coarseR_[c] = w.radius[m];
        }
    }

    void append(int tx, int ty, const Out& o) {
        uint64_t* e = &index_[(size_t(ty) * size_t(P_) + size_t(tx)) * L_.entryWords()];
        e[0] = at_;
        for (int c = 0; c < L_.chunks; ++c) {
            e[1 + c] = L_.chunkEnd[size_t(c)];
            e[1 + L_.chunks + c] = o.crcs[size_t(c)];
        }
        e[1 + 2 * L_.chunks] = o.mask.size();
        e[2 + 2 * L_.chunks] = o.mask.empty() ? 0 : crc(o.mask.data(), o.mask.size());
        SIERRA_CHECK(o.blob.size() == L_.chunkEnd.back(), "tile build: tile ", tx, ", ", ty,
                     " has ", o.blob.size(), " bytes, the layout ", L_.chunkEnd.back());
        writeAt(at_, o.blob.data(), o.blob.size());
        at_ += o.blob.size();
        if (!o.mask.empty()) {
            writeAt(at_, o.mask.data(), o.mask.size());
            at_ += o.mask.size();
        }
        ++written_;
    }

    // Rows of tiles are independent (each window reads its own neighbours):
    // enough rows at once to give every thread a window, written in order.
    void tiles() {
        const int groups = (storedX_ + kWindowTiles - 1) / kWindowTiles;
        const int batch = std::max(1, std::min(storedY_, (2 * threads_ + groups - 1) / groups));
        std::vector<Out> rows(size_t(batch) * size_t(storedX_));
        Progress progress("tiles", int64_t(storedX_) * storedY_);
        for (int ty0 = 0; ty0 < storedY_; ty0 += batch) {
            const int rowCount = std::min(batch, storedY_ - ty0);
            parallelFor(
                0, int64_t(rowCount) * groups,
                [&](int64_t job) {
                    const int r = int(job / groups), tx0 = int(job % groups) * kWindowTiles;
                    band(ty0 + r, tx0, std::min(storedX_, tx0 + kWindowTiles) - 1,
                         &rows[size_t(r) * size_t(storedX_)]);
                },
                threads_);
            for (int r = 0; r < rowCount; ++r)
                for (int tx = 0; tx < storedX_; ++tx)
                    append(tx, ty0 + r, rows[size_t(r) * size_t(storedX_) + size_t(tx)]);
            // The next batch's windows start a tile above it: nothing before is read again.
            input_.releaseRowsBefore(int64_t(ty0 + rowCount - 1) * T_);
            if (options_.progress)
                progress.update(written_, msg(ty0 + rowCount, "/", storedY_, " rows"));
        }
        if (options_.progress) progress.finish();
    }

    // The corners' heights (the nearest real sample, as the padding is) and
    // the levels above the tiles, saturated over the tile centres. Centres of
    // tiles wholly in the padding keep zero records: never refined, they
    // draw nothing.
    std::vector<uint8_t> coarseSection() {
        const int64_t W = info_.width, H = info_.height;
        for (int cj = 0; cj <= P_; ++cj)
            for (int ci = 0; ci <= P_; ++ci) {
                float h;
                uint8_t ok;
                input_.read(std::min<int64_t>(int64_t(ci) * T_, W - 1),
                            std::min<int64_t>(int64_t(cj) * T_, H - 1), 1, 1, &h, &ok);
                if (!ok) h = enc_.fill;
                if (enc_.heights == TileHeights::Int16) {
                    cornerQ_[size_t(cj) * size_t(P_ + 1) + size_t(ci)] = enc_.quantize(h);
                    h = dequantizeHeight(enc_.quantize(h), enc_.scale, enc_.offset);
                }
                coarseH_[size_t(2 * cj) * size_t(cw_) + size_t(2 * ci)] = h;
            }
        if (info_.k < info_.n) {
            const SampleWindow g{.n = info_.n,
                                 .stride = T_ / 2,
                                 .w = cw_,
                                 .h = cw_,
                                 .height = coarseH_.data(),
                                 .error = coarseE_.data(),
                                 .radius = coarseR_.data(),
                                 .sx = info_.spacingX,
                                 .sz = info_.spacingZ,
                                 .vs = info_.verticalScale};
            saturateLevels(g, 2 * (info_.n - info_.k) - 1, 0, threads_,
                           [](int, int) { return false; });
        }
        std::vector<uint8_t> coarse;
        coarse.reserve(hd_.coarseBytes);
        auto putCorner = [&](int i, int j) {
            const size_t c = size_t(2 * (j / T_)) * size_t(cw_) + size_t(2 * (i / T_));
            if (enc_.heights == TileHeights::Int16)
                put<int16_t>(coarse, cornerQ_[size_t(j / T_) * size_t(P_ + 1) + size_t(i / T_)]);
            else
                put<float>(coarse, coarseH_[c]);
            put<float>(coarse, coarseE_[c]);
            put<float>(coarse, coarseR_[c]);
        };
        for (int l = 0; l < 2 * (info_.n - info_.k); ++l)
            forLevelVertices(info_.n, l, 0, S_, 0, S_, SerialRows{},
                             [&](int i, int j, int, int, int, int) { putCorner(i, j); });
        for (int j : {0, S_})
            for (int i : {0, S_}) putCorner(i, j);
        SIERRA_CHECK(coarse.size() == hd_.coarseBytes, "tile build: coarse section of ",
                     coarse.size(), " bytes, expected ", hd_.coarseBytes);
        return coarse;
    }

    const terrain::GridReader& input_;
    const TileFileInfo& info_;
    const Encoding& enc_;
    const TileBuildOptions& options_;
    const int threads_;
    const Layout L_;
    const int T_, P_, S_, cw_;
    int storedX_ = 0, storedY_ = 0;
    std::vector<uint8_t> meta_;
    std::vector<uint64_t> index_;
    // The coarse window: stride T/2 over the grid, tile corners at even
    // positions, tile centres at odd ones.
    std::vector<float> coarseH_, coarseE_, coarseR_;
    std::vector<int16_t> cornerQ_;
    Header hd_{};
    std::FILE* f_ = nullptr;
    uint64_t at_ = 0;
    int64_t written_ = 0;
};

}  // namespace

int autoTileLevels(int64_t width, int64_t height, TileHeights heights, bool noData) {
    const int n = levelsFor(width, height);
    const int top = std::min(8, n), bottom = std::min(4, top);
    std::vector<double> bytes(size_t(top + 1), 0.0);
    for (int k = bottom; k <= top; ++k) {
        const Layout L(n, k, heights);
        const int64_t T = int64_t(1) << k;
        const double stored = double(std::max<int64_t>(1, (width - 1 + T - 1) / T)) *
                              double(std::max<int64_t>(1, (height - 1 + T - 1) / T));
        const double perTile = double(L.chunkEnd.back()) + 8.0 * double(L.entryWords()) +
                               (noData ? double(L.maskBytes()) : 0.0);
        const double corners = double(L.P + 1) * double(L.P + 1) * double(L.heightBytes + 8);
        bytes[size_t(k)] = stored * perTile + corners;
    }
    const double least = *std::min_element(bytes.begin() + bottom, bytes.end());
    int k = top;
    while (bytes[size_t(k)] > 1.05 * least) --k;
    return k;
}

TileBuildReport buildTileFile(const terrain::GridReader& input, const std::string& path,
                              const TileBuildOptions& options) {
    const terrain::GridInfo& in = input.info();
    SIERRA_CHECK(in.width >= 2 && in.height >= 2, "tile build: a ", in.width, "x", in.height,
                 " grid is too small (at least 2x2)");
    const int n = levelsFor(in.width, in.height);
    SIERRA_CHECK(n <= kMaxLevels, "tile build: a ", in.width, "x", in.height,
                 " grid is larger than the ", (1 << kMaxLevels) + 1,
                 "-sample side tile files take");
    SIERRA_CHECK(options.k >= 0, "tile build: tiles of 2^k cells need k >= 1, got ", options.k);
    SIERRA_CHECK(std::isfinite(options.verticalScale) && options.verticalScale > 0.0f,
                 "tile build: the vertical scale must be > 0, got ", options.verticalScale);
    const int threads = options.threads > 0 ? options.threads : defaultThreadCount();
    const Encoding enc = chooseEncoding(input, options, threads);

    TileFileInfo info;
    info.n = n;
    info.k = options.k > 0 ? std::min(options.k, n)
                           : autoTileLevels(in.width, in.height, options.heights, in.hasNoData);
    info.width = in.width;
    info.height = in.height;
    info.heights = options.heights;
    info.heightScale = enc.scale;
    info.heightOffset = enc.offset;
    info.spacingX = in.spacingX;
    info.spacingZ = in.spacingZ;
    info.verticalScale = options.verticalScale;
    info.metres = in.metres;
    info.hasNoData = in.hasNoData;
    info.geoCentre = in.geoCentre;
    info.georeference = in.georeference;

    Builder builder(input, info, enc, options, threads);
    writeFileAtomic(path, [&](std::FILE* f) { builder.write(f); });
    TileBuildReport report;
    report.info = info;
    report.storedTiles = builder.storedTiles();
    report.fileBytes = builder.fileBytes();
    report.bytesPerSample = double(report.fileBytes) / (double(in.width) * double(in.height));
    return report;
}

}  // namespace sierra::sbt
