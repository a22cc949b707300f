#pragma once
// The hatch field: per vertex, the direction and opacity of one stroke on the
// vertex's tangent plane (the CPU reference of what the hatch pass computes
// on the GPU from the curvature field).
//
// Direction: the four direction vectors summed with curvature weights
// |k_d|. Opposite directions are the same direction, so the vectors are
// summed as axes: each as (cos 2a_d, sin 2a_d), a_d its world angle in the
// x-z plane (atan2(dj * spacingZ, di * spacingX)), and the sum's angle is
// halved. (Summing fixed-sign vectors would let the arbitrary sign of a
// direction tilt the result: on a cylinder along x the two diagonals would
// pull the stroke 35 degrees off its section.) When the weighted sum is
// nearly zero (as much curvature in every direction, e.g. a round summit) the
// single direction of largest curvature is used. The horizontal axis is then
// lifted onto the tangent plane: Along gives the stroke in the direction of
// greatest curvature (the document's "with"), Across gives cross(normal,
// along), perpendicular to it on the tangent plane.
// Opacity: the largest |k| of the vertex, clamped to [0, 1].

#include <sierra/analysis/Curvature.h>
#include <sierra/analysis/Normals.h>

#include <string>
#include <vector>

namespace sierra::analysis {

enum class HatchDirection { Along, Across };

// "along" / "across".
const char* hatchDirectionName(HatchDirection direction);
// Parses "along" or "across"; throws sierra::Error naming the choices.
HatchDirection parseHatchDirection(const std::string& name);

// The curvature-weighted axis of greatest curvature as a horizontal unit
// vector (ux, uz) in world x-z, from the 4 magnitudes of one vertex (NaN and
// negative weights count as their absolute value, NaN as 0). Returns false,
// leaving ux, uz alone, when all four are zero or NaN.
bool blendedCurvatureAxis(const float curvature[kDirectionCount], float spacingX, float spacingZ,
                          float& ux, float& uz);

// One vertex's stroke direction: a unit world vector on the tangent plane of
// the unit normal n. NaN when the normal is NaN; along +x lifted onto the
// plane when the vertex has no curvature at all (its opacity is then 0).
Vec3 hatchStrokeDirection(const float curvature[kDirectionCount], const Vec3& normal,
                          float spacingX, float spacingZ, HatchDirection direction);

struct HatchOptions {
    HatchDirection direction = HatchDirection::Along;
    NormalMethod normals = NormalMethod::Quad;  // the tangent planes
    int threads = 0;                            // 0 = sierra::defaultThreadCount()
};

// Row-major like the heightfield; NaN direction and opacity for no-data samples.
struct HatchField {
    int width = 0;
    int height = 0;
    std::vector<Vec3> direction;  // unit, world space, on the tangent plane
    std::vector<float> opacity;   // largest |curvature|, clamped to [0, 1]

    size_t index(int i, int j) const { return size_t(j) * size_t(width) + size_t(i); }
};

// Throws sierra::Error when the curvature field's size differs from the heightfield's.
HatchField computeHatchField(const terrain::Heightfield& field, const CurvatureField& curvature,
                             const HatchOptions& options = {});

}  // namespace sierra::analysis
