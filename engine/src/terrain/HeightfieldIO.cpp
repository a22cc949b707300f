#include <sierra/terrain/HeightfieldIO.h>

#include "terrain/Npz.h"

#include <sierra/terrain/FileIO.h>
#include <sierra/terrain/Padding.h>

#include <stb/stb_image.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string_view>

#ifdef SIERRA_WITH_GDAL
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#endif

namespace sierra::terrain {
namespace {

// Largest side a loader accepts, as Heightfield does: 65537 = 2^16 + 1.
constexpr int kMaxSide = 65537;

// SRTM tile sides: 3 arc-second (SRTM3, ~90 m) and 1 arc-second (SRTM1, ~30 m).
constexpr int kSrtm3Side = 1201;
constexpr int kSrtm1Side = 3601;
constexpr int16_t kSrtmNoData = -32768;

const char* const kSupported =
    ".png .pgm .r16 .r32 .hgt .npy .npz"
#ifdef SIERRA_WITH_GDAL
    " .tif .tiff";
#else
    " (.tif/.tiff need a build with SIERRA_WITH_GDAL=ON)";
#endif

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// Rejects a size before anything is allocated for it.
void checkSize(const std::string& path, int64_t width, int64_t height, const char* what) {
    if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide)
        throw Error(msg(path, ": ", what, " size ", width, "x", height, " is outside 1..", kMaxSide,
                        " samples per side"));
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

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

Heightfield loadPng(const std::string& path, const std::vector<uint8_t>& bytes) {
    static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature, 8) != 0)
        throw Error(msg(path,
                        ": not a PNG file (no PNG signature); expected an 8- or 16-bit "
                        "greyscale PNG"));
    if (bytes.size() > size_t(INT_MAX))
        throw Error(
            msg(path, ": PNG of ", bytes.size(), " bytes is too large to decode (limit 2 GiB)"));
    const int size = int(bytes.size());
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes.data(), size, &width, &height, &channels))
        throw Error(msg(path, ": unreadable PNG header (stb_image: ", stbi_failure_reason(),
                        "); expected an 8- or 16-bit greyscale PNG"));
    checkSize(path, width, height, "PNG");
    const bool sixteen = stbi_is_16_bit_from_memory(bytes.data(), size) != 0;
    std::unique_ptr<void, StbFree> pixels(
        sixteen ? static_cast<void*>(
                      stbi_load_16_from_memory(bytes.data(), size, &width, &height, &channels, 0))
                : static_cast<void*>(
                      stbi_load_from_memory(bytes.data(), size, &width, &height, &channels, 0)));
    if (!pixels)
        throw Error(msg(path, ": cannot decode PNG (stb_image: ", stbi_failure_reason(),
                        "); the file is truncated or corrupt"));
    Heightfield field(width, height);
    auto out = field.samples();
    const size_t count = out.size();
    if (sixteen) {
        auto* p = static_cast<const uint16_t*>(pixels.get());
        for (size_t k = 0; k < count; ++k) out[k] = float(p[k * channels]);
    } else {
        auto* p = static_cast<const uint8_t*>(pixels.get());
        for (size_t k = 0; k < count; ++k) out[k] = float(p[k * channels]);
    }
    return field;
}

// ---------------------------------------------------------------------------- PGM

class PgmReader {
  public:
    PgmReader(const std::string& path, const std::vector<uint8_t>& bytes)
        : path_(path), bytes_(bytes) {}

    Heightfield load() {
        if (bytes_.size() < 2 || bytes_[0] != 'P' || (bytes_[1] != '2' && bytes_[1] != '5'))
            throw Error(msg(path_, ": not a greyscale PGM (magic must be P2 or P5)"));
        const bool binary = bytes_[1] == '5';
        pos_ = 2;
        const uint64_t width = headerNumber("width");
        const uint64_t height = headerNumber("height");
        const uint64_t maxval = headerNumber("maxval");
        checkSize(path_, int64_t(std::min<uint64_t>(width, INT_MAX)),
                  int64_t(std::min<uint64_t>(height, INT_MAX)), "PGM");
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
    checkSize(path, width, height, "raw");
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

// ---------------------------------------------------------------------------- SRTM

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
    // Nominal ground spacing in metres (exact along north-south; east-west it
    // shrinks with the cosine of the latitude, which the file does not give).
    const float spacing = side == kSrtm3Side ? 90.0f : 30.0f;
    field.setSpacing(spacing, spacing);
    return field;
}

// ---------------------------------------------------------------------------- NumPy

// Finds `key` (quoted either way) in a .npy header dictionary and returns the
// position just after its ':', or npos.
size_t npyValue(std::string_view header, std::string_view key) {
    for (char q : {'\'', '"'}) {
        std::string quoted(1, q);
        quoted.append(key);
        quoted.push_back(q);
        size_t at = header.find(quoted);
        if (at == std::string_view::npos) continue;
        size_t colon = header.find(':', at + quoted.size());
        if (colon != std::string_view::npos) return colon + 1;
    }
    return std::string_view::npos;
}

size_t skipBlanks(std::string_view s, size_t pos) {
    while (pos < s.size() && std::isspace(static_cast<unsigned char>(s[pos]))) ++pos;
    return pos;
}

Heightfield loadNpy(const std::string& path, const std::vector<uint8_t>& bytes) {
    static const uint8_t kMagic[6] = {0x93, 'N', 'U', 'M', 'P', 'Y'};
    if (bytes.size() < 10 || std::memcmp(bytes.data(), kMagic, 6) != 0)
        throw Error(msg(path, ": not a NumPy .npy file (no \\x93NUMPY magic)"));
    const int major = bytes[6], minor = bytes[7];
    if (major != 1 && major != 2)
        throw Error(msg(path, ": .npy format version ", major, ".", minor,
                        " is not supported; expected 1.0 or 2.0 (numpy.save writes 1.0)"));
    const size_t lengthBytes = major == 1 ? 2 : 4;
    if (bytes.size() < 8 + lengthBytes) throw Error(msg(path, ": truncated .npy header"));
    const uint64_t headerLength = major == 1 ? le16(&bytes[8]) : le32(&bytes[8]);
    const uint64_t dataStart = 8 + lengthBytes + headerLength;
    if (dataStart > bytes.size())
        throw Error(msg(path, ": truncated .npy header: ", headerLength,
                        " header bytes announced, the file has ", bytes.size()));
    const std::string_view header(reinterpret_cast<const char*>(bytes.data()) + 8 + lengthBytes,
                                  headerLength);

    // 'descr': a quoted type string ('<f4'); a list would be a structured array.
    size_t at = npyValue(header, "descr");
    if (at == std::string_view::npos)
        throw Error(msg(path, ": .npy header has no 'descr'; not an array written by numpy.save?"));
    at = skipBlanks(header, at);
    std::string descr;
    if (at < header.size() && (header[at] == '\'' || header[at] == '"')) {
        size_t end = header.find(header[at], at + 1);
        if (end != std::string_view::npos) descr = std::string(header.substr(at + 1, end - at - 1));
    }
    struct DType {
        const char* name;
        int bytes;
    };
    static const DType kTypes[] = {{"<f4", 4}, {"<f8", 8}, {"<i2", 2},
                                   {"<u2", 2}, {"|u1", 1}, {"<u1", 1}};
    const DType* type = nullptr;
    for (const DType& t : kTypes)
        if (descr == t.name) type = &t;
    if (!type)
        throw Error(msg(path, ": .npy dtype '",
                        descr.empty() ? std::string(header.substr(at, 16)) : descr,
                        "' is not supported; expected one of <f4 <f8 <i2 <u2 |u1 (little-endian)"));

    at = npyValue(header, "fortran_order");
    if (at == std::string_view::npos)
        throw Error(msg(path, ": .npy header has no 'fortran_order'"));
    at = skipBlanks(header, at);
    if (header.substr(at, 4) == "True")
        throw Error(msg(path,
                        ": .npy array is in Fortran order; save a C-order array "
                        "(numpy.ascontiguousarray) instead"));
    if (header.substr(at, 5) != "False")
        throw Error(msg(path, ": .npy header 'fortran_order' must be True or False"));

    at = npyValue(header, "shape");
    if (at == std::string_view::npos) throw Error(msg(path, ": .npy header has no 'shape'"));
    at = skipBlanks(header, at);
    if (at >= header.size() || header[at] != '(')
        throw Error(msg(path, ": .npy header 'shape' is not a tuple"));
    size_t close = header.find(')', at);
    if (close == std::string_view::npos)
        throw Error(msg(path, ": .npy header 'shape' tuple is not closed"));
    std::vector<uint64_t> shape;
    const std::string_view dims = header.substr(at + 1, close - at - 1);
    for (size_t p = 0; p < dims.size();) {
        p = skipBlanks(dims, p);
        if (p >= dims.size()) break;
        if (!std::isdigit(static_cast<unsigned char>(dims[p])))
            throw Error(msg(path, ": .npy header 'shape' (", dims, ") is not a tuple of integers"));
        uint64_t v = 0;
        for (; p < dims.size() && std::isdigit(static_cast<unsigned char>(dims[p])); ++p)
            v = std::min<uint64_t>(v * 10 + (dims[p] - '0'), uint64_t(1) << 40);
        shape.push_back(v);
        p = skipBlanks(dims, p);
        if (p < dims.size() && dims[p] == ',') ++p;
    }
    if (shape.size() != 2)
        throw Error(
            msg(path, ": .npy array has shape (", dims, "); expected a 2-D array (rows, columns)"));
    const int64_t height = int64_t(shape[0]), width = int64_t(shape[1]);
    checkSize(path, width, height, ".npy array");

    const uint64_t need = uint64_t(width) * uint64_t(height) * uint64_t(type->bytes);
    if (bytes.size() - dataStart < need)
        throw Error(msg(path, ": truncated .npy data: ", height, "x", width, " ", descr,
                        " values need ", need, " bytes, the file has ", bytes.size() - dataStart));
    Heightfield field{int(width), int(height)};
    auto out = field.samples();
    const uint8_t* p = bytes.data() + dataStart;
    for (size_t k = 0; k < out.size(); ++k) {
        switch (descr[1]) {
            case 'f':
                out[k] = type->bytes == 4 ? std::bit_cast<float>(le32(p + 4 * k))
                                          : float(std::bit_cast<double>(le64(p + 8 * k)));
                break;
            case 'i':
                out[k] = float(int16_t(le16(p + 2 * k)));
                break;
            default:
                out[k] = type->bytes == 2 ? float(le16(p + 2 * k)) : float(p[k]);
                break;
        }
    }
    if (descr[1] == 'f') checkFinite(path, field);
    return field;
}

// ---------------------------------------------------------------------------- GeoTIFF

#ifdef SIERRA_WITH_GDAL
Heightfield loadGdal(const std::string& path) {
    GDALAllRegister();
    struct Closer {
        void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
    };
    std::unique_ptr<GDALDataset, Closer> data(
        GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!data) {
        std::string reason = CPLGetLastErrorMsg();
        throw Error(msg("cannot open ", path, " with GDAL: ",
                        reason.empty() ? "not a raster format GDAL recognises" : reason));
    }
    const int width = data->GetRasterXSize(), height = data->GetRasterYSize();
    checkSize(path, width, height, "GeoTIFF");
    GDALRasterBand* band = data->GetRasterBand(1);
    if (!band) throw Error(msg(path, ": GeoTIFF has no raster band"));
    Heightfield field(width, height);
    if (band->RasterIO(GF_Read, 0, 0, width, height, field.samples().data(), width, height,
                       GDT_Float32, 0, 0) != CE_None)
        throw Error(msg(path, ": GDAL cannot read band 1: ", CPLGetLastErrorMsg()));
    int hasNoData = 0;
    const double noData = band->GetNoDataValue(&hasNoData);
    if (hasNoData) {
        std::vector<uint8_t> mask(field.samples().size(), 1);
        bool any = false;
        for (size_t k = 0; k < mask.size(); ++k) {
            float v = field.samples()[k];
            if (v == float(noData) || (std::isnan(noData) && std::isnan(v))) {
                mask[k] = 0;
                field.samples()[k] = 0.0f;
                any = true;
            }
        }
        if (any) {
            field.setMask(std::move(mask));
            fillNoData(field);
        }
    }
    checkFinite(path, field);
    // Ground spacing only from a projected (metric) system; degrees would make
    // the terrain absurdly steep.
    double geo[6];
    const OGRSpatialReference* srs = data->GetSpatialRef();
    if (data->GetGeoTransform(geo) == CE_None && srs && srs->IsProjected())
        field.setSpacing(float(std::abs(geo[1])), float(std::abs(geo[5])));
    return field;
}
#endif

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

}  // namespace

Heightfield loadHeightfield(const std::string& path, const LoadOptions& options) {
    const std::string ext = lowerExtension(path);
    enum class Format { Png, Pgm, R16, R32, Hgt, Npy, Npz, Tiff };
    static const std::pair<const char*, Format> kFormats[] = {
        {".png", Format::Png},  {".pgm", Format::Pgm},  {".r16", Format::R16},
        {".r32", Format::R32},  {".hgt", Format::Hgt},  {".npy", Format::Npy},  {".npz", Format::Npz},
        {".tif", Format::Tiff}, {".tiff", Format::Tiff}};
    const auto known = std::find_if(std::begin(kFormats), std::end(kFormats),
                                    [&](const auto& entry) { return ext == entry.first; });
    if (known == std::end(kFormats))
        throw Error(
            msg(path, ": unknown heightfield extension '", ext, "'; supported: ", kSupported));
    const Format format = known->second;
    if (format == Format::Tiff) {
#ifdef SIERRA_WITH_GDAL
        return loadGdal(path);
#else
        throw Error(msg(path,
                        ": GeoTIFF needs a build with SIERRA_WITH_GDAL=ON "
                        "(apt-get install libgdal-dev); supported here: ",
                        kSupported));
#endif
    }
    const std::vector<uint8_t> bytes = readFileBytes(path);
    switch (format) {
        case Format::Png:
            return loadPng(path, bytes);
        case Format::Pgm:
            return PgmReader(path, bytes).load();
        case Format::R16:
            return loadRaw(path, bytes, false, options);
        case Format::R32:
            return loadRaw(path, bytes, true, options);
        case Format::Hgt:
            return loadHgt(path, bytes);
        case Format::Npy:
            return loadNpy(path, bytes);
        case Format::Npz:
            return loadNpy(path, npzMember(path, bytes));
        case Format::Tiff:
            break;
    }
    throw Error(msg(path, ": internal error: unhandled format"));
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
