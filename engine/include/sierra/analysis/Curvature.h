#pragma once
// Curvature of a heightfield along four grid directions, by four methods.
//
// Directions (the last axis of every CurvatureField, in this order):
//   0: +x        step (1, 0)   length spacingX
//   1: +z        step (0, 1)   length spacingZ
//   2: x+z       step (1, 1)   length hypot(spacingX, spacingZ)
//   3: x-z       step (1, -1)  length hypot(spacingX, spacingZ)
// Opposite directions give the same value, so four are all there are.
//
// Along a direction with step length L (world units), y is the world height
// (stored height * verticalScale) and p, v, n are the previous vertex, the
// vertex and the next one. Equation 1 is  k = |y''| / (1 + y'^2)^(3/2).
//   TwoNormal:   slopes s_v, s_n of the tangent planes at v and n along the
//                direction (from the vertex normals); y'' = (s_n - s_v) / L,
//                y' = s_v, then Equation 1.
//   ThreeNormal: the Equation 1 values of the pairs (p, v) and (v, n), each
//                with y'' = (s_2 - s_1) / L and y' = s_v (the slope at the
//                vertex analysed), averaged.
//   ThreeVertex: edge slopes s1 = (y_v - y_p) / L, s2 = (y_n - y_v) / L;
//                y'' = (s2 - s1) / L, y' = (s1 + s2) / 2, then Equation 1.
//   EdgeAngle:   theta = the angle between the world-space edges v->p and
//                v->n; the value is 1 + cos(theta) clamped to [0, 1]: 0 on a
//                straight line, 1 at a right angle (no Equation 1).
// Reinforcement (distance d > 1, ThreeNormal, ThreeVertex and EdgeAngle): the
// value is multiplied by the same measure taken with the neighbours d steps
// away (step length d * L), which pushes values below 1 down and above 1 up.
// Then: value *= scale; with level control, value = clamp((value - black) /
// (white - black), 0, 1)^(1 / gamma). Signed: the value takes the sign of y''
// (of the near measure; positive = concave/valley, negative = convex/ridge);
// level control then applies to the magnitude.
//
// Border rule (clamp): a vertex whose stencil would leave the grid takes the
// value computed at the nearest vertex whose stencil fits: its coordinates
// clamped, on each axis the direction moves along, to [reach, size - 1 -
// reach] (reach = d, or 1 without reinforcement; TwoNormal reaches one step
// forward only). Along +x or +z a border vertex so repeats its inner
// neighbour's value, i.e. a one-sided stencil; no padded heights are invented.
// Normals at the border are one-sided (see Normals.h).
//
// No data: a no-data sample gets NaN in all four directions; a valid vertex
// gets NaN in a direction whose stencil (the samples its value is computed
// from, after clamping; for the normal methods the vertices whose normals are
// used) contains a no-data sample. Nothing else is NaN: the
// normals of valid samples are built from valid neighbours only, so a no-data
// sample never reaches further than the stencils that include it.

#include <sierra/analysis/Normals.h>
#include <sierra/terrain/Heightfield.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace sierra::analysis {

inline constexpr int kDirectionCount = 4;
// Grid steps (di, dj) of the four directions, in the order above.
inline constexpr std::array<std::array<int, 2>, kDirectionCount> kDirectionSteps{
    {{1, 0}, {0, 1}, {1, 1}, {1, -1}}};

enum class CurvatureMethod { TwoNormal, ThreeNormal, ThreeVertex, EdgeAngle };

// "two-normal", "three-normal", "three-vertex", "edge-angle".
const char* curvatureMethodName(CurvatureMethod method);
// Parses the names above; throws sierra::Error naming the choices.
CurvatureMethod parseCurvatureMethod(const std::string& name);

// What the field holds. SecondDerivative is y'' itself (signed, world units
// 1/length, before Equation 1, scale and levels): a check of the stencils and a
// debug view; it needs an Equation 1 method and no reinforcement.
enum class CurvatureOutput { Curvature, SecondDerivative };

// Level control: maps [black, white] to [0, 1], clamps, then applies
// 1 / gamma (gamma > 1 brightens the mid-tones).
struct Levels {
    bool enabled = false;
    float black = 0.0f;  // values at or below give 0, >= 0
    float white = 1.0f;  // values at or above give 1, > black
    float gamma = 1.0f;  // > 0
    bool operator==(const Levels&) const = default;
};

struct CurvatureOptions {
    CurvatureMethod method = CurvatureMethod::ThreeNormal;
    NormalMethod normals = NormalMethod::Quad;  // for TwoNormal and ThreeNormal
    int distance = 1;    // reinforcement distance in steps; 1 = none, >= 1; TwoNormal needs 1
    float scale = 1.0f;  // multiplies every value, >= 0
    Levels levels;       // off by default
    bool signedValues = false;  // keep the sign of y''
    CurvatureOutput output = CurvatureOutput::Curvature;
    int threads = 0;  // 0 = sierra::defaultThreadCount(); the result does not depend on it
    bool operator==(const CurvatureOptions&) const = default;
};

// Throws sierra::Error with one clear message for a bad option (distance < 1,
// a negative or non-finite scale, bad levels, reinforcement with TwoNormal...).
void validate(const CurvatureOptions& options);

// width x height x 4 float32, row-major, index (j * width + i) * 4 + direction.
struct CurvatureField {
    int width = 0;
    int height = 0;
    float spacingX = 1.0f;  // the heightfield's, for directions in world space
    float spacingZ = 1.0f;
    std::vector<float> values;

    float at(int i, int j, int direction) const {
        return values[(size_t(j) * size_t(width) + size_t(i)) * kDirectionCount +
                      size_t(direction)];
    }
    // The largest magnitude over the 4 directions, ignoring NaN; NaN when all
    // four are NaN (a no-data sample).
    float maxMagnitude(int i, int j) const;
    // The direction (0..3) of maxMagnitude (the first on ties), -1 when all are NaN.
    int maxDirection(int i, int j) const;
};

// Per sample the largest magnitude over the 4 directions (maxMagnitude), in
// row order, no-data (and any non-finite) samples left out: what lines and
// hatches are drawn from.
std::vector<float> largestMagnitudes(const CurvatureField& field);

// The value the top 5% of `values` reach: the one at rank 0.95 (n - 1) in
// ascending order (partially reorders `values`); 0 when it is empty.
float topFivePercent(std::vector<float>& values);

// The scale that brings `top`, a value of a field computed at `scale`, to
// `target` (values are proportional to the scale): scale * target / top;
// `scale` itself when top or target is not a positive finite number or the
// scale is 0.
float scaleToReach(float top, float scale, float target);

// Computes the field; threads as in options. Throws sierra::Error for bad
// options or a grid smaller than the stencil (2 * distance + 1 samples a side,
// at least 3).
CurvatureField computeCurvature(const terrain::Heightfield& field,
                                const CurvatureOptions& options = {});
// The same into `out`, reusing its storage (no page faults for a field of the
// same size: a 2049^2 field is 64 MiB).
void computeCurvature(const terrain::Heightfield& field, const CurvatureOptions& options,
                      CurvatureField& out);

}  // namespace sierra::analysis
