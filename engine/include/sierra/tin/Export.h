#pragma once
// Writing a TIN as OBJ (with an MTL), PLY and STL, and reading an OBJ back.
//
// World positions: (x * spacingX, height, y * spacingZ), y up; faces are wound
// so that their normals point up (+y). Every file goes through
// sierra::writeFileAtomic: a failed write leaves no half file.

#include <sierra/tin/Tin.h>

#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace sierra::tin {

struct ObjOptions {
    // The MTL file to write beside the OBJ; "" = the OBJ's path with ".mtl".
    std::string mtlPath;
    // Tile image of each surface type (zone number), written as map_Kd exactly as
    // given (relative paths are relative to the MTL). A surface with no image
    // gets a plain colour.
    std::map<int32_t, std::string> tileImages;
    // Image of a band's blended tiles, by its two surface types (first, second).
    // A band with none names the first surface's tile (the MTL says so).
    std::map<std::pair<int32_t, int32_t>, std::string> bandImages;
    // Kd colour (0xRRGGBB) of each surface type; a band gets the mean of its
    // two. A surface with none gets a stable made-up colour.
    std::map<int32_t, uint32_t> surfaceColours;
    // Planar UVs: u = (x + uvOffset[0]) / period x, v = (y + uvOffset[1]) / period y,
    // in grid samples. A surface type's period is its surfacePeriods entry (x, y),
    // a band's the mean of its two surfaces' (its blended image is drawn once),
    // any other uvPeriod on both axes (default 64). Materials with different
    // periods get their own vt lines, so a vertex on a borderline has one UV per
    // period around it.
    double uvPeriod = 64.0;
    std::map<int32_t, std::array<double, 2>> surfacePeriods;
    std::array<double, 2> uvOffset = {0.0, 0.0};
};

// The UV period (grid samples per repetition along x and y) that writeObj
// gives a triangle of these surfaces.
std::array<double, 2> uvPeriodOf(const ObjOptions& options, const std::array<int32_t, 2>& surfaces);

// Material name of a triangle's surfaces: "zone_<a>" or, in a band, "band_<a>_<b>".
std::string materialName(const std::array<int32_t, 2>& surfaces);

// One material group per surface type (and per band pair); throws sierra::Error
// when a file cannot be written.
void writeObj(const std::string& path, const TinMesh& mesh, const ObjOptions& options = {});
// Binary little-endian PLY: float x, y, z per vertex; per face the vertex list
// and int properties zone, surface0, surface1.
void writePly(const std::string& path, const TinMesh& mesh);
// Binary STL with facet normals.
void writeStl(const std::string& path, const TinMesh& mesh);
// By extension: .obj, .ply or .stl (case-insensitive); anything else is an error.
void writeMesh(const std::string& path, const TinMesh& mesh, const ObjOptions& options = {});

// An OBJ as read back: positions, texture coordinates, triangles (0-based
// indices into both) with their material names, and the mtllib named.
struct ObjFile {
    std::vector<std::array<float, 3>> positions;
    std::vector<std::array<float, 2>> uvs;
    std::vector<std::array<int32_t, 3>> faces;
    std::vector<std::array<int32_t, 3>> faceUvs;  // -1 where a corner has no vt
    std::vector<std::string> faceMaterials;
    std::string mtllib;
};
// Reads v, vt, f (triangles, "i", "i/t", "i/t/n" or "i//n"; negative indices
// relative), usemtl and mtllib; ignores other statements. Throws sierra::Error
// naming the file and line for anything malformed.
ObjFile readObj(const std::string& path);
// Material name -> its map_Kd image ("" for none) from an MTL file.
std::map<std::string, std::string> readMtlTextures(const std::string& path);

}  // namespace sierra::tin
