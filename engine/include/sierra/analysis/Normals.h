#pragma once
// Vertex normals of a heightfield, in world units (the heightfield's spacing
// and vertical scale), by the three averaging schemes of Sierra's curvature
// analysis. Quad-based is the default: it averages twice as many vertices as
// the other two and gives the smoothest, least noisy normals.

#include <sierra/terrain/Heightfield.h>

#include <cstdint>
#include <string>
#include <vector>

namespace sierra::analysis {

enum class NormalMethod {
    // Slopes along x and along z, each the mean of the slopes of the two edges
    // to the neighbours on that axis (one edge at the border or beside no-data);
    // the tangents (1, sx, 0) and (0, sz, 1) give n = normalize(-sx, 1, -sz).
    Edge,
    // The four triangles (centre, E, N), (centre, N, W), (centre, W, S),
    // (centre, S, E); the mean of their unit normals, normalised.
    Triangle,
    // The four quads around the vertex over its 8 neighbours; a quad's normal
    // is the mean of the unit normals of its two triangles split through the
    // centre vertex (which is its plane's normal when it is planar); the mean
    // of the four quad normals, normalised.
    Quad,
};

// Returns "edge", "triangle" or "quad".
const char* normalMethodName(NormalMethod method);
// Parses "edge", "triangle" or "quad"; throws sierra::Error naming the choices.
NormalMethod parseNormalMethod(const std::string& name);

struct Vec3 {
    float x = 0.0f, y = 0.0f, z = 0.0f;
};

// Unit normals, one per sample, row-major like the heightfield (index
// j * width + i). Triangles or edges that would use a sample outside the grid
// or without data are left out of the average; a no-data sample's normal is
// NaN, and a valid sample with no usable triangle gets (0, 1, 0).
struct NormalField {
    int width = 0;
    int height = 0;
    std::vector<Vec3> normals;

    const Vec3& at(int i, int j) const { return normals[size_t(j) * size_t(width) + size_t(i)]; }
};

// Samples below which the analysis passes run on the calling thread: fewer
// than this cost less (about a millisecond) than waking the thread pool pays back.
inline constexpr int64_t kParallelMinSamples = 32768;

// threads: 0 = sierra::defaultThreadCount(). The result does not depend on
// the thread count. Throws sierra::Error for an empty heightfield.
NormalField computeNormals(const terrain::Heightfield& field,
                           NormalMethod method = NormalMethod::Quad, int threads = 0);

}  // namespace sierra::analysis
