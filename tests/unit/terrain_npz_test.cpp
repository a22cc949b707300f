// NumPy .npz archives built byte by byte: a stored member decodes like the
// .npy it holds, and malformed archives (found by fuzzing among them) are
// refused with one sierra::Error, never undefined behaviour.

#include <sierra/core/Error.h>
#include <sierra/terrain/HeightfieldIO.h>

#include <gtest/gtest.h>
#include <zlib.h>

#include <bit>
#include <cmath>
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

// A 0-d .npy (numpy.savez of a Python float) holding `value` as '<f8', or
// as '<i2' when `integer`.
Bytes scalar(double value, bool integer = false) {
    Bytes out = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0};
    std::string header = std::string("{'descr': '") + (integer ? "<i2" : "<f8") +
                         "', 'fortran_order': False, 'shape': (), }";
    header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ');
    header.push_back('\n');
    put16(out, uint32_t(header.size()));
    out.insert(out.end(), header.begin(), header.end());
    if (integer) {
        put16(out, uint32_t(uint16_t(int16_t(value))));
    } else {
        const uint64_t bits = std::bit_cast<uint64_t>(value);
        put32(out, uint32_t(bits)), put32(out, uint32_t(bits >> 32));
    }
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

// A 4 x 3 DEM (4 columns, 3 rows) with matplotlib's georeferencing scalars.
Bytes georeferenced(double dx, double dy, double xmin, double xmax, double ymin, double ymax) {
    return zipOf({{"elevation.npy", npy(3, 4)},
                  {"dx.npy", scalar(dx)},
                  {"dy.npy", scalar(dy)},
                  {"xmin.npy", scalar(xmin)},
                  {"xmax.npy", scalar(xmax)},
                  {"ymin.npy", scalar(ymin)},
                  {"ymax.npy", scalar(ymax)}});
}

// Geographic bounds: dx and dy are degrees, the spacing becomes metres on
// WGS 84 at the bounds' middle latitude (the ellipsoid's radii of
// curvature), and the heights are taken as metres.
TEST(TerrainNpz, GeographicBoundsGiveMetres) {
    const double step = 1.0 / 1200.0;  // 3 arc-seconds
    const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
    const double radians = 3.14159265358979323846 / 180.0;
    // At the equator: east-west a, north-south a (1 - e^2).
    Heightfield equator = decodeHeightfield(
        "t.npz", georeferenced(step, step, 10.0, 10.0 + 4 * step, -1.5 * step, 1.5 * step));
    EXPECT_TRUE(equator.metres());
    EXPECT_NEAR(equator.spacingX(), step * radians * a, 1e-4);
    EXPECT_NEAR(equator.spacingZ(), step * radians * a * (1.0 - e2), 1e-4);
    EXPECT_NEAR(equator.spacingX(), 92.766, 0.01);  // 111 319 m per degree
    EXPECT_NEAR(equator.spacingZ(), 92.145, 0.01);  // 110 574 m per degree
    // At 60 degrees north (bounds given north first, as matplotlib's
    // Jacksboro DEM has them, and spanning samples rather than cells): east-west
    // shrinks with the cosine.
    Heightfield north = decodeHeightfield(
        "t.npz", georeferenced(step, step, -84.0, -84.0 + 3 * step, 60.0 + step, 60.0 - step));
    const double s = std::sin(60.0 * radians), w = std::sqrt(1.0 - e2 * s * s);
    EXPECT_NEAR(north.spacingX(), step * radians * a / w * 0.5, 1e-4);
    EXPECT_NEAR(north.spacingZ(), step * radians * a * (1.0 - e2) / (w * w * w), 1e-4);
    EXPECT_TRUE(north.metres());
    // The georeference: WGS 84 degrees, pixel corners from the west and north
    // edges; bounds spanning the samples (3 steps for 4 columns) are their
    // centres, so the edges lie half a step outside, and cells' bounds (4
    // steps for 4 columns at the equator) are the edges themselves.
    ASSERT_TRUE(north.georeference().has_value());
    const auto& g = north.georeference()->geoTransform;
    EXPECT_NEAR(g[0], -84.0 - 0.5 * step, 1e-12);
    EXPECT_NEAR(g[1], step, 1e-15);
    EXPECT_NEAR(g[3], 60.0 + 1.5 * step, 1e-12);
    EXPECT_NEAR(g[5], -step, 1e-15);
    EXPECT_EQ(g[2], 0.0);
    EXPECT_EQ(g[4], 0.0);
    EXPECT_NE(north.georeference()->crsWkt.find("EPSG\",\"4326"), std::string::npos);
    ASSERT_TRUE(equator.georeference().has_value());
    EXPECT_NEAR(equator.georeference()->geoTransform[0], 10.0, 1e-12);
    EXPECT_NEAR(equator.georeference()->geoTransform[3], 1.5 * step, 1e-12);
}

// dx and dy without geographic bounds are taken in the file's own unit, and
// the heights' unit stays unknown.
TEST(TerrainNpz, SpacingWithoutGeographicBoundsIsTakenAsGiven) {
    Heightfield plain = decodeHeightfield("t.npz", zipOf({{"elevation.npy", npy(3, 4)},
                                                          {"dx.npy", scalar(25.0)},
                                                          {"dy.npy", scalar(30, true)}}));
    EXPECT_EQ(plain.spacingX(), 25.0f);
    EXPECT_EQ(plain.spacingZ(), 30.0f);
    EXPECT_FALSE(plain.metres());
    EXPECT_FALSE(plain.georeference().has_value());
    // Projected bounds (UTM metres) are not degrees.
    Heightfield utm = decodeHeightfield(
        "t.npz", georeferenced(30.0, 30.0, 500000.0, 500120.0, 4100000.0, 4100090.0));
    EXPECT_EQ(utm.spacingX(), 30.0f);
    EXPECT_FALSE(utm.metres());
    // Bounds that do not span the grid (here 100 steps for 4 samples) are not
    // its georeferencing.
    Heightfield stray = decodeHeightfield("t.npz", georeferenced(0.01, 0.01, 10.0, 11.0, 5.0, 6.0));
    EXPECT_FLOAT_EQ(stray.spacingX(), 0.01f);
    EXPECT_FALSE(stray.metres());
    // No scalars: spacing 1.
    Heightfield none = decodeHeightfield("t.npz", zipOf({{"elevation.npy", npy(3, 4)}}));
    EXPECT_EQ(none.spacingX(), 1.0f);
    EXPECT_FALSE(none.metres());
}

// A float64 .npy list of `values` (a 1-d array).
Bytes list(const std::vector<double>& values) {
    Bytes out = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0};
    std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" +
                         std::to_string(values.size()) + ",), }";
    header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ');
    header.push_back('\n');
    put16(out, uint32_t(header.size()));
    out.insert(out.end(), header.begin(), header.end());
    for (double v : values) {
        const uint64_t bits = std::bit_cast<uint64_t>(v);
        put32(out, uint32_t(bits)), put32(out, uint32_t(bits >> 32));
    }
    return out;
}

// Latitude and longitude lists (matplotlib's topobathy.npz): degrees,
// converted at the middle latitude; rows stored south first, or columns east
// first, are flipped so that row 0 is the north edge and column 0 the west.
TEST(TerrainNpz, LatitudeAndLongitudeListsGiveMetresNorthUp) {
    const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
    const double radians = 3.14159265358979323846 / 180.0;
    // npy(3, 4): row j holds 4j ... 4j + 3.
    const std::vector<double> southFirst = {44.0, 45.0, 46.0}, eastward = {0.0, 0.5, 1.0, 1.5};
    Heightfield dem = decodeHeightfield("t.npz", zipOf({{"topo.npy", npy(3, 4)},
                                                        {"latitude.npy", list(southFirst)},
                                                        {"longitude.npy", list(eastward)}}));
    EXPECT_TRUE(dem.metres());
    const double s = std::sin(45.0 * radians), w = std::sqrt(1.0 - e2 * s * s);
    EXPECT_NEAR(dem.spacingX(), 0.5 * radians * a / w * std::cos(45.0 * radians), 1e-2);
    EXPECT_NEAR(dem.spacingZ(), 1.0 * radians * a * (1.0 - e2) / (w * w * w), 1e-2);
    EXPECT_EQ(dem.at(0, 0), 8.0f) << "the northernmost row (46 degrees) first";
    EXPECT_EQ(dem.at(3, 2), 3.0f);
    // Sample (0, 0) is the north-west one: its pixel centre at 0 E, 46 N.
    ASSERT_TRUE(dem.georeference().has_value());
    const auto& g = dem.georeference()->geoTransform;
    EXPECT_NEAR(g[0] + 0.5 * g[1], 0.0, 1e-12);
    EXPECT_NEAR(g[3] + 0.5 * g[5], 46.0, 1e-12);
    EXPECT_NEAR(g[5], -1.0, 1e-12);
    // Stored north first and east first: the columns are flipped.
    Heightfield eastFirst =
        decodeHeightfield("t.npz", zipOf({{"topo.npy", npy(3, 4)},
                                          {"lat.npy", list({46.0, 45.0, 44.0})},
                                          {"lon.npy", list({-120.0, -120.5, -121.0, -121.5})}}));
    EXPECT_EQ(eastFirst.at(0, 0), 3.0f);
    EXPECT_EQ(eastFirst.at(3, 2), 8.0f);
    EXPECT_NEAR(eastFirst.spacingX(), dem.spacingX(), 1e-3);
    // Lists of another length are not the grid's coordinates.
    Heightfield other = decodeHeightfield("t.npz", zipOf({{"topo.npy", npy(3, 4)},
                                                          {"latitude.npy", list({44.0, 45.0})},
                                                          {"longitude.npy", list(eastward)}}));
    EXPECT_FALSE(other.metres());
    EXPECT_EQ(other.at(0, 0), 0.0f);
    // Coordinates that are not monotonic degrees are refused.
    EXPECT_NE(errorOf(zipOf({{"topo.npy", npy(3, 4)},
                             {"latitude.npy", list({44.0, 46.0, 45.0})},
                             {"longitude.npy", list(eastward)}}))
                  .find("latitude list is not latitudes in degrees"),
              std::string::npos);
    EXPECT_NE(errorOf(zipOf({{"topo.npy", npy(3, 4)},
                             {"latitude.npy", list({44.0, 45.0, 95.0})},
                             {"longitude.npy", list(eastward)}}))
                  .find("value 2: 95"),
              std::string::npos);
}

TEST(TerrainNpz, UnusableSpacingIsRefused) {
    auto with = [](Bytes dx, Bytes dy) {
        std::vector<std::pair<std::string, Bytes>> members = {{"elevation.npy", npy(3, 4)}};
        if (!dx.empty()) members.push_back({"dx.npy", dx});
        if (!dy.empty()) members.push_back({"dy.npy", dy});
        return errorOf(zipOf(members));
    };
    EXPECT_NE(with(scalar(1.0), {}).find("has dx but not dy"), std::string::npos);
    EXPECT_NE(with({}, scalar(1.0)).find("has dy but not dx"), std::string::npos);
    EXPECT_NE(with(scalar(-2.0), scalar(1.0)).find("dx = -2 is not a usable sample spacing"),
              std::string::npos);
    EXPECT_NE(with(scalar(1.0), scalar(std::nan(""))).find("dy = nan"), std::string::npos);
    EXPECT_NE(with(scalar(0.0, true), scalar(1.0)).find("dx = 0"), std::string::npos);
}

}  // namespace
}  // namespace sierra::terrain
