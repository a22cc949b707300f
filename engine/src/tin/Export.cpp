#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/tin/Export.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace sierra::tin {

namespace {

std::array<float, 3> worldPosition(const TinMesh& mesh, size_t v) {
    return {float(mesh.vertices[v].x) * mesh.spacingX, mesh.heights[v],
            float(mesh.vertices[v].y) * mesh.spacingZ};
}

// Triangles are counter-clockwise in (x, y) grid coordinates, which with y up
// and grid y along +z faces down; written as (0, 2, 1) they face up.
std::array<int32_t, 3> upward(const std::array<int32_t, 3>& t) {
    return {t[0], t[2], t[1]};
}

void put(std::FILE* f, const std::string& s) {
    if (std::fwrite(s.data(), 1, s.size(), f) != s.size()) throw Error("short write");
}

template <typename T>
void putBinary(std::string& out, T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out.append(bytes, sizeof(T));  // little-endian hosts only (x86-64, aarch64)
}

void checkMesh(const TinMesh& mesh) {
    SIERRA_CHECK(mesh.heights.size() == mesh.vertices.size() &&
                     mesh.surfaces.size() == mesh.triangles.size() &&
                     mesh.zone.size() == mesh.triangles.size(),
                 "sierra::tin: the mesh's per-vertex or per-triangle arrays disagree in size");
}

}  // namespace

std::string materialName(const std::array<int32_t, 2>& s) {
    return s[0] == s[1] ? msg("zone_", s[0]) : msg("band_", s[0], "_", s[1]);
}

std::array<double, 2> uvPeriodOf(const ObjOptions& options, const std::array<int32_t, 2>& s) {
    auto period = [&](int32_t surface) {
        auto it = options.surfacePeriods.find(surface);
        return it == options.surfacePeriods.end()
                   ? std::array<double, 2>{options.uvPeriod, options.uvPeriod}
                   : it->second;
    };
    const std::array<double, 2> a = period(s[0]), b = period(s[1]);
    return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
}

void writeObj(const std::string& path, const TinMesh& mesh, const ObjOptions& options) {
    checkMesh(mesh);
    SIERRA_CHECK(options.uvPeriod > 0.0, "sierra::tin::writeObj: uvPeriod must be positive, got ",
                 options.uvPeriod);
    for (const auto& [surface, period] : options.surfacePeriods)
        SIERRA_CHECK(period[0] > 0.0 && period[1] > 0.0 && std::isfinite(period[0]) &&
                         std::isfinite(period[1]),
                     "sierra::tin::writeObj: the UV period of surface ", surface,
                     " must be positive, got ", period[0], " x ", period[1]);
    SIERRA_CHECK(std::isfinite(options.uvOffset[0]) && std::isfinite(options.uvOffset[1]),
                 "sierra::tin::writeObj: the UV offset must be finite");
    const std::filesystem::path objPath(path);
    const std::string mtlPath =
        options.mtlPath.empty() ? std::filesystem::path(objPath).replace_extension(".mtl").string()
                                : options.mtlPath;
    // mtllib relative to the OBJ's folder when the MTL is beside it.
    std::string mtlRef = mtlPath;
    if (std::filesystem::path(mtlPath).parent_path() == objPath.parent_path())
        mtlRef = std::filesystem::path(mtlPath).filename().string();

    // Triangles grouped by material, in order of first appearance.
    std::map<std::array<int32_t, 2>, std::vector<size_t>> groups;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) groups[mesh.surfaces[t]].push_back(t);

    std::ostringstream mtl;
    mtl << "# Sierra TIN materials: one per surface type, one per band (pair of surface types)\n";
    for (const auto& [surfaces, tris] : groups) {
        mtl << "\nnewmtl " << materialName(surfaces) << "\n";
        auto tile = [&](int32_t s) {
            auto it = options.tileImages.find(s);
            return it == options.tileImages.end() ? std::string() : it->second;
        };
        std::string image;
        if (surfaces[0] == surfaces[1]) {
            image = tile(surfaces[0]);
        } else {
            auto it = options.bandImages.find({surfaces[0], surfaces[1]});
            if (it != options.bandImages.end()) {
                image = it->second;
            } else {
                image = tile(surfaces[0]);
                mtl << "# band of surfaces " << surfaces[0] << " and " << surfaces[1]
                    << ": no blended image given, the first surface's tile stands in\n";
            }
        }
        // The palette colours, or a stable plain colour per material, for viewers without textures.
        auto a = options.surfaceColours.find(surfaces[0]),
             b = options.surfaceColours.find(surfaces[1]);
        if (a != options.surfaceColours.end() && b != options.surfaceColours.end()) {
            mtl << "Ka 0 0 0\nKd";
            for (int shift : {16, 8, 0})
                mtl << " "
                    << (double((a->second >> shift) & 255u) + double((b->second >> shift) & 255u)) /
                           510.0;
            mtl << "\nKs 0 0 0\nillum 1\n";
        } else {
            const uint32_t h = uint32_t(surfaces[0]) * 2654435761u ^ uint32_t(surfaces[1]) * 40503u;
            mtl << "Ka 0 0 0\nKd " << 0.35 + 0.6 * ((h >> 0) & 255) / 255.0 << " "
                << 0.35 + 0.6 * ((h >> 8) & 255) / 255.0 << " "
                << 0.35 + 0.6 * ((h >> 16) & 255) / 255.0 << "\nKs 0 0 0\nillum 1\n";
        }
        if (!image.empty()) mtl << "map_Kd " << image << "\n";
    }
    writeFileAtomic(mtlPath, mtl.str());

    writeFileAtomic(path, [&](std::FILE* f) {
        char line[160];
        put(f, msg("# Sierra TIN: ", mesh.vertices.size(), " vertices, ", mesh.triangles.size(),
                   " triangles, grid ", mesh.gridWidth, " x ", mesh.gridHeight, "\nmtllib ", mtlRef,
                   "\n"));
        for (size_t v = 0; v < mesh.vertices.size(); ++v) {
            const auto p = worldPosition(mesh, v);
            std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", double(p[0]), double(p[1]),
                          double(p[2]));
            put(f, line);
        }
        // One period for every material: one vt per vertex, same index. Otherwise
        // each material's vt lines come before its faces, one per (vertex, period).
        std::map<std::array<double, 2>, std::vector<int32_t>> uvIndex;
        for (const auto& [surfaces, tris] : groups) uvIndex[uvPeriodOf(options, surfaces)];
        const bool shared = uvIndex.size() <= 1;
        int32_t uvCount = 0;
        auto putUv = [&](const GridPoint& g, const std::array<double, 2>& period) {
            std::snprintf(line, sizeof line, "vt %.9g %.9g\n",
                          (g.x + options.uvOffset[0]) / period[0],
                          (g.y + options.uvOffset[1]) / period[1]);
            put(f, line);
            return uvCount++;
        };
        if (shared)
            for (const GridPoint& g : mesh.vertices)
                putUv(g, uvPeriodOf(options, groups.empty() ? std::array<int32_t, 2>{0, 0}
                                                            : groups.begin()->first));
        for (const auto& [surfaces, tris] : groups) {
            const std::array<double, 2> period = uvPeriodOf(options, surfaces);
            std::vector<int32_t>& uv = uvIndex[period];
            if (!shared) {
                if (uv.empty()) uv.assign(mesh.vertices.size(), -1);
                for (size_t t : tris)
                    for (int32_t v : mesh.triangles[t])
                        if (uv[size_t(v)] < 0)
                            uv[size_t(v)] = putUv(mesh.vertices[size_t(v)], period);
            }
            put(f, "usemtl " + materialName(surfaces) + "\n");
            for (size_t t : tris) {
                const auto tri = upward(mesh.triangles[t]);
                int32_t vt[3];
                for (int k = 0; k < 3; ++k) vt[k] = shared ? tri[k] : uv[size_t(tri[k])];
                std::snprintf(line, sizeof line, "f %d/%d %d/%d %d/%d\n", tri[0] + 1, vt[0] + 1,
                              tri[1] + 1, vt[1] + 1, tri[2] + 1, vt[2] + 1);
                put(f, line);
            }
        }
    });
}

void writePly(const std::string& path, const TinMesh& mesh) {
    checkMesh(mesh);
    std::string out =
        msg("ply\nformat binary_little_endian 1.0\ncomment Sierra TIN, grid ", mesh.gridWidth,
            " x ", mesh.gridHeight, "\nelement vertex ", mesh.vertices.size(),
            "\nproperty float x\nproperty float y\nproperty float z\nelement face ",
            mesh.triangles.size(),
            "\nproperty list uchar int vertex_indices\nproperty int zone\nproperty int surface0\n"
            "property int surface1\nend_header\n");
    out.reserve(out.size() + mesh.vertices.size() * 12 + mesh.triangles.size() * 25);
    for (size_t v = 0; v < mesh.vertices.size(); ++v)
        for (float c : worldPosition(mesh, v)) putBinary(out, c);
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        putBinary(out, uint8_t(3));
        for (int32_t i : upward(mesh.triangles[t])) putBinary(out, i);
        putBinary(out, mesh.zone[t]);
        putBinary(out, mesh.surfaces[t][0]);
        putBinary(out, mesh.surfaces[t][1]);
    }
    writeFileAtomic(path, std::string_view(out));
}

void writeStl(const std::string& path, const TinMesh& mesh) {
    checkMesh(mesh);
    std::string out(80, ' ');
    const std::string header = "Sierra TIN";
    out.replace(0, header.size(), header);
    putBinary(out, uint32_t(mesh.triangles.size()));
    out.reserve(out.size() + mesh.triangles.size() * 50);
    for (const auto& t : mesh.triangles) {
        const auto tri = upward(t);
        const auto a = worldPosition(mesh, size_t(tri[0])), b = worldPosition(mesh, size_t(tri[1])),
                   c = worldPosition(mesh, size_t(tri[2]));
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
                     w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                       u[0] * w[1] - u[1] * w[0]};
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (double& x : n) putBinary(out, float(len > 0 ? x / len : 0.0));
        for (const auto& p : {a, b, c})
            for (float x : p) putBinary(out, x);
        putBinary(out, uint16_t(0));
    }
    writeFileAtomic(path, std::string_view(out));
}

void writeMesh(const std::string& path, const TinMesh& mesh, const ObjOptions& options) {
    const std::string ext = lowerExtension(path);
    if (ext == ".obj")
        writeObj(path, mesh, options);
    else if (ext == ".ply")
        writePly(path, mesh);
    else if (ext == ".stl")
        writeStl(path, mesh);
    else
        throw Error(msg(path, ": unknown mesh format '", ext, "' (use .obj, .ply or .stl)"));
}

ObjFile readObj(const std::string& path) {
    const std::vector<uint8_t> bytes = readFileBytes(path);
    std::istringstream in(std::string(bytes.begin(), bytes.end()));
    ObjFile obj;
    std::string line, material;
    int lineNo = 0;
    auto fail = [&](const std::string& what) { throw Error(msg(path, ":", lineNo, ": ", what)); };
    while (std::getline(in, line)) {
        ++lineNo;
        std::istringstream ls(line);
        std::string key;
        if (!(ls >> key) || key[0] == '#') continue;
        if (key == "v") {
            std::array<float, 3> p{};
            if (!(ls >> p[0] >> p[1] >> p[2])) fail("a vertex needs three numbers");
            obj.positions.push_back(p);
        } else if (key == "vt") {
            std::array<float, 2> t{};
            if (!(ls >> t[0] >> t[1])) fail("a texture coordinate needs two numbers");
            obj.uvs.push_back(t);
        } else if (key == "f") {
            std::array<int32_t, 3> f{}, ft{};
            std::string corner;
            int n = 0;
            while (ls >> corner) {
                if (n == 3) fail("only triangles are supported");
                int vi = 0, ti = 0;
                char* end = nullptr;
                vi = int(std::strtol(corner.c_str(), &end, 10));
                if (end == corner.c_str()) fail("bad face corner '" + corner + "'");
                bool hasT = false;
                if (*end == '/' && end[1] != '/' && end[1] != '\0') {
                    const char* s = end + 1;
                    ti = int(std::strtol(s, &end, 10));
                    if (end == s) fail("bad face corner '" + corner + "'");
                    hasT = true;
                }
                auto resolve = [&](int i, size_t count) {
                    const long r = i > 0 ? i - 1 : long(count) + i;
                    if (i == 0 || r < 0 || r >= long(count))
                        fail(msg("index ", i, " out of range"));
                    return int32_t(r);
                };
                f[size_t(n)] = resolve(vi, obj.positions.size());
                ft[size_t(n)] = hasT ? resolve(ti, obj.uvs.size()) : -1;
                ++n;
            }
            if (n != 3) fail("a face needs three corners");
            obj.faces.push_back(f);
            obj.faceUvs.push_back(ft);
            obj.faceMaterials.push_back(material);
        } else if (key == "usemtl") {
            ls >> material;
        } else if (key == "mtllib") {
            ls >> obj.mtllib;
        }
    }
    return obj;
}

std::map<std::string, std::string> readMtlTextures(const std::string& path) {
    const std::vector<uint8_t> bytes = readFileBytes(path);
    std::istringstream in(std::string(bytes.begin(), bytes.end()));
    std::map<std::string, std::string> out;
    std::string line, current;
    while (std::getline(in, line)) {
        std::istringstream ls(line);
        std::string key;
        if (!(ls >> key)) continue;
        if (key == "newmtl") {
            ls >> current;
            out[current];
        } else if (key == "map_Kd") {
            SIERRA_CHECK(!current.empty(), path, ": map_Kd before any newmtl");
            std::getline(ls >> std::ws, out[current]);
        }
    }
    return out;
}

}  // namespace sierra::tin
