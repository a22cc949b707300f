// The view-dependent refinement against a straightforward reference: the same
// triangles in the same (Sierpinski) order, over random cameras (some outside
// the terrain or looking partly away from it), taus and terrains from smooth
// to very rough, with and without culling, for 1, 2 and 3 threads.
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/DiamondSquare.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

namespace sbt = sierra::sbt;
using sierra::terrain::Heightfield;
using Tri = std::array<uint32_t, 3>;

// The rule of Refiner.h written as plainly as possible, in double: a triangle
// (entry a, apex q, exit b) at level l < 2n looks at its hypotenuse midpoint m;
// with culling, m's sphere fully outside a plane drops the triangle, fully
// inside a plane stops testing that plane below; the triangle splits when m
// is active, (lambda / tau * e + r)^2 > |p - eye|^2. Leaves in curve order,
// vertices sorted (the strip's winding is checked elsewhere).
std::vector<Tri> referenceLeaves(const Heightfield& f, const sbt::VertexErrors& ve,
                                 const sbt::ViewParams& vp) {
    const uint32_t side = uint32_t(f.width());
    const int finest = 2 * std::countr_zero(side - 1);
    const double kE = double(vp.lambda) / double(vp.tau);
    std::vector<Tri> out;
    auto rec = [&](auto&& self, uint32_t a, uint32_t q, uint32_t b, int l, unsigned mask) -> void {
        if (l < finest) {
            const uint32_t m = (a + b) / 2;
            const double x = double(m % side) * double(f.spacingX());
            const double y = double(f.samples()[m]) * double(f.verticalScale());
            const double z = double(m / side) * double(f.spacingZ());
            const double r = ve.radius[m];
            for (int k = 0; k < 6; ++k) {
                if (!(mask & (1u << k))) continue;
                const sbt::Plane& p = vp.planes[k];
                const double s = double(p.a) * x + double(p.b) * y + double(p.c) * z + double(p.d);
                if (s < -r) return;
                if (s >= r) mask &= ~(1u << k);
            }
            const double dx = x - vp.eye[0], dy = y - vp.eye[1], dz = z - vp.eye[2];
            const double reach = kE * double(ve.error[m]) + r;
            if (reach * reach > dx * dx + dy * dy + dz * dz) {
                self(self, a, m, q, l + 1, mask);
                self(self, q, m, b, l + 1, mask);
                return;
            }
        }
        Tri t{a, q, b};
        std::sort(t.begin(), t.end());
        out.push_back(t);
    };
    const uint32_t S = side - 1;
    const unsigned all = vp.cull ? 0x3fu : 0u;
    rec(rec, 0, S * side, S * side + S, 0, all);
    rec(rec, S * side + S, S, 0, 0, all);
    return out;
}

std::vector<Tri> decodedInOrder(const sbt::StripMesh& mesh) {
    std::vector<Tri> tris = sbt::decodeStrip(mesh.indices);
    for (Tri& t : tris) std::sort(t.begin(), t.end());
    return tris;
}

// Column-major perspective * look-at, the eye anywhere (also outside the
// terrain), the target anywhere within twice the extent, so that some cameras
// see the terrain only partly or look away from most of it.
std::array<float, 16> viewProjection(const std::array<float, 3>& eye,
                                     const std::array<float, 3>& target, float fovy, float aspect,
                                     float zn, float zf) {
    std::array<float, 3> f = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
    const float fl = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (float& x : f) x /= fl;
    std::array<float, 3> s = {-f[2], 0.0f, f[0]};  // f x (0, 1, 0)
    const float sl = std::sqrt(s[0] * s[0] + s[2] * s[2]);
    for (float& x : s) x /= sl;
    const std::array<float, 3> u = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2],
                                    s[0] * f[1] - s[1] * f[0]};
    const float view[16] = {s[0],
                            u[0],
                            -f[0],
                            0,
                            s[1],
                            u[1],
                            -f[1],
                            0,
                            s[2],
                            u[2],
                            -f[2],
                            0,
                            -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]),
                            -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]),
                            f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2],
                            1};
    const float t = 1.0f / std::tan(fovy / 2);
    const float proj[16] = {t / aspect,
                            0,
                            0,
                            0,
                            0,
                            t,
                            0,
                            0,
                            0,
                            0,
                            (zf + zn) / (zn - zf),
                            -1,
                            0,
                            0,
                            2 * zf * zn / (zn - zf),
                            0};
    std::array<float, 16> m{};
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            for (int k = 0; k < 4; ++k) m[c * 4 + r] += proj[k * 4 + r] * view[c * 4 + k];
    return m;
}

TEST(SbtViewOrder, SameTrianglesInTheSameOrderAsTheReference) {
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int64_t triangles = 0, partial = 0;
    for (int trial = 0; trial < 36; ++trial) {
        SCOPED_TRACE("trial " + std::to_string(trial));
        const int side = trial % 4 == 0 ? 513 : trial % 4 == 1 ? 257 : 129;
        // Hurst exponents 0.1 (very rough) to 0.9, and a plain fractal.
        Heightfield f =
            trial % 5 == 4
                ? sierra::terrain::generateDiamondSquare({.size = side, .seed = uint64_t(trial)})
                : sierra::terrain::generateDiamondSquare({.size = side,
                                                          .seed = uint64_t(trial),
                                                          .hurst = 0.1f + 0.2f * float(trial % 5)});
        auto [lo, hi] = f.range();
        const float spacing = trial % 6 == 5 ? 25.0f : 0.5f + 0.5f * float(trial % 3);
        f.setSpacing(spacing, spacing * (trial % 2 ? 1.0f : 1.25f));
        // relief from 5% to 40% of the extent
        const float extent = float(side - 1) * spacing;
        f.setVerticalScale((0.05f + 0.35f * u(rng)) * extent / std::max(1e-6f, hi - lo));
        if (trial % 7 == 6) {  // large world coordinates: a terrain far from the origin in height
            for (float& h : f.samples()) h += 1.0e4f;
        }
        const auto ve = sbt::computeVertexErrors(f);
        auto [lo2, hi2] = f.range();
        const float top = hi2 * f.verticalScale(), bottom = lo2 * f.verticalScale();
        // Eyes from low over the terrain to high above it, a third of them
        // outside the square; targets anywhere within twice the extent.
        std::array<float, 3> eye = {extent * (1.6f * u(rng) - 0.3f), 0.0f,
                                    extent * (1.6f * u(rng) - 0.3f)};
        eye[1] = top + (0.01f + 0.6f * u(rng) * u(rng)) * extent;
        const std::array<float, 3> target = {extent * (2.0f * u(rng) - 0.5f),
                                             bottom + (top - bottom) * u(rng),
                                             extent * (2.0f * u(rng) - 0.5f)};
        const float fovy = 0.5f + 0.7f * u(rng);
        const auto m =
            viewProjection(eye, target, fovy, 16.0f / 9.0f, 1e-3f * extent, 4.0f * extent);
        sbt::ViewParams vp;
        vp.eye = eye;
        vp.lambda = sbt::projectionLambda(1080.0f, fovy);
        vp.tau = trial % 3 == 0 ? 1.0f
                                : std::exp(std::uniform_real_distribution<float>(-1.5f, 2.5f)(rng));
        vp.planes = sbt::frustumPlanes(m.data());
        // Chunks from level 0 or 1 of a 513² grid (18 levels) leave nodes
        // more levels above the finest than the keyed walk has functions for
        // (16): the exact path walks them down to that depth.
        const int chunkLevel = trial % 8 == 0 ? (trial / 8) % 2 : -1;
        sbt::Refiner refiner(f, ve, {.threads = 1 + trial % 3, .chunkLevel = chunkLevel});
        for (bool cull : {true, false}) {
            vp.cull = cull;
            const std::vector<Tri> expected = referenceLeaves(f, ve, vp);
            sbt::StripMesh mesh, again, baseline;
            refiner.refineView(vp, mesh);
            ASSERT_EQ(decodedInOrder(mesh), expected) << "cull " << cull << " tau " << vp.tau;
            EXPECT_EQ(mesh.triangleCount, int64_t(expected.size()));
            refiner.refineViewReference(vp, baseline);
            EXPECT_EQ(mesh.indices, baseline.indices) << "cull " << cull;
            // a second call reuses buffers (and whatever the first call built)
            refiner.refineView(vp, again);
            EXPECT_EQ(again.indices, mesh.indices);
            triangles += mesh.triangleCount;
            if (cull && mesh.triangleCount > 0) {
                vp.cull = false;
                sbt::StripMesh all;
                refiner.refineView(vp, all);
                partial += all.triangleCount > mesh.triangleCount;
            }
        }
    }
    EXPECT_GT(triangles, 300000) << "the cameras see real meshes";
    EXPECT_GT(partial, 10) << "many cameras see the terrain only partly";
}

// The same terrain refined again after the view changes a lot (tau, lambda,
// eye from near to far): nothing built for one view leaks into the next.
TEST(SbtViewOrder, SuccessiveViewsMatchTheReference) {
    Heightfield f = sierra::terrain::generateDiamondSquare({.size = 257, .seed = 9, .hurst = 0.3f});
    auto [lo, hi] = f.range();
    f.setVerticalScale(0.2f * 256.0f / std::max(1e-6f, hi - lo));
    const auto ve = sbt::computeVertexErrors(f);
    sbt::Refiner refiner(f, ve, {.threads = 2});
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int k = 0; k < 12; ++k) {
        SCOPED_TRACE("view " + std::to_string(k));
        const std::array<float, 3> eye = {300.0f * u(rng) - 20.0f, 60.0f + 200.0f * u(rng) * u(rng),
                                          300.0f * u(rng) - 20.0f};
        const std::array<float, 3> target = {256.0f * u(rng), 0.0f, 256.0f * u(rng)};
        const float fovy = 0.4f + u(rng);
        const auto m = viewProjection(eye, target, fovy, 1.5f, 0.1f, 2000.0f);
        sbt::ViewParams vp;
        vp.eye = eye;
        vp.lambda = sbt::projectionLambda(400.0f + 1000.0f * u(rng), fovy);
        vp.tau = 0.3f + 6.0f * u(rng);
        vp.cull = k % 3 != 2;
        vp.planes = sbt::frustumPlanes(m.data());
        sbt::StripMesh mesh;
        refiner.refineView(vp, mesh);
        ASSERT_EQ(decodedInOrder(mesh), referenceLeaves(f, ve, vp));
    }
}

// Terrains the view keys describe trivially, not at all, or near float
// precision: a flat one (every height key 0), one with NaN samples (no keys:
// the exact path), a small relief 10^5 units up (the key step close to the
// float spacing of the heights), and a rough one with a flat quadrant (errors
// of 0 below the error keys' base: key 0, read as "below the base").
TEST(SbtViewOrder, FlatNanAndHighTerrainsMatchTheReference) {
    for (int kind = 0; kind < 4; ++kind) {
        SCOPED_TRACE("kind " + std::to_string(kind));
        Heightfield f =
            kind == 0
                ? Heightfield(129, 129, 3.0f)
                : sierra::terrain::generateDiamondSquare({.size = 129, .seed = 4, .hurst = 0.5f});
        auto [lo, hi] = f.range();
        if (kind > 0) f.setVerticalScale((kind == 2 ? 2.0f : 25.0f) / (hi - lo));
        if (kind == 1) {
            f.at(40, 77) = std::numeric_limits<float>::quiet_NaN();
            f.at(100, 3) = std::numeric_limits<float>::quiet_NaN();
        }
        if (kind == 2)
            for (float& h : f.samples()) h += 1.0e5f / f.verticalScale();
        if (kind == 3)
            for (int j = 0; j <= 64; ++j)
                for (int i = 0; i <= 64; ++i) f.at(i, j) = lo;
        const auto ve = sbt::computeVertexErrors(f);
        sbt::Refiner refiner(f, ve, {.threads = 1});
        const float base = kind == 2 ? 1.0e5f : 0.0f;
        const std::array<float, 3> eye = {-20.0f, base + 40.0f, 30.0f};
        const auto m = viewProjection(eye, {64.0f, base, 64.0f}, 0.9f, 1.5f, 0.1f, 1000.0f);
        sbt::ViewParams vp;
        vp.eye = eye;
        vp.lambda = sbt::projectionLambda(1080.0f, 0.9f);
        vp.tau = 0.5f;
        vp.planes = sbt::frustumPlanes(m.data());
        for (bool cull : {true, false}) {
            vp.cull = cull;
            sbt::StripMesh mesh;
            refiner.refineView(vp, mesh);
            EXPECT_GT(mesh.triangleCount, 0);
            ASSERT_EQ(decodedInOrder(mesh), referenceLeaves(f, ve, vp)) << "cull " << cull;
        }
    }
}

}  // namespace
