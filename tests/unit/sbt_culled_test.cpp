// The view-dependent refiner's count of subtrees culled by the frustum
// (StripMesh::culledSubtrees): checked against a brute-force recursion, for
// both view paths, any thread count and any chunk level; 0 without culling.
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/DiamondSquare.h>

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <bit>
#include <cstdint>

namespace {

namespace sbt = sierra::sbt;
using sierra::terrain::Heightfield;

Heightfield terrain(int size, uint64_t seed) {
    Heightfield f = sierra::terrain::generateDiamondSquare({.size = size, .seed = seed});
    auto [lo, hi] = f.range();
    f.setVerticalScale(0.2f * float(size - 1) /
                       std::max(1e-6f, hi - lo));  // relief 20% of the extent
    return f;
}

// A perspective camera at `eye` looking at `target` (world units), 45 degrees
// vertical field of view, 16:9 at 1080 pixels, far plane 4 extents.
sbt::ViewParams view(const Heightfield& f, glm::vec3 eye, glm::vec3 target, bool cull) {
    const float extent = float(f.width() - 1) * f.spacingX();
    return sbt::lookAtView({eye.x, eye.y, eye.z}, {target.x, target.y, target.z},
                           glm::radians(45.0f), 16.0f / 9.0f, 1080.0f, extent * 1e-3f,
                           extent * 4.0f, 1.0f, cull);
}

// lookAtView builds the same frustum as GL's look-at and perspective matrices.
TEST(SbtLookAtView, FrustumOfTheGlLookAtCamera) {
    const glm::vec3 eye{-40.0f, 90.0f, 310.0f}, target{128.0f, -5.0f, 120.0f};
    const float fovy = glm::radians(50.0f), aspect = 1.6f, nearPlane = 0.5f, farPlane = 2000.0f;
    const sbt::ViewParams v =
        sbt::lookAtView({eye.x, eye.y, eye.z}, {target.x, target.y, target.z}, fovy, aspect, 900.0f,
                        nearPlane, farPlane, 2.0f, false);
    const glm::mat4 vp =
        glm::perspective(fovy, aspect, nearPlane, farPlane) * glm::lookAt(eye, target, {0, 1, 0});
    const auto planes = sbt::frustumPlanes(glm::value_ptr(vp));
    for (size_t k = 0; k < planes.size(); ++k) {
        EXPECT_NEAR(v.planes[k].a, planes[k].a, 1e-5f) << "plane " << k;
        EXPECT_NEAR(v.planes[k].b, planes[k].b, 1e-5f) << "plane " << k;
        EXPECT_NEAR(v.planes[k].c, planes[k].c, 1e-5f) << "plane " << k;
        // The far plane comes from a difference of nearly equal rows: float rounding in both.
        EXPECT_NEAR(v.planes[k].d, planes[k].d, 3e-4f * std::abs(planes[k].d) + 1e-4f)
            << "plane " << k;
    }
    EXPECT_EQ(v.eye, (std::array<float, 3>{eye.x, eye.y, eye.z}));
    EXPECT_FLOAT_EQ(v.lambda, sbt::projectionLambda(900.0f, fovy));
    EXPECT_EQ(v.tau, 2.0f);
    EXPECT_FALSE(v.cull);
}

// Culled subtrees by a plain recursion in double: a triangle above the finest
// level is culled when its split vertex's sphere lies outside a plane not yet
// passed by an ancestor's sphere (fully inside it); otherwise it splits while
// its split vertex is active.
int64_t bruteCulled(const Heightfield& f, const sbt::VertexErrors& ve, const sbt::ViewParams& v) {
    const uint32_t side = uint32_t(f.width());
    const int finest = 2 * std::countr_zero(side - 1);
    const double sx = f.spacingX(), sz = f.spacingZ(), vs = f.verticalScale();
    const double kE = double(v.lambda) / double(v.tau);
    int64_t culled = 0;
    auto rec = [&](auto&& self, uint32_t a, uint32_t q, uint32_t b, int l, unsigned mask) -> void {
        if (l >= finest) return;
        const uint32_t m = (a + b) / 2, i = m % side, j = m / side;
        const double x = i * sx, y = double(f.samples()[m]) * vs, z = j * sz;
        const float r = ve.radius[m];
        for (int k = 0; k < 6 && v.cull; ++k) {
            if (!(mask & (1u << k))) continue;
            const sbt::Plane& p = v.planes[size_t(k)];
            const double s = p.a * x + p.b * y + p.c * z + p.d;
            if (s < -double(r)) {
                ++culled;
                return;
            }
            if (s >= double(r)) mask &= ~(1u << k);
        }
        const double dx = x - v.eye[0], dy = y - v.eye[1], dz = z - v.eye[2];
        const double reach = kE * double(ve.error[m]) + double(r);
        if (reach * reach > dx * dx + dy * dy + dz * dz) {
            self(self, a, m, q, l + 1, mask);
            self(self, q, m, b, l + 1, mask);
        }
    };
    const uint32_t S = side - 1;
    rec(rec, 0, S * side, S * side + S, 0, 0x3f);
    rec(rec, S * side + S, S, 0, 0, 0x3f);
    return culled;
}

TEST(SbtCulledSubtrees, CountedForAPartialViewAndZeroWithoutCulling) {
    Heightfield f = terrain(257, 3);
    auto ve = sbt::computeVertexErrors(f);
    sbt::Refiner refiner(f, ve, {.threads = 2});
    auto [lo, hi] = f.range();
    const float vs = f.verticalScale();
    // Inside the terrain, low, looking across one corner: most of it is out of view.
    const glm::vec3 eye{60.0f, hi * vs + 10.0f, 60.0f}, target{200.0f, lo * vs, 120.0f};
    sbt::StripMesh culled, all;
    refiner.refineView(view(f, eye, target, true), culled);
    refiner.refineView(view(f, eye, target, false), all);
    EXPECT_GT(culled.culledSubtrees, 0);
    EXPECT_LT(culled.triangleCount, all.triangleCount) << "culling dropped triangles";
    EXPECT_EQ(all.culledSubtrees, 0);
    // Fixed-error meshes never cull.
    sbt::StripMesh fixed;
    refiner.refineFixed(0.5f, fixed);
    EXPECT_EQ(fixed.culledSubtrees, 0);
}

TEST(SbtCulledSubtrees, MatchBruteForceOnBothPathsForAnyThreadsAndChunkLevel) {
    Heightfield f = terrain(257, 7);
    auto ve = sbt::computeVertexErrors(f);
    auto [lo, hi] = f.range();
    const float vs = f.verticalScale();
    const float top = hi * vs, bottom = lo * vs;
    // A partial view, a view from outside that sees nearly everything, one
    // looking away from the terrain (everything culled near the root).
    const sbt::ViewParams views[] = {
        view(f, {30.0f, top + 5.0f, 220.0f}, {230.0f, bottom, 40.0f}, true),
        view(f, {-150.0f, top + 120.0f, 400.0f}, {128.0f, bottom, 128.0f}, true),
        view(f, {128.0f, top + 20.0f, 128.0f}, {128.0f, top + 400.0f, -300.0f}, true),
    };
    int64_t total = 0;
    for (size_t k = 0; k < std::size(views); ++k) {
        const int64_t expected = bruteCulled(f, ve, views[k]);
        total += expected;
        for (int chunkLevel : {-1, 0, 3, 6})
            for (int threads : {1, 3}) {
                SCOPED_TRACE(testing::Message() << "view " << k << " chunk level " << chunkLevel
                                                << " threads " << threads);
                sbt::Refiner refiner(f, ve, {.threads = threads, .chunkLevel = chunkLevel});
                sbt::StripMesh fast, reference;
                refiner.refineView(views[k], fast);
                refiner.refineViewReference(views[k], reference);
                EXPECT_EQ(fast.culledSubtrees, expected);
                EXPECT_EQ(reference.culledSubtrees, expected);
            }
    }
    EXPECT_GT(total, 10) << "the views cull something";
}

}  // namespace
