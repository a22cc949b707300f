// The NumPy loaders of loadHeightfield (HeightfieldIO.cpp): .npy grids of any
// numeric dtype, and the georeferencing an .npz DEM carries beside its grid
// (its members are read by Npz.cpp). The helpers shared by every loader are
// declared in HeightfieldLoaders.h.
#include "HeightfieldLoaders.h"

#include "terrain/Npz.h"

#include <sierra/core/Files.h>
#include <sierra/terrain/FileIO.h>
#include <sierra/terrain/Padding.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <string_view>

namespace sierra::terrain::detail {

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

// The value bytes of a little-endian float or integer dtype ('<f4', '<i8',
// '|u1' ...), 0 for any other.
int numericBytes(const std::string& descr) {
    if (descr.size() != 3 || (descr[0] != '<' && descr[0] != '|')) return 0;
    const int width = descr[2] - '0';
    if (width != 1 && width != 2 && width != 4 && width != 8) return 0;
    if (descr[1] == 'f') return width >= 4 ? width : 0;
    return descr[1] == 'i' || descr[1] == 'u' ? width : 0;
}

// Value k of data in numericBytes' dtype `descr`.
double npyNumber(const std::string& descr, const uint8_t* data, size_t k) {
    const int width = descr[2] - '0';
    const uint8_t* p = data + k * size_t(width);
    if (descr[1] == 'f')
        return width == 4 ? double(std::bit_cast<float>(le32(p))) : std::bit_cast<double>(le64(p));
    const uint64_t bits = width == 1 ? p[0] : width == 2 ? le16(p) : width == 4 ? le32(p) : le64(p);
    if (descr[1] == 'u') return double(bits);
    const int shift = 64 - 8 * width;  // sign-extended
    return double(int64_t(bits << shift) >> shift);
}

// Parses and checks a .npy header (magic, version, C order, a shape tuple).
// `supported` lists the dtypes taken, as the message names them. Throws
// sierra::Error naming `path` for anything else.
NpyHeader parseNpyHeader(const std::string& path, std::span<const uint8_t> bytes,
                         std::initializer_list<const char*> supported) {
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
    NpyHeader out;
    out.dataStart = 8 + lengthBytes + headerLength;
    if (out.dataStart > bytes.size())
        throw Error(msg(path, ": truncated .npy header: ", headerLength,
                        " header bytes announced, the file has ", bytes.size()));
    const std::string_view header(reinterpret_cast<const char*>(bytes.data()) + 8 + lengthBytes,
                                  headerLength);

    // 'descr': a quoted type string ('<f4'); a list would be a structured array.
    size_t at = npyValue(header, "descr");
    if (at == std::string_view::npos)
        throw Error(msg(path, ": .npy header has no 'descr'; not an array written by numpy.save?"));
    at = skipBlanks(header, at);
    std::string& descr = out.descr;
    if (at < header.size() && (header[at] == '\'' || header[at] == '"')) {
        size_t end = header.find(header[at], at + 1);
        if (end != std::string_view::npos) descr = std::string(header.substr(at + 1, end - at - 1));
    }
    std::string names;
    for (const char* name : supported) {
        names += msg(names.empty() ? "" : " ", name);
        if (descr == name) out.valueBytes = numericBytes(descr);
    }
    if (out.valueBytes == 0)
        throw Error(msg(path, ": .npy dtype '",
                        descr.empty() ? std::string(header.substr(at, 16)) : descr,
                        "' is not supported; expected one of ", names, " (little-endian)"));

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
    const std::string_view dims = header.substr(at + 1, close - at - 1);
    out.dims = std::string(dims);
    for (size_t p = 0; p < dims.size();) {
        p = skipBlanks(dims, p);
        if (p >= dims.size()) break;
        if (!std::isdigit(static_cast<unsigned char>(dims[p])))
            throw Error(msg(path, ": .npy header 'shape' (", dims, ") is not a tuple of integers"));
        uint64_t v = 0;
        for (; p < dims.size() && std::isdigit(static_cast<unsigned char>(dims[p])); ++p)
            v = std::min<uint64_t>(v * 10 + (dims[p] - '0'), uint64_t(1) << 40);
        out.shape.push_back(v);
        p = skipBlanks(dims, p);
        if (p < dims.size() && dims[p] == ',') ++p;
    }
    return out;
}

Heightfield loadNpy(const std::string& path, const std::vector<uint8_t>& bytes,
                    const LoadOptions& options) {
    const NpyHeader h = parseNpyHeader(path, bytes, {"<f4", "<f8", "<i2", "<u2", "|u1", "<u1"});
    const std::vector<uint64_t>& shape = h.shape;
    const std::string& descr = h.descr;
    const std::string& dims = h.dims;
    const uint64_t dataStart = h.dataStart;
    if (shape.size() != 2)
        throw Error(
            msg(path, ": .npy array has shape (", dims, "); expected a 2-D array (rows, columns)"));
    const int64_t height = int64_t(shape[0]), width = int64_t(shape[1]);
    checkSize(path, width, height, ".npy array", options);

    const uint64_t need = uint64_t(width) * uint64_t(height) * uint64_t(h.valueBytes);
    if (bytes.size() - dataStart < need)
        throw Error(msg(path, ": truncated .npy data: ", height, "x", width, " ", descr,
                        " values need ", need, " bytes, the file has ", bytes.size() - dataStart));
    Heightfield field{int(width), int(height)};
    auto out = field.samples();
    const uint8_t* p = bytes.data() + dataStart;
    for (size_t k = 0; k < out.size(); ++k) out[k] = float(npyNumber(descr, p, k));
    if (descr[1] == 'f') checkFinite(path, field);
    return field;
}

// Row j becomes row height - 1 - j (byRows), or column i column width - 1 -
// i. For .npy grids, which carry no no-data mask (NaN is refused).
void flip(Heightfield& field, bool byRows) {
    SIERRA_CHECK(!field.hasMask(), "flip: a field with a no-data mask");
    const int w = field.width(), h = field.height();
    std::span<float> v = field.samples();
    if (byRows) {
        for (int j = 0; j < h / 2; ++j)
            std::swap_ranges(v.begin() + ptrdiff_t(j) * w, v.begin() + ptrdiff_t(j + 1) * w,
                             v.begin() + ptrdiff_t(h - 1 - j) * w);
    } else {
        for (int j = 0; j < h; ++j)
            std::reverse(v.begin() + ptrdiff_t(j) * w, v.begin() + ptrdiff_t(j + 1) * w);
    }
}

// An .npz DEM's georeferencing, in either of the forms matplotlib's sample
// DEMs use:
// - scalars dx and dy, the sample spacing. With bounds xmin, xmax, ymin and
//   ymax that span the grid (its samples or its cells, to within a step)
//   inside longitudes -180 ... 360 and latitudes -90 ... 90, dx and dy are
//   degrees; otherwise they are taken in the file's own unit;
// - lists latitude (or lat) and longitude (or lon) of every row and column,
//   in degrees, each strictly monotonic. Rows run north to south in Sierra
//   (north is -z) and columns west to east, so a grid stored south first or
//   east first is flipped to that order; the spacing is the mean step.
// Degrees become metres on WGS 84 at the grid's middle latitude, and the
// heights are then taken as metres. An archive with neither keeps spacing 1.
namespace {
// The reference system of an .npz's degrees: WGS 84 geographic, longitude
// east first as the geotransform's X (GDAL's traditional GIS axis order).
constexpr const char* kWgs84Wkt =
    "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],"
    "PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433],AUTHORITY[\"EPSG\",\"4326\"]]";
}  // namespace

void applyNpzGeoreference(const std::string& path, const std::vector<uint8_t>& bytes,
                          Heightfield& field) {
    // Numbers and lists of numbers (0-d and 1-d arrays of a little-endian
    // float or integer type) among the archive's small members, by name;
    // members of any other kind are no georeferencing and are skipped.
    const size_t longest = size_t(std::max(field.width(), field.height()));
    std::map<std::string, std::vector<double>> numbers;
    for (auto& [name, npy] : npzSmallMembers(path, bytes, 4096 + 8 * uint64_t(longest))) {
        NpyHeader h;
        try {
            h = parseNpyHeader(name, npy,
                               {"<f4", "<f8", "<i1", "<i2", "<i4", "<i8", "|i1", "<u1", "|u1",
                                "<u2", "<u4", "<u8"});
        } catch (const Error&) {
            continue;
        }
        const uint64_t count = h.shape.empty() ? 1 : h.shape[0];
        if (h.shape.size() > 1 || count == 0 || count > longest ||
            npy.size() - h.dataStart < count * uint64_t(h.valueBytes))
            continue;
        std::vector<double>& values = numbers[name];
        for (size_t k = 0; k < count; ++k)
            values.push_back(npyNumber(h.descr, npy.data() + h.dataStart, k));
    }
    auto scalar = [&](const char* name) -> std::optional<double> {
        auto it = numbers.find(name);
        if (it == numbers.end() || it->second.size() != 1) return std::nullopt;
        return it->second[0];
    };
    auto list = [&](std::initializer_list<const char*> names,
                    int length) -> const std::vector<double>* {
        for (const char* name : names)
            if (auto it = numbers.find(name);
                it != numbers.end() && it->second.size() == size_t(length))
                return &it->second;
        return nullptr;
    };
    auto toMetres = [&](double east, double north, double latitude) {
        const auto [x, z] = degreesToMetres(east, north, latitude);
        field.setSpacing(float(x), float(z));
        field.setMetres(true);
    };
    const std::optional<double> dx = scalar("dx"), dy = scalar("dy");
    if (dx || dy) {
        if (!dx || !dy)
            throw Error(msg(path, ": has ", dx ? "dx" : "dy", " but not ", dx ? "dy" : "dx",
                            "; a georeferenced .npz gives both sample spacings"));
        for (auto [name, v] : {std::pair{"dx", *dx}, std::pair{"dy", *dy}})
            if (!(v > 0.0) || !std::isfinite(v) || v > 1e9)
                throw Error(msg(path, ": ", name, " = ", v,
                                " is not a usable sample spacing (a positive, finite number)"));
        const std::optional<double> x0 = scalar("xmin"), x1 = scalar("xmax"), y0 = scalar("ymin"),
                                    y1 = scalar("ymax");
        auto spans = [](double a, double b, double step, int samples) {
            const double steps = std::abs(b - a) / step;
            return steps >= double(samples) - 2.0 && steps <= double(samples) + 1.0;
        };
        auto within = [](double a, double b, double lo, double hi) {
            return std::min(a, b) >= lo && std::max(a, b) <= hi;
        };
        if (x0 && x1 && y0 && y1 && within(*x0, *x1, -180.0, 360.0) &&
            within(*y0, *y1, -90.0, 90.0) && spans(*x0, *x1, *dx, field.width()) &&
            spans(*y0, *y1, *dy, field.height())) {
            toMetres(*dx, *dy, 0.5 * (*y0 + *y1));
            field.setGeoCentre(Heightfield::GeoPoint{0.5 * (*y0 + *y1), 0.5 * (*x0 + *x1)});
            // Bounds a step short of the samples are their centres, else the
            // cells' outer edges. Row 0 is the north (Sierra's -z).
            auto edge = [&](double a, double b, double step, int samples) {
                const double steps = std::abs(b - a) / step;
                return std::abs(steps - samples) <= std::abs(steps - (samples - 1)) ? 0.0
                                                                                    : 0.5 * step;
            };
            const double west = std::min(*x0, *x1) - edge(*x0, *x1, *dx, field.width());
            const double north = std::max(*y0, *y1) + edge(*y0, *y1, *dy, field.height());
            field.setGeoreference(
                Heightfield::Georeference{{west, *dx, 0.0, north, 0.0, -*dy}, kWgs84Wkt});
        } else {
            field.setSpacing(float(*dx), float(*dy));
        }
        return;
    }
    const std::vector<double>* lat = list({"latitude", "lat"}, field.height());
    const std::vector<double>* lon = list({"longitude", "lon"}, field.width());
    if (!lat || !lon) return;
    auto check = [&](const char* what, const std::vector<double>& v, double lo, double hi) {
        const bool rising = v.back() > v.front();
        for (size_t k = 0; k < v.size(); ++k)
            if (!std::isfinite(v[k]) || v[k] < lo || v[k] > hi ||
                (k > 0 && (v[k] > v[k - 1]) != rising) || (k > 0 && v[k] == v[k - 1]))
                throw Error(msg(path, ": its ", what, " list is not ", what,
                                "s in degrees, strictly rising or falling (value ", k, ": ", v[k],
                                ")"));
        return rising;
    };
    if (field.height() < 2 || field.width() < 2) return;
    const bool northward = check("latitude", *lat, -90.0, 90.0);
    const bool eastward = check("longitude", *lon, -180.0, 360.0);
    const double north = std::abs(lat->back() - lat->front()) / double(lat->size() - 1);
    const double east = std::abs(lon->back() - lon->front()) / double(lon->size() - 1);
    toMetres(east, north, 0.5 * (lat->front() + lat->back()));
    field.setGeoCentre(Heightfield::GeoPoint{0.5 * (lat->front() + lat->back()),
                                             0.5 * (lon->front() + lon->back())});
    if (northward) flip(field, true);
    if (!eastward) flip(field, false);
    // After the flips row 0 is the northernmost latitude and column 0 the
    // westernmost longitude; the lists give sample centres.
    const double west = std::min(lon->front(), lon->back()) - 0.5 * east;
    const double top = std::max(lat->front(), lat->back()) + 0.5 * north;
    field.setGeoreference(
        Heightfield::Georeference{{west, east, 0.0, top, 0.0, -north}, kWgs84Wkt});
}

}  // namespace sierra::terrain::detail
