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

TEST(TinExport, PlyCarriesZonesAndStlEveryFacet) {
    TempDir dir;
    const tin::TinMesh mesh = zonedMesh().mesh;
    tin::writeMesh(dir / "m.PLY", mesh);
    const std::vector<uint8_t> ply = readFileBytes(dir / "m.PLY");
    const std::string text(ply.begin(), ply.end());
    const size_t end = text.find("end_header\n");
    ASSERT_NE(end, std::string::npos);
    const std::string header = text.substr(0, end);
    EXPECT_NE(header.find("element face " + std::to_string(mesh.triangles.size())),
              std::string::npos);
    EXPECT_NE(header.find("property int zone"), std::string::npos);
    size_t at = end + 11 + mesh.vertices.size() * 12;
    ASSERT_EQ(ply.size(), at + mesh.triangles.size() * 25);
    for (size_t t = 0; t < mesh.triangles.size(); ++t, at += 25) {
        int32_t zone = 0;
        std::memcpy(&zone, &ply[at + 13], 4);
        EXPECT_EQ(zone, mesh.zone[t]);
    }
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
