// Mesh export: the OBJ parses back to the same mesh with its materials, the MTL
// names the tile files given, PLY carries per-face zones, STL has every facet.
#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/tin/Export.h>
#include <sierra/tin/Tin.h>

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

namespace {

using namespace sierra;
namespace fs = std::filesystem;

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("sierra_tin_export_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    std::string operator/(const std::string& name) const { return (path / name).string(); }
};

// A 2-zone mesh with a band: lines x = 10 and x = 14 on a 33 x 33 fractal.
tin::TinResult zonedMesh() {
    terrain::Heightfield field =
        terrain::generateDiamondSquare({.size = 33, .seed = 2, .threads = 1});
    field.setSpacing(2.0f, 0.5f);
    field.setVerticalScale(10.0f);
    tin::Constraints c;
    c.vertices = {{10, 0}, {10, 32}, {14, 0}, {14, 32}};
    c.segments = {{0, 1, 1, 3}, {2, 3, 3, 2}};
    c.bands = {{3, 1, 2}};
    return tin::buildTin(field, c, {.maxErrorRel = 0.01});
}

TEST(TinExport, ObjParsesBackToTheSameMesh) {
    TempDir dir;
    const tin::TinResult r = zonedMesh();
    const tin::TinMesh& mesh = r.mesh;
    const std::string obj = dir / "mesh.obj";
    tin::ObjOptions options{.tileImages = {{1, "tiles/grass.png"}, {2, "tiles/rock.png"}},
                            .bandImages = {{{1, 2}, "tiles/grass_rock.png"}},
                            .uvPeriod = 16.0};
    tin::writeObj(obj, mesh, options);
    const tin::ObjFile back = tin::readObj(obj);
    EXPECT_EQ(back.mtllib, "mesh.mtl");
    ASSERT_EQ(back.positions.size(), mesh.vertices.size());
    ASSERT_EQ(back.faces.size(), mesh.triangles.size());
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
        EXPECT_EQ(back.positions[v][0], float(mesh.vertices[v].x) * 2.0f);
        EXPECT_EQ(back.positions[v][1], mesh.heights[v]);
        EXPECT_EQ(back.positions[v][2], float(mesh.vertices[v].y) * 0.5f);
        EXPECT_FLOAT_EQ(back.uvs[v][0], float(mesh.vertices[v].x / 16.0));
        EXPECT_FLOAT_EQ(back.uvs[v][1], float(mesh.vertices[v].y / 16.0));
    }
    // Same triangles (as rotation-normalised vertex triples) with the same materials.
    auto key = [](std::array<int32_t, 3> t) {
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        return t;
    };
    std::map<std::array<int32_t, 3>, std::string> expected;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        expected[key({tri[0], tri[2], tri[1]})] = tin::materialName(mesh.surfaces[t]);
    }
    std::set<std::string> materials;
    for (size_t f = 0; f < back.faces.size(); ++f) {
        auto it = expected.find(key(back.faces[f]));
        ASSERT_NE(it, expected.end()) << "face not in the mesh";
        EXPECT_EQ(it->second, back.faceMaterials[f]);
        EXPECT_EQ(back.faceUvs[f], back.faces[f]);
        materials.insert(back.faceMaterials[f]);
        // Up-facing: counter-clockwise seen from +y means (x, z) clockwise.
        const auto& a = back.positions[size_t(back.faces[f][0])];
        const auto& b = back.positions[size_t(back.faces[f][1])];
        const auto& c = back.positions[size_t(back.faces[f][2])];
        const double ny = (c[0] - a[0]) * (b[2] - a[2]) - (b[0] - a[0]) * (c[2] - a[2]);
        EXPECT_GT(ny, 0.0);
    }
    EXPECT_EQ(materials, (std::set<std::string>{"zone_1", "zone_2", "band_1_2"}));
    const auto textures = tin::readMtlTextures(dir / "mesh.mtl");
    EXPECT_EQ(textures.at("zone_1"), "tiles/grass.png");
    EXPECT_EQ(textures.at("zone_2"), "tiles/rock.png");
    EXPECT_EQ(textures.at("band_1_2"), "tiles/grass_rock.png");
    // No band image: the first surface's tile stands in; no tile: no map_Kd.
    tin::writeObj(dir / "b.obj", mesh,
                  {.mtlPath = dir / "other.mtl", .tileImages = {{1, "g.png"}}});
    const auto other = tin::readMtlTextures(dir / "other.mtl");
    EXPECT_EQ(other.at("band_1_2"), "g.png");
    EXPECT_EQ(other.at("zone_2"), "");
    EXPECT_EQ(tin::readObj(dir / "b.obj").mtllib, "other.mtl");
}

// A binary little-endian PLY as read by its header: every element's rows of
// properties, each property as a double (lists: the count, then the items).
struct PlyFile {
    std::map<std::string, std::vector<std::string>> properties;  // element -> names
    std::map<std::string, std::vector<std::vector<double>>> rows;
};

PlyFile readPly(const std::vector<uint8_t>& bytes) {
    const std::string text(bytes.begin(), bytes.end());
    const size_t end = text.find("end_header\n");
    EXPECT_NE(end, std::string::npos);
    std::istringstream header(text.substr(0, end));
    struct Property {
        std::string name, type, countType;  // countType set for a list
    };
    std::vector<std::pair<std::string, size_t>> elements;
    std::map<std::string, std::vector<Property>> props;
    std::string line;
    std::getline(header, line);
    EXPECT_EQ(line, "ply");
    while (std::getline(header, line)) {
        std::istringstream in(line);
        std::string word;
        in >> word;
        if (word == "format") {
            in >> word;
            EXPECT_EQ(word, "binary_little_endian");
        } else if (word == "element") {
            size_t count = 0;
            in >> word >> count;
            elements.push_back({word, count});
        } else if (word == "property") {
            Property p;
            in >> p.type;
            if (p.type == "list") in >> p.countType >> p.type;
            in >> p.name;
            props[elements.back().first].push_back(p);
        }
    }
    size_t at = end + 11;
    auto value = [&](const std::string& type) {
        double v = 0.0;
        auto get = [&](auto x) {
            EXPECT_LE(at + sizeof(x), bytes.size());
            std::memcpy(&x, &bytes[at], sizeof(x));
            at += sizeof(x);
            return double(x);
        };
        if (type == "uchar")
            v = get(uint8_t());
        else if (type == "int")
            v = get(int32_t());
        else if (type == "float")
            v = get(float());
        else
            ADD_FAILURE() << "PLY type " << type;
        return v;
    };
    PlyFile ply;
    for (const auto& [name, count] : elements) {
        for (const Property& p : props[name]) ply.properties[name].push_back(p.name);
        for (size_t r = 0; r < count; ++r) {
            std::vector<double> row;
            for (const Property& p : props[name]) {
                if (!p.countType.empty()) {
                    const double n = value(p.countType);
                    row.push_back(n);
                    for (int k = 0; k < int(n); ++k) row.push_back(value(p.type));
                } else {
                    row.push_back(value(p.type));
                }
            }
            ply.rows[name].push_back(row);
        }
    }
    EXPECT_EQ(at, bytes.size()) << "bytes after the last element";
    return ply;
}

// The PLY read back by its own header: the vertices, the faces (up-facing) and
// per face the zone and the two surfaces. A band face's zone is the band's own
// zone number (3 here) and surface0, surface1 are the two zones it blends (1, 2);
// a face of one zone has zone = surface0 = surface1.
TEST(TinExport, PlyCarriesEachFacesZoneAndStlEveryFacet) {
    TempDir dir;
    const tin::TinMesh mesh = zonedMesh().mesh;
    tin::writeMesh(dir / "m.PLY", mesh);
    const PlyFile ply = readPly(readFileBytes(dir / "m.PLY"));
    EXPECT_EQ(ply.properties.at("vertex"), (std::vector<std::string>{"x", "y", "z"}));
    EXPECT_EQ(ply.properties.at("face"),
              (std::vector<std::string>{"vertex_indices", "zone", "surface0", "surface1"}));
    const auto& vertices = ply.rows.at("vertex");
    const auto& faces = ply.rows.at("face");
    ASSERT_EQ(vertices.size(), mesh.vertices.size());
    ASSERT_EQ(faces.size(), mesh.triangles.size());
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
        EXPECT_EQ(vertices[v][0], double(float(mesh.vertices[v].x) * 2.0f));
        EXPECT_EQ(vertices[v][1], double(mesh.heights[v]));
        EXPECT_EQ(vertices[v][2], double(float(mesh.vertices[v].y) * 0.5f));
    }
    std::map<int, int> zones;
    int bandFaces = 0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& f = faces[t];
        ASSERT_EQ(f.size(), 7u);
        ASSERT_EQ(f[0], 3.0);
        const auto& tri = mesh.triangles[t];
        EXPECT_EQ((std::array<double, 3>{f[1], f[2], f[3]}),
                  (std::array<double, 3>{double(tri[0]), double(tri[2]), double(tri[1])}));
        EXPECT_EQ(f[4], double(mesh.zone[t]));
        EXPECT_EQ(f[5], double(mesh.surfaces[t][0]));
        EXPECT_EQ(f[6], double(mesh.surfaces[t][1]));
        ++zones[int(f[4])];
        // The zone follows the triangle's side of the lines x = 10 and x = 14.
        double cx = 0.0;
        for (int k = 1; k <= 3; ++k) cx += vertices[size_t(f[size_t(k)])][0] / 2.0 / 3.0;
        const int expected = cx < 10.0 ? 1 : cx < 14.0 ? 3 : 2;
        EXPECT_EQ(int(f[4]), expected) << "face " << t << " centroid x " << cx;
        if (f[4] == 3.0) {
            ++bandFaces;
            EXPECT_EQ(f[5], 1.0);
            EXPECT_EQ(f[6], 2.0);
        } else {
            EXPECT_EQ(f[5], f[4]);
            EXPECT_EQ(f[6], f[4]);
        }
    }
    EXPECT_EQ(zones.size(), 3u);
    EXPECT_GT(bandFaces, 4);
    tin::writeMesh(dir / "m.stl", mesh);
    EXPECT_EQ(fs::file_size(dir / "m.stl"), 84 + 50 * mesh.triangles.size());
    EXPECT_THROW(tin::writeMesh(dir / "m.xyz", mesh), Error);
    EXPECT_FALSE(fs::exists(dir / "m.xyz"));
}

TEST(TinExport, ReaderRejectsMalformedObj) {
    TempDir dir;
    writeFileAtomic(dir / "bad.obj", std::string_view("v 0 0 0\nv 1 0 0\nf 1 2 7\n"));
    EXPECT_THROW(tin::readObj(dir / "bad.obj"), Error);
    writeFileAtomic(dir / "quad.obj",
                    std::string_view("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
    EXPECT_THROW(tin::readObj(dir / "quad.obj"), Error);
    EXPECT_THROW(tin::readObj(dir / "missing.obj"), Error);
}

}  // namespace
