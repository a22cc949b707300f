// The view a refineView takes (Refiner.h): the projection's lambda, the
// frustum planes of a view-projection matrix, and a look-at camera's view,
// for tools and tests. The refiner itself is in Refiner.cpp.
#include <sierra/core/Error.h>
#include <sierra/sbt/Refiner.h>

#include <array>
#include <cmath>

namespace sierra::sbt {

float projectionLambda(float viewportHeightPx, float fovyRadians) {
    SIERRA_CHECK(viewportHeightPx > 0 && fovyRadians > 0 && fovyRadians < 3.14159f,
                 "projectionLambda: need a positive viewport height and 0 < fovy < pi, got ",
                 viewportHeightPx, " px, ", fovyRadians, " rad");
    return viewportHeightPx / (2.0f * std::tan(0.5f * fovyRadians));
}

std::array<Plane, 6> frustumPlanes(const float m[16]) {
    // row k of the matrix (column-major storage): m[k], m[4 + k], m[8 + k], m[12 + k]
    auto row = [&](int k, float out[4]) {
        for (int c = 0; c < 4; ++c) out[c] = m[4 * c + k];
    };
    float r0[4], r1[4], r2[4], r3[4];
    row(0, r0), row(1, r1), row(2, r2), row(3, r3);
    std::array<Plane, 6> planes;
    const float* rows[3] = {r0, r1, r2};
    for (int k = 0; k < 6; ++k) {
        const float* r = rows[k / 2];
        float sgn = (k & 1) ? -1.0f : 1.0f;
        Plane p{r3[0] + sgn * r[0], r3[1] + sgn * r[1], r3[2] + sgn * r[2], r3[3] + sgn * r[3]};
        float len = std::sqrt(p.a * p.a + p.b * p.b + p.c * p.c);
        if (len > 0) p = Plane{p.a / len, p.b / len, p.c / len, p.d / len};
        planes[k] = p;
    }
    return planes;
}

ViewParams lookAtView(const std::array<float, 3>& eye, const std::array<float, 3>& target,
                      float fovyRadians, float aspect, float viewportHeightPx, float nearPlane,
                      float farPlane, float tau, bool cull) {
    using V3 = std::array<double, 3>;
    auto dot = [](const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
    auto cross = [](const V3& a, const V3& b) {
        return V3{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    };
    auto normalised = [&](V3 a) {
        const double length = std::sqrt(dot(a, a));
        for (double& x : a) x /= length;
        return a;
    };
    const V3 e{eye[0], eye[1], eye[2]};
    const V3 forward{target[0] - e[0], target[1] - e[1], target[2] - e[2]};
    SIERRA_CHECK(dot(forward, forward) > 0 && std::abs(normalised(forward)[1]) < 1.0,
                 "lookAtView: the camera must look somewhere other than straight up or down");
    SIERRA_CHECK(aspect > 0 && nearPlane > 0 && farPlane > nearPlane,
                 "lookAtView: need aspect > 0 and 0 < near < far, got ", aspect, ", ", nearPlane,
                 ", ", farPlane);
    // The OpenGL look-at view (right-handed, +y up) and perspective projection
    // (clip z in [-w, w]), column-major: m[column * 4 + row].
    const V3 f = normalised(forward), side = normalised(cross(f, V3{0, 1, 0})), up = cross(side, f);
    double viewM[16] = {side[0], up[0], -f[0], 0, side[1],       up[1],       -f[1],     0,
                        side[2], up[2], -f[2], 0, -dot(side, e), -dot(up, e), dot(f, e), 1};
    const double t = std::tan(0.5 * double(fovyRadians)), n = nearPlane, fa = farPlane;
    double proj[16] = {};
    proj[0] = 1.0 / (double(aspect) * t);
    proj[5] = 1.0 / t;
    proj[10] = -(fa + n) / (fa - n);
    proj[11] = -1.0;
    proj[14] = -2.0 * fa * n / (fa - n);
    float vp[16];
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            double sum = 0;
            for (int k = 0; k < 4; ++k) sum += proj[k * 4 + r] * viewM[c * 4 + k];
            vp[c * 4 + r] = float(sum);
        }
    ViewParams view;
    view.eye = eye;
    view.lambda = projectionLambda(viewportHeightPx, fovyRadians);
    view.tau = tau;
    view.cull = cull;
    view.planes = frustumPlanes(vp);
    return view;
}

}  // namespace sierra::sbt
