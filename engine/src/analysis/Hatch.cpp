#include <sierra/analysis/Hatch.h>

#include "Internal.h"

#include <sierra/core/Error.h>

#include <cmath>

namespace sierra::analysis {

const char* hatchDirectionName(HatchDirection direction) {
    return direction == HatchDirection::Along ? "along" : "across";
}

HatchDirection parseHatchDirection(const std::string& name) {
    if (name == "along") return HatchDirection::Along;
    if (name == "across") return HatchDirection::Across;
    throw Error(msg("unknown hatch direction '", name, "' (expected along or across)"));
}

bool blendedCurvatureAxis(const float curvature[kDirectionCount], float spacingX, float spacingZ,
                          float& ux, float& uz) {
    float sx = 0.0f, sz = 0.0f, largest = 0.0f;
    int best = -1;
    float bestAngle = 0.0f;
    for (int d = 0; d < kDirectionCount; ++d) {
        float w = std::fabs(curvature[d]);
        if (std::isnan(w)) continue;
        float angle = std::atan2(float(kDirectionSteps[size_t(d)][1]) * spacingZ,
                                 float(kDirectionSteps[size_t(d)][0]) * spacingX);
        sx += w * std::cos(2.0f * angle);
        sz += w * std::sin(2.0f * angle);
        if (w > largest) {
            largest = w;
            best = d;
            bestAngle = angle;
        }
    }
    if (best < 0) return false;
    // Below a thousandth of the largest weight the sum's angle is rounding noise.
    float angle = std::hypot(sx, sz) > 1e-3f * largest ? 0.5f * std::atan2(sz, sx) : bestAngle;
    ux = std::cos(angle);
    uz = std::sin(angle);
    return true;
}

Vec3 hatchStrokeDirection(const float curvature[kDirectionCount], const Vec3& n, float spacingX,
                          float spacingZ, HatchDirection direction) {
    if (std::isnan(n.x) || std::isnan(n.y) || std::isnan(n.z)) return {NAN, NAN, NAN};
    float ax = 1.0f, az = 0.0f;
    blendedCurvatureAxis(curvature, spacingX, spacingZ, ax, az);
    // Lift the horizontal axis onto the tangent plane: n . t = 0.
    detail::V3 t = detail::normalized({ax, -(n.x * ax + n.z * az) / n.y, az});
    if (direction == HatchDirection::Across)
        t = detail::normalized(detail::cross({n.x, n.y, n.z}, t));
    return {t.x, t.y, t.z};
}

HatchField computeHatchField(const terrain::Heightfield& field, const CurvatureField& curvature,
                             const HatchOptions& options) {
    SIERRA_CHECK(curvature.width == field.width() && curvature.height == field.height(),
                 "hatch field: the curvature field is ", curvature.width, "x", curvature.height,
                 " but the heightfield is ", field.width(), "x", field.height());
    NormalField normals = computeNormals(field, options.normals, options.threads);
    HatchField out;
    out.width = field.width();
    out.height = field.height();
    out.direction.resize(size_t(field.sampleCount()));
    out.opacity.resize(size_t(field.sampleCount()));
    const float sx = field.spacingX(), sz = field.spacingZ();
    detail::forRows(out.width, out.height, options.threads, [&](int j0, int j1) {
        for (int j = j0; j < j1; ++j)
            for (int i = 0; i < out.width; ++i) {
                size_t k = out.index(i, j);
                const float* c = &curvature.values[k * kDirectionCount];
                out.direction[k] =
                    hatchStrokeDirection(c, normals.normals[k], sx, sz, options.direction);
                float m = curvature.maxMagnitude(i, j);
                out.opacity[k] = std::isnan(m) ? NAN : std::min(1.0f, m);
            }
    });
    return out;
}

}  // namespace sierra::analysis
