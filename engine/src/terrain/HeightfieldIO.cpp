#include <sierra/terrain/HeightfieldIO.h>

#include "HeightfieldLoaders.h"
#include "terrain/Npz.h"

#include <sierra/core/Files.h>
#include <sierra/terrain/FileIO.h>
#include <sierra/terrain/Maps.h>
#include <sierra/terrain/Padding.h>

#include <spng.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string_view>

#ifdef SIERRA_WITH_GDAL
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#endif

namespace sierra::terrain {
namespace detail {

// Bytes a loader may read beyond the samples themselves: headers, comments,
// PNG chunk framing and deflate block headers (1 MiB is far more than any
// real file's overhead, far less than a hostile one could claim).
constexpr uint64_t kHeaderSlack = uint64_t(1) << 20;

// SRTM tile sides: 3 arc-second (SRTM3, ~90 m) and 1 arc-second (SRTM1, ~30 m).
constexpr int kSrtm3Side = 1201;
constexpr int kSrtm1Side = 3601;
constexpr int16_t kSrtmNoData = -32768;
// WGS 84: semi-major axis in metres, inverse flattening.
constexpr double kWgs84SemiMajor = 6378137.0;
constexpr double kWgs84InverseFlattening = 298.257223563;

const char* const kSupported =
    ".png .pgm .r16 .r32 .hgt .npy .npz"
#ifdef SIERRA_WITH_GDAL
    " .tif .tiff";
#else
    " (.tif/.tiff need a build with SIERRA_WITH_GDAL=ON)";
#endif

// Most samples a field within the limits may hold: width * height never
// exceeds the padded square.
uint64_t maxSamples(const LoadOptions& options) {
    const auto side = uint64_t(std::clamp(options.maxPaddedSide, 3, kMaxSide));
    return side * side;
}

// Rejects a size before anything is allocated for it.
void checkSize(const std::string& path, int64_t width, int64_t height, const char* what,
               const LoadOptions& options) {
    checkFieldSize(msg(path, ": ", what), width, height, options.maxPaddedSide);
}

// Float input must be finite; a no-data value belongs in .hgt or a mask, not NaN.
void checkFinite(const std::string& path, const Heightfield& field) {
    for (int j = 0; j < field.height(); ++j)
        for (int i = 0; i < field.width(); ++i) {
            float v = field.at(i, j);
            if (std::isnan(v))
                throw Error(msg(path, ": NaN height at (", i, ",", j,
                                "); heights must be finite (use a no-data value in .hgt or mask)"));
            if (std::isinf(v))
                throw Error(msg(path, ": infinite height at (", i, ",", j,
                                "); heights must be finite float32 values"));
        }
}

uint16_t le16(const uint8_t* p) {
    return uint16_t(p[0] | (p[1] << 8));
}
uint16_t be16(const uint8_t* p) {
    return uint16_t((p[0] << 8) | p[1]);
}
uint32_t le32(const uint8_t* p) {
    return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}
uint64_t le64(const uint8_t* p) {
    return uint64_t(le32(p)) | (uint64_t(le32(p + 4)) << 32);
}

// ---------------------------------------------------------------------------- PNG

struct SpngFree {
    void operator()(spng_ctx* ctx) const { spng_ctx_free(ctx); }
};

// Ancillary chunk data libspng may keep (text, ICC profiles: a heightmap needs
// none of it): 8 MiB, or the file's size for a larger file. Any one chunk is
// capped at the file's size: a length field claiming more than the file holds
// fails at once.
constexpr size_t kPngChunkCache = size_t(8) << 20;

// How a colour PNG's samples become one height (LoadOptions::channel).
enum class Channel { GreyOnly, Luminance, R, G, B };

Channel parseChannel(const std::string& path, const std::string& name) {
    if (name.empty()) return Channel::GreyOnly;
    if (name == "luminance") return Channel::Luminance;
    if (name == "r") return Channel::R;
    if (name == "g") return Channel::G;
    if (name == "b") return Channel::B;
    throw Error(msg(path, ": unknown channel '", name,
                    "'; expected luminance, r, g or b (or none for a grey heightmap)"));
}

using SpngContext = std::unique_ptr<spng_ctx, SpngFree>;

// A libspng decoder over `bytes` with every CRC checked (ancillary chunks
// included: a damaged file is refused instead of drawn) and the image and chunk
// limits set before anything is read; `ihdr` receives the header, whose size
// is checked against the field limits. `expected` ends the message for a file
// that is not a PNG at all.
SpngContext openPng(const std::string& what, std::span<const uint8_t> bytes, int maxPaddedSide,
                    const char* expected, spng_ihdr& ihdr) {
    static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature, 8) != 0)
        throw Error(msg(what, ": not a PNG file (no PNG signature); expected ", expected));
    SpngContext ctx(spng_ctx_new(0));
    if (!ctx) throw Error(msg(what, ": cannot decode PNG: out of memory for the decoder"));
    const auto check = [&](int err, const char* step) {
        if (err != 0)
            throw Error(msg(what, ": ", step, " (libspng: ", spng_strerror(err),
                            "); the file is truncated or corrupt"));
    };
    check(spng_set_crc_action(ctx.get(), SPNG_CRC_ERROR, SPNG_CRC_ERROR),
          "cannot set up PNG decoding");
    check(spng_set_image_limits(ctx.get(), kMaxSide, kMaxSide), "cannot set up PNG decoding");
    // libspng refuses a chunk limit above the cache limit (SPNG_EINVAL), which
    // made every PNG over 8 MiB unreadable; the cache may then hold up to the
    // file's size, memory the file already takes.
    const size_t chunkLimit = std::min<size_t>(bytes.size(), INT32_MAX);
    check(spng_set_chunk_limits(ctx.get(), chunkLimit, std::max(kPngChunkCache, chunkLimit)),
          "cannot set up PNG decoding");
    check(spng_set_png_buffer(ctx.get(), bytes.data(), bytes.size()), "cannot set up PNG decoding");
    check(spng_get_ihdr(ctx.get(), &ihdr), "unreadable PNG header");
    checkFieldSize(msg(what, ": PNG"), ihdr.width, ihdr.height, maxPaddedSide);
    return ctx;
}

Heightfield loadPng(const std::string& path, const std::vector<uint8_t>& bytes,
                    const LoadOptions& options) {
    const Channel channel = parseChannel(path, options.channel);
    spng_ihdr ihdr{};
    SpngContext ctx =
        openPng(path, bytes, options.maxPaddedSide, "an 8- or 16-bit greyscale PNG", ihdr);
    auto check = [&](int err, const char* what) {
        if (err != 0)
            throw Error(msg(path, ": ", what, " (libspng: ", spng_strerror(err),
                            "); the file is truncated or corrupt"));
    };
    const int width = int(ihdr.width), height = int(ihdr.height);
    const bool grey = ihdr.color_type == SPNG_COLOR_TYPE_GRAYSCALE ||
                      ihdr.color_type == SPNG_COLOR_TYPE_GRAYSCALE_ALPHA;
    if (!grey && channel == Channel::GreyOnly)
        throw Error(msg(path, ": PNG is colour (",
                        ihdr.color_type == SPNG_COLOR_TYPE_INDEXED     ? "palette"
                        : ihdr.color_type == SPNG_COLOR_TYPE_TRUECOLOR ? "RGB"
                                                                       : "RGBA",
                        "); a heightmap must be greyscale (8 or 16 bit), or pick a channel: "
                        "luminance, r, g or b"));
    const bool sixteen = ihdr.bit_depth == 16;
    // Grey: grey+alpha pairs, alpha ignored (grey is expanded to them, 1/2/4-bit
    // scaled to 8; grey+alpha, 8 or 16 bit, is decoded as stored); colour:
    // RGBA (palette expanded). 16-bit samples come host-endian.
    const int fmt = ihdr.color_type == SPNG_COLOR_TYPE_GRAYSCALE_ALPHA ? SPNG_FMT_PNG
                    : grey ? (sixteen ? SPNG_FMT_GA16 : SPNG_FMT_GA8)
                           : (sixteen ? SPNG_FMT_RGBA16 : SPNG_FMT_RGBA8);
    const int components = grey ? 2 : 4;
    const size_t rowBytes = size_t(width) * components * (sixteen ? 2 : 1);

    Heightfield field(width, height);
    auto sample = [&](const uint8_t* row, int i, int c) -> float {
        if (sixteen) {
            uint16_t v;
            std::memcpy(&v, row + (size_t(i) * components + c) * 2, 2);  // host-endian
            return float(v);
        }
        return float(row[size_t(i) * components + c]);
    };
    auto convertRow = [&](const uint8_t* row, int j) {
        for (int i = 0; i < width; ++i) {
            float h = 0.0f;
            if (grey) {
                h = sample(row, i, 0);
            } else {
                switch (channel) {
                    case Channel::R:
                        h = sample(row, i, 0);
                        break;
                    case Channel::G:
                        h = sample(row, i, 1);
                        break;
                    case Channel::B:
                        h = sample(row, i, 2);
                        break;
                    default:  // Rec. 709 luma weights on the stored values
                        h = 0.2126f * sample(row, i, 0) + 0.7152f * sample(row, i, 1) +
                            0.0722f * sample(row, i, 2);
                        break;
                }
            }
            field.at(i, j) = h;
        }
    };
    check(spng_decode_image(ctx.get(), nullptr, 0, fmt, SPNG_DECODE_PROGRESSIVE),
          "cannot decode PNG");
    // Row by row: a non-interlaced image never needs more than one decoded row
    // besides the heights. An interlaced one fills rows over seven passes, so it
    // is decoded into a whole image first.
    std::vector<uint8_t> pixels(ihdr.interlace_method ? rowBytes * height : rowBytes);
    int err = 0;
    for (;;) {
        spng_row_info info{};
        err = spng_get_row_info(ctx.get(), &info);
        if (err != 0) break;
        uint8_t* row = pixels.data() + (ihdr.interlace_method ? rowBytes * info.row_num : 0);
        err = spng_decode_row(ctx.get(), row, rowBytes);
        if (err != 0 && err != SPNG_EOI) break;
        if (!ihdr.interlace_method) convertRow(row, int(info.row_num));
        if (err == SPNG_EOI) break;
    }
    if (err != SPNG_EOI) check(err, "cannot decode PNG");
    // The rows end with the deflate stream, before the last IDAT's CRC and the
    // chunks after it: read on to IEND so those CRCs are checked too.
    check(spng_decode_chunks(ctx.get()), "cannot decode PNG");
    if (ihdr.interlace_method)
        for (int j = 0; j < height; ++j) convertRow(pixels.data() + rowBytes * j, j);
    return field;
}

}  // namespace detail

using namespace detail;

RgbImage decodePngRgb8(const std::string& what, std::span<const uint8_t> bytes, int maxPaddedSide) {
    spng_ihdr ihdr{};
    SpngContext ctx = openPng(what, bytes, maxPaddedSide, "a colour PNG", ihdr);
    RgbImage image;
    image.width = int(ihdr.width);
    image.height = int(ihdr.height);
    size_t size = 0;
    int err = spng_decoded_image_size(ctx.get(), SPNG_FMT_RGB8, &size);
    if (err == 0) {
        image.rgb.resize(size);
        err = spng_decode_image(ctx.get(), image.rgb.data(), size, SPNG_FMT_RGB8, 0);
    }
    // Read on to IEND so the CRCs of the chunks after the image are checked too.
    if (err == 0) err = spng_decode_chunks(ctx.get());
    if (err != 0)
        throw Error(msg(what, ": cannot decode PNG (libspng: ", spng_strerror(err),
                        "); the file is truncated or corrupt"));
    return image;
}

namespace detail {

// ---------------------------------------------------------------------------- PGM

class PgmReader {
  public:
    PgmReader(const std::string& path, const std::vector<uint8_t>& bytes,
              const LoadOptions& options)
        : path_(path), bytes_(bytes), options_(options) {}

    Heightfield load() {
        if (bytes_.size() < 2 || bytes_[0] != 'P' || (bytes_[1] != '2' && bytes_[1] != '5'))
            throw Error(msg(path_, ": not a greyscale PGM (magic must be P2 or P5)"));
        const bool binary = bytes_[1] == '5';
        pos_ = 2;
        const uint64_t width = headerNumber("width");
        const uint64_t height = headerNumber("height");
        const uint64_t maxval = headerNumber("maxval");
        checkSize(path_, int64_t(std::min<uint64_t>(width, INT_MAX)),
                  int64_t(std::min<uint64_t>(height, INT_MAX)), "PGM", options_);
        if (maxval < 1 || maxval > 65535)
            throw Error(msg(path_, ": PGM maxval ", maxval, " is outside 1..65535"));
        const uint64_t count = width * height;
        if (binary) {
            // Exactly one whitespace byte separates maxval from the samples.
            if (pos_ >= bytes_.size() || !std::isspace(bytes_[pos_]))
                throw Error(msg(path_, ": truncated PGM: no sample data after the header"));
            ++pos_;
            const uint64_t bytesPerSample = maxval < 256 ? 1 : 2;
            const uint64_t need = count * bytesPerSample;
            if (bytes_.size() - pos_ < need)
                throw Error(msg(path_, ": truncated PGM: ", width, "x", height, " samples need ",
                                need, " bytes of data, the file has ", bytes_.size() - pos_));
            Heightfield field{int(width), int(height)};
            const uint8_t* p = bytes_.data() + pos_;
            for (uint64_t k = 0; k < count; ++k) {
                uint32_t v = bytesPerSample == 1 ? p[k] : be16(p + 2 * k);
                checkMax(v, maxval, k, width);
                field.samples()[k] = float(v);
            }
            return field;
        }
        // P2: every sample takes at least one digit, so a file too short to hold
        // them is refused before allocating.
        if (bytes_.size() - std::min(pos_, bytes_.size()) < count)
            throw Error(msg(path_, ": truncated PGM: ", width, "x", height, " samples but only ",
                            bytes_.size() - pos_, " bytes left"));
        Heightfield field{int(width), int(height)};
        for (uint64_t k = 0; k < count; ++k) {
            skipSpace();
            if (pos_ >= bytes_.size())
                throw Error(
                    msg(path_, ": truncated PGM: sample ", k + 1, " of ", count, " is missing"));
            if (!std::isdigit(bytes_[pos_]))
                throw Error(msg(path_, ": PGM sample at (", k % width, ",", k / width,
                                ") is not a decimal number"));
            uint64_t v = number();
            checkMax(v, maxval, k, width);
            field.samples()[k] = float(v);
        }
        return field;
    }

  private:
    void skipSpace() {
        while (pos_ < bytes_.size()) {
            if (bytes_[pos_] == '#') {
                while (pos_ < bytes_.size() && bytes_[pos_] != '\n') ++pos_;
            } else if (std::isspace(bytes_[pos_])) {
                ++pos_;
            } else {
                break;
            }
        }
    }
    // Digits at pos_, saturated at 2^32 so a long run cannot overflow.
    uint64_t number() {
        uint64_t v = 0;
        while (pos_ < bytes_.size() && std::isdigit(bytes_[pos_])) {
            v = std::min<uint64_t>(v * 10 + (bytes_[pos_] - '0'), uint64_t(1) << 32);
            ++pos_;
        }
        return v;
    }
    uint64_t headerNumber(const char* name) {
        skipSpace();
        if (pos_ >= bytes_.size() || !std::isdigit(bytes_[pos_]))
            throw Error(msg(path_, ": bad PGM header: expected the ", name,
                            " as a decimal number at byte ", pos_));
        return number();
    }
    void checkMax(uint64_t v, uint64_t maxval, uint64_t k, uint64_t width) const {
        if (v > maxval)
            throw Error(msg(path_, ": PGM sample ", v, " at (", k % width, ",", k / width,
                            ") exceeds the header's maxval ", maxval));
    }

    const std::string& path_;
    const std::vector<uint8_t>& bytes_;
    const LoadOptions& options_;
    size_t pos_ = 0;
};

// ---------------------------------------------------------------------------- raw

Heightfield loadRaw(const std::string& path, const std::vector<uint8_t>& bytes, bool isFloat,
                    const LoadOptions& options) {
    const uint64_t sampleBytes = isFloat ? 4 : 2;
    const char* type = isFloat ? "float32" : "uint16";
    int64_t width = options.rawWidth, height = options.rawHeight;
    if (width < 0 || height < 0 || (width == 0) != (height == 0))
        throw Error(msg(path, ": raw size ", width, "x", height,
                        " is incomplete; give both LoadOptions rawWidth and rawHeight, or neither "
                        "to guess a square"));
    if (width == 0) {
        const uint64_t count = bytes.size() / sampleBytes;
        const auto side = int64_t(std::llround(std::sqrt(double(count))));
        if (count == 0 || bytes.size() % sampleBytes != 0 || uint64_t(side * side) != count)
            throw Error(msg(path, ": cannot guess the size of a raw file of ", bytes.size(),
                            " bytes (not a square grid of ", type,
                            " samples); pass rawWidth and rawHeight"));
        width = height = side;
    }
    checkSize(path, width, height, "raw", options);
    const uint64_t need = uint64_t(width) * uint64_t(height) * sampleBytes;
    if (bytes.size() < need)
        throw Error(msg(path, ": truncated raw file: ", width, "x", height, " ", type,
                        " samples need ", need, " bytes, the file has ", bytes.size()));
    if (bytes.size() > need)
        throw Error(msg(path, ": raw file has ", bytes.size(), " bytes but ", width, "x", height,
                        " ", type, " samples are ", need, " bytes; check rawWidth and rawHeight"));
    Heightfield field{int(width), int(height)};
    auto out = field.samples();
    for (size_t k = 0; k < out.size(); ++k)
        out[k] = isFloat ? std::bit_cast<float>(le32(&bytes[4 * k])) : float(le16(&bytes[2 * k]));
    if (isFloat) checkFinite(path, field);
    return field;
}

// The exact byte count of a raw file whose size LoadOptions gives, checked
// against the file's size before reading; without a size, the most a square
// grid within the limits can take.
uint64_t rawFileBytes(const std::string& path, bool isFloat, const LoadOptions& options) {
    const uint64_t sampleBytes = isFloat ? 4 : 2;
    const int64_t width = options.rawWidth, height = options.rawHeight;
    if (width <= 0 || height <= 0) return maxSamples(options) * sampleBytes;
    checkSize(path, width, height, "raw", options);
    const uint64_t need = uint64_t(width) * uint64_t(height) * sampleBytes;
    const uint64_t have = regularFileSize(path);
    if (have != need)
        throw Error(msg(path, ": raw file has ", have, " bytes but ", width, "x", height, " ",
                        isFloat ? "float32" : "uint16", " samples are ", need,
                        " bytes; check rawWidth and rawHeight"));
    return need;
}

// ---------------------------------------------------------------------------- SRTM

// Ground spacing in metres of a step of (east, north) radians of longitude
// and latitude at `latitude` radians, on an ellipsoid of semi-major axis `a`
// metres and flattening `f`: the meridian radius of curvature north-south,
// the prime vertical one (shrinking with the cosine of the latitude)
// east-west.
std::pair<double, double> ellipsoidSpacing(double east, double north, double latitude, double a,
                                           double f) {
    const double e2 = f * (2.0 - f);
    const double s = std::sin(latitude);
    const double w = std::sqrt(1.0 - e2 * s * s);
    const double meridian = a * (1.0 - e2) / (w * w * w);
    const double primeVertical = a / w;
    return {east * primeVertical * std::cos(latitude), north * meridian};
}

// Ground spacing in metres of a step of (east, north) degrees at `latitude`
// degrees on WGS 84.
std::pair<double, double> degreesToMetres(double east, double north, double latitude) {
    constexpr double kRadians = 3.14159265358979323846 / 180.0;
    return ellipsoidSpacing(east * kRadians, north * kRadians, latitude * kRadians, kWgs84SemiMajor,
                            1.0 / kWgs84InverseFlattening);
}

// The south-west corner of an SRTM tile from its file name, in whole degrees
// (N45E006.hgt: latitude 45, longitude 6; S12W077.hgt: -12, -77), or nothing
// for a name of another form.
std::optional<std::pair<int, int>> srtmTileCorner(const std::string& path) {
    const std::string name = std::filesystem::path(path).filename().string();
    if (name.size() < 7 || (name[0] != 'N' && name[0] != 'n' && name[0] != 'S' && name[0] != 's'))
        return std::nullopt;
    if (!std::isdigit(static_cast<unsigned char>(name[1])) ||
        !std::isdigit(static_cast<unsigned char>(name[2])))
        return std::nullopt;
    const char ew = char(std::toupper(static_cast<unsigned char>(name[3])));
    if (ew != 'E' && ew != 'W') return std::nullopt;
    for (int k = 4; k < 7; ++k)
        if (!std::isdigit(static_cast<unsigned char>(name[size_t(k)]))) return std::nullopt;
    const int degrees = (name[1] - '0') * 10 + (name[2] - '0');
    const int east = (name[4] - '0') * 100 + (name[5] - '0') * 10 + (name[6] - '0');
    if (degrees > 89 || east > 180) return std::nullopt;
    return std::pair{name[0] == 'N' || name[0] == 'n' ? degrees : -degrees,
                     ew == 'E' ? east : -east};
}

Heightfield loadHgt(const std::string& path, const std::vector<uint8_t>& bytes) {
    int side = 0;
    for (int s : {kSrtm3Side, kSrtm1Side})
        if (bytes.size() == size_t(s) * s * 2) side = s;
    if (side == 0)
        throw Error(msg(path, ": SRTM .hgt file has ", bytes.size(), " bytes; expected ",
                        size_t(kSrtm3Side) * kSrtm3Side * 2, " (1201x1201, SRTM3) or ",
                        size_t(kSrtm1Side) * kSrtm1Side * 2, " (3601x3601, SRTM1)"));
    Heightfield field(side, side);
    std::vector<uint8_t> mask(size_t(side) * side, 1);
    bool anyMissing = false;
    auto out = field.samples();
    for (size_t k = 0; k < out.size(); ++k) {
        auto v = int16_t(be16(&bytes[2 * k]));
        if (v == kSrtmNoData) {
            mask[k] = 0;
            anyMissing = true;
            out[k] = 0.0f;
        } else {
            out[k] = float(v);
        }
    }
    if (anyMissing) {
        field.setMask(std::move(mask));
        fillNoData(field);
    }
    // Ground spacing in metres: 3 or 1 arc-second steps on WGS 84 at the
    // tile's middle latitude, which its name gives (N45E006.hgt: the tile's
    // south-west corner); nominal 90 or 30 m both ways for a file named
    // otherwise.
    const double step = (side == kSrtm3Side ? 3.0 : 1.0) / 3600.0;
    if (const auto corner = srtmTileCorner(path)) {
        const auto [east, north] = degreesToMetres(step, step, corner->first + 0.5);
        field.setSpacing(float(east), float(north));
        field.setGeoCentre(Heightfield::GeoPoint{corner->first + 0.5, corner->second + 0.5});
    } else {
        const float spacing = side == kSrtm3Side ? 90.0f : 30.0f;
        field.setSpacing(spacing, spacing);
    }
    field.setMetres(true);
    return field;
}

// ---------------------------------------------------------------------------- writers

void checkWritable(const std::string& path, const Heightfield& field) {
    if (field.empty()) throw Error(msg("cannot write ", path, ": the heightfield is empty"));
    for (int j = 0; j < field.height(); ++j)
        for (int i = 0; i < field.width(); ++i)
            if (!std::isfinite(field.at(i, j)))
                throw Error(msg("cannot write ", path, ": height at (", i, ",", j,
                                ") is not finite; heights must be finite"));
}

void savePng16(const std::string& path, const Heightfield& field) {
    const auto [lo, hi] = field.range();
    const double scale = hi > lo ? 65535.0 / (double(hi) - double(lo)) : 0.0;
    std::vector<uint16_t> quantised(field.samples().size());
    for (size_t k = 0; k < quantised.size(); ++k) {
        double v = std::round((double(field.samples()[k]) - lo) * scale);
        quantised[k] = uint16_t(std::clamp(v, 0.0, 65535.0));  // masked fill values may lie outside
    }
    writeFileAtomic(path, encodePngGrey16(field.width(), field.height(), quantised));
}

void saveNpy(const std::string& path, const Heightfield& field) {
    std::string header = msg("{'descr': '<f4', 'fortran_order': False, 'shape': (", field.height(),
                             ", ", field.width(), "), }");
    // Pad with spaces so the data starts on a 64-byte boundary, as numpy does.
    const size_t unpadded = 10 + header.size() + 1;
    header.append((64 - unpadded % 64) % 64, ' ');
    header.push_back('\n');
    std::vector<uint8_t> bytes = {
        0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, uint8_t(header.size()), uint8_t(header.size() >> 8)};
    bytes.insert(bytes.end(), header.begin(), header.end());
    bytes.reserve(bytes.size() + field.samples().size() * 4);
    for (float v : field.samples()) {
        uint32_t u = std::bit_cast<uint32_t>(v);
        for (int b = 0; b < 4; ++b) bytes.push_back(uint8_t(u >> (8 * b)));
    }
    writeFileAtomic(path, bytes);
}

}  // namespace detail

void checkFieldSize(const std::string& what, int64_t width, int64_t height, int maxPaddedSide) {
    SIERRA_CHECK(maxPaddedSide >= 3 && maxPaddedSide <= kMaxSide, "maxPaddedSide ", maxPaddedSide,
                 " is outside 3..", kMaxSide);
    if (width > kMaxSide || height > kMaxSide || width < 1 || height < 1)
        throw Error(msg(what, " size ", width, "x", height, " is outside ", kMinSide, "..",
                        kMaxSide, " samples per side"));
    if (width < kMinSide || height < kMinSide)
        throw Error(msg(what, " size ", width, "x", height, ": a heightfield needs at least ",
                        kMinSide, "x", kMinSide, " samples"));
    const int side = paddedSide(int(std::max(width, height)));
    if (side > maxPaddedSide)
        throw Error(
            msg(what, " size ", width, "x", height, " pads to a ", side, "x", side, " grid (",
                int64_t(side) * side, " samples), over the limit of ", maxPaddedSide, "x",
                maxPaddedSide, " samples (maxPaddedSide: ",
                maxPaddedSide == kDefaultMaxPaddedSide
                    ? "the loaders' budget, 1 GiB of float32 heights"
                    : "the largest grid the caller takes, for a renderer its GL's texture size",
                ")"));
}

namespace {

enum class Format { Png, Pgm, R16, R32, Hgt, Npy, Npz, Tiff };

Format formatOf(const std::string& path) {
    const std::string ext = lowerExtension(path);
    static const std::pair<const char*, Format> kFormats[] = {
        {".png", Format::Png}, {".pgm", Format::Pgm},  {".r16", Format::R16},
        {".r32", Format::R32}, {".hgt", Format::Hgt},  {".npy", Format::Npy},
        {".npz", Format::Npz}, {".tif", Format::Tiff}, {".tiff", Format::Tiff}};
    const auto known = std::find_if(std::begin(kFormats), std::end(kFormats),
                                    [&](const auto& entry) { return ext == entry.first; });
    if (known == std::end(kFormats))
        throw Error(
            msg(path, ": unknown heightfield extension '", ext, "'; supported: ", kSupported));
    return known->second;
}

// The most bytes a file of `format` can hold for the largest allowed grid,
// plus some header: a larger file is refused before it is read. Sets `reason`
// to the sentence that says so.
uint64_t maxFileBytes(Format format, const std::string& path, const LoadOptions& options,
                      std::string& reason) {
    const uint64_t samples = maxSamples(options);
    reason =
        msg("a ", lowerExtension(path), " heightmap within the limit of ", options.maxPaddedSide,
            "x", options.maxPaddedSide, " samples (maxPaddedSide) is smaller");
    switch (format) {
        case Format::Png:  // RGBA16 stored uncompressed: 8 bytes a sample, plus framing
            return samples * 8 + samples / 8 + kHeaderSlack;
        case Format::Pgm:  // P5 16-bit: 2 bytes a sample; P2: "65535 " is 6
            return samples * 6 + kHeaderSlack;
        case Format::R16:
            return samples * 2;
        case Format::R32:
            return samples * 4;
        case Format::Hgt:
            reason = "the largest SRTM tile (3601x3601, SRTM1) is 25934402 bytes";
            return uint64_t(kSrtm1Side) * kSrtm1Side * 2;
        case Format::Npy:  // float64: 8 bytes a sample
        case Format::Npz:  // the same array, stored or deflated
            return samples * 8 + kHeaderSlack;
        case Format::Tiff:
            break;
    }
    return 0;
}

Heightfield decode(Format format, const std::string& path, const std::vector<uint8_t>& bytes,
                   const LoadOptions& options) {
    switch (format) {
        case Format::Png:
            return loadPng(path, bytes, options);
        case Format::Pgm:
            return PgmReader(path, bytes, options).load();
        case Format::R16:
            return loadRaw(path, bytes, false, options);
        case Format::R32:
            return loadRaw(path, bytes, true, options);
        case Format::Hgt:
            return loadHgt(path, bytes);
        case Format::Npy:
            return loadNpy(path, bytes, options);
        case Format::Npz: {
            std::string reason;
            Heightfield field = loadNpy(
                path, npzMember(path, bytes, {}, maxFileBytes(format, path, options, reason)),
                options);
            applyNpzGeoreference(path, bytes, field);
            return field;
        }
        case Format::Tiff:
            break;
    }
    throw Error(msg(path, ": internal error: unhandled format"));
}

}  // namespace

Heightfield loadHeightfield(const std::string& path, const LoadOptions& options) {
    const Format format = formatOf(path);
    if (format == Format::Tiff) {
#ifdef SIERRA_WITH_GDAL
        return loadGdal(path, options);
#else
        throw Error(msg(path,
                        ": GeoTIFF needs a build with SIERRA_WITH_GDAL=ON "
                        "(apt-get install libgdal-dev); supported here: ",
                        kSupported));
#endif
    }
    std::string reason;
    uint64_t maxBytes = maxFileBytes(format, path, options, reason);
    // A raw file whose size is given must be exactly that size: checked
    // against the file system before reading.
    if (format == Format::R16 || format == Format::R32)
        maxBytes = rawFileBytes(path, format == Format::R32, options);
    return decode(format, path, readFileBytes(path, maxBytes, reason), options);
}

Heightfield decodeHeightfield(const std::string& name, const std::vector<uint8_t>& bytes,
                              const LoadOptions& options) {
    const Format format = formatOf(name);
    SIERRA_CHECK(format != Format::Tiff, name,
                 ": GeoTIFF is read from files only (loadHeightfield)");
    std::string reason;
    const uint64_t maxBytes = maxFileBytes(format, name, options, reason);
    SIERRA_CHECK(bytes.size() <= maxBytes, name, ": ", bytes.size(),
                 " bytes is too large: ", reason);
    return decode(format, name, bytes, options);
}

void saveHeightfield(const std::string& path, const Heightfield& field) {
    const std::string ext = lowerExtension(path);
    if (ext != ".png" && ext != ".npy")
        throw Error(msg("cannot write ", path, ": unknown extension '", ext,
                        "'; saveHeightfield writes .png (16-bit grey) or .npy (float32)"));
    checkWritable(path, field);
    if (ext == ".png")
        savePng16(path, field);
    else
        saveNpy(path, field);
}

}  // namespace sierra::terrain
