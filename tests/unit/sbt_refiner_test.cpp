// Vertex errors, fixed-error and view-dependent refinement, strips: checked
// against brute-force recursions and mesh invariants.
#include <sierra/sbt/Addressing.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/DiamondSquare.h>

#include "sbt_mesh_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <vector>

namespace {

namespace sbt = sierra::sbt;
using sierra::terrain::Heightfield;
using Tri = std::array<uint32_t, 3>;
using sierra::test::cross2;
using sierra::test::expectConforming;

Heightfield fractal(int size, uint64_t seed, float roughness = 1.0f) {
    return sierra::terrain::generateDiamondSquare(
        {.size = size, .seed = seed, .roughness = roughness});
}

// Smooth, real-looking terrain: a sum of Gaussian hills.
Heightfield gaussians(int size, uint64_t seed) {
    Heightfield f(size, size);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    struct Hill {
        double x, z, s, h;
    };
    std::vector<Hill> hills;
    for (int k = 0; k < 12; ++k)
        hills.push_back({u(rng), u(rng), 0.05 + 0.2 * u(rng), 2.0 * u(rng) - 0.7});
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            double x = double(i) / (size - 1), z = double(j) / (size - 1), h = 0;
            for (const Hill& hl : hills)
                h += hl.h *
                     std::exp(-((x - hl.x) * (x - hl.x) + (z - hl.z) * (z - hl.z)) / (hl.s * hl.s));
            f.at(i, j) = float(h * 40.0);
        }
    return f;
}

struct Node {
    uint32_t a, q, b;
    int level;
};

// Brute-force recursion over the tree, leaves in Sierpinski order.
template <typename Split>
void leaves(int side, Split&& split, std::vector<Node>& out) {
    const int n = std::countr_zero(unsigned(side - 1));
    auto rec = [&](auto&& self, uint32_t a, uint32_t q, uint32_t b, int l) -> void {
        uint32_t m = (a + b) / 2;
        if (l < 2 * n && split(m, l)) {
            self(self, a, m, q, l + 1);
            self(self, q, m, b, l + 1);
        } else {
            out.push_back({a, q, b, l});
        }
    };
    uint32_t S = side - 1;
    rec(rec, 0, S * side, S * side + S, 0);
    rec(rec, S * side + S, S, 0, 0);
}

std::vector<Tri> sortedTris(std::vector<Tri> tris) {
    for (Tri& t : tris) std::sort(t.begin(), t.end());
    std::sort(tris.begin(), tris.end());
    return tris;
}
std::vector<Tri> sortedTris(const std::vector<Node>& nodes) {
    std::vector<Tri> tris;
    for (const Node& n : nodes) tris.push_back({n.a, n.q, n.b});
    return sortedTris(tris);
}

// Consecutive triangles of a strip share an edge (Sierpinski order).
void expectConsecutiveShareEdge(const std::vector<uint32_t>& indices) {
    std::vector<uint32_t> strip;
    auto check = [&] {
        std::vector<uint32_t> s = strip;
        s.push_back(sbt::kRestartIndex);
        auto tris = sbt::decodeStrip(s);
        for (size_t k = 1; k < tris.size(); ++k) {
            int shared = 0;
            for (uint32_t a : tris[k - 1])
                for (uint32_t b : tris[k]) shared += a == b;
            ASSERT_EQ(shared, 2);
        }
        strip.clear();
    };
    for (uint32_t v : indices) {
        if (v == sbt::kRestartIndex)
            check();
        else
            strip.push_back(v);
    }
    check();
}

TEST(SbtErrors, SaturatedAndNestedByBruteForce) {
    for (int trial = 0; trial < 4; ++trial) {
        Heightfield f = trial % 2 ? fractal(33, trial) : gaussians(33, trial);
        f.setSpacing(1.5f, 0.75f);
        f.setVerticalScale(trial + 0.5f);
        sbt::VertexErrors ve = sbt::computeVertexErrors(f, 2);
        const int side = f.width(), n = 5;
        sbt::Addressing ad(n);
        auto pos = [&](sbt::GridVertex v) {
            return std::array<double, 3>{v.i * double(f.spacingX()),
                                         double(f.at(v.i, v.j)) * double(f.verticalScale()),
                                         v.j * double(f.spacingZ())};
        };
        auto dist = [&](sbt::GridVertex a, sbt::GridVertex b) {
            auto p = pos(a), q = pos(b);
            return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                             (p[2] - q[2]) * (p[2] - q[2]));
        };
        // brute force, level by level from the finest, over every triangle
        std::vector<double> e(size_t(side) * side, 0.0), r(size_t(side) * side, 0.0);
        for (int l = ad.finestLevel() - 1; l >= 0; --l)
            for (int row = 0; row < sbt::Addressing::rows(l); ++row)
                for (int col = 0; col < sbt::Addressing::cols(l); ++col) {
                    sbt::TriangleId t{l, row, col};
                    sbt::GridVertex m = ad.splitVertex(t), a = ad.vertex(t, 1), b = ad.vertex(t, 2);
                    size_t mi = size_t(m.j) * side + m.i;
                    double raw = std::fabs(
                        double(f.worldHeight(m.i, m.j)) -
                        0.5 * (double(f.worldHeight(a.i, a.j)) + double(f.worldHeight(b.i, b.j))));
                    e[mi] = std::max(e[mi], raw);
                    for (int k = 0; k < 3; ++k) r[mi] = std::max(r[mi], dist(m, ad.vertex(t, k)));
                    if (l + 1 < ad.finestLevel()) {
                        for (sbt::TriangleId c :
                             {sbt::Addressing::leftChild(t), sbt::Addressing::rightChild(t)}) {
                            sbt::GridVertex cm = ad.splitVertex(c);
                            size_t ci = size_t(cm.j) * side + cm.i;
                            e[mi] = std::max(e[mi], e[ci]);
                            r[mi] = std::max(r[mi], dist(m, cm) + r[ci]);
                            // the stored arrays satisfy the definitions directly
                            EXPECT_GE(ve.error[mi], ve.error[ci]);
                            EXPECT_GE(double(ve.radius[mi]), dist(m, cm) + double(ve.radius[ci]));
                        }
                    }
                    for (int k = 0; k < 3; ++k)
                        EXPECT_GE(double(ve.radius[mi]), dist(m, ad.vertex(t, k)));
                }
        for (size_t k = 0; k < e.size(); ++k) {
            EXPECT_NEAR(ve.error[k], e[k], 1e-5 * (1 + e[k]));
            EXPECT_NEAR(ve.radius[k], r[k], 1e-5 * (1 + r[k]));
        }
    }
}

TEST(SbtErrors, SameForAnyThreadCountAndRejectsBadGrids) {
    Heightfield f = fractal(129, 7);
    auto a = sbt::computeVertexErrors(f, 1), b = sbt::computeVertexErrors(f, 4);
    EXPECT_EQ(a.error, b.error);
    EXPECT_EQ(a.radius, b.radius);
    EXPECT_THROW(sbt::computeVertexErrors(Heightfield(100, 100)), sierra::Error);
    EXPECT_THROW(sbt::computeVertexErrors(Heightfield(33, 17)), sierra::Error);
}

TEST(SbtErrors, MorphBaseIsTheHypotenuseMean) {
    Heightfield f = fractal(17, 3);
    f.setVerticalScale(2.0f);
    auto base = sbt::buildMorphBase(f, 2);
    for (int j = 0; j < 17; ++j)
        for (int i = 0; i < 17; ++i) {
            int ai, aj, bi, bj;
            float expected = sbt::hypotenuseEndpoints(i, j, 4, &ai, &aj, &bi, &bj)
                                 ? 0.5f * (f.worldHeight(ai, aj) + f.worldHeight(bi, bj))
                                 : f.worldHeight(i, j);
            EXPECT_FLOAT_EQ(base[size_t(j) * 17 + i], expected);
        }
}

TEST(SbtFixed, PlaneAtZeroErrorGivesTwoTriangles) {
    Heightfield f(65, 65);
    for (int j = 0; j < 65; ++j)
        for (int i = 0; i < 65; ++i) f.at(i, j) = float(2 * i + 3 * j);
    auto ve = sbt::computeVertexErrors(f);
    sbt::Refiner refiner(f, ve);
    sbt::StripMesh mesh;
    refiner.refineFixed(0.0f, mesh);
    EXPECT_EQ(mesh.triangleCount, 2);
    auto tris = sbt::decodeStrip(mesh.indices);
    ASSERT_EQ(tris.size(), 2u);
    expectConforming(tris, 65, true);
    EXPECT_NEAR(sbt::maxVerticalDistance(f, tris), 0.0, 1e-4);
}

TEST(SbtFixed, MeshesMatchBruteForceAndConform) {
    struct Case {
        Heightfield f;
        const char* name;
    };
    std::vector<Case> cases;
    cases.push_back({fractal(65, 11), "fractal"});
    cases.push_back({gaussians(65, 5), "gaussians"});
    cases.push_back({fractal(9, 2), "small"});
    for (Case& cs : cases) {
        const int side = cs.f.width();
        auto ve = sbt::computeVertexErrors(cs.f);
        sbt::Refiner refiner(cs.f, ve, {.threads = 2});
        float emax = *std::max_element(ve.error.begin(), ve.error.end());
        std::vector<float> epsilons = {-1.0f, 0.0f};
        for (int k = 0; k <= 16; ++k) epsilons.push_back(emax * std::pow(0.7f, float(k)));
        sbt::StripMesh mesh;
        for (float eps : epsilons) {
            SCOPED_TRACE(std::string(cs.name) + " eps " + std::to_string(eps));
            refiner.refineFixed(eps, mesh);
            std::vector<Node> expected;
            leaves(
                side, [&](uint32_t m, int) { return ve.error[m] > eps; }, expected);
            ASSERT_EQ(mesh.triangleCount, int64_t(expected.size()));
            auto tris = sbt::decodeStrip(mesh.indices);
            ASSERT_EQ(sortedTris(tris), sortedTris(expected))
                << "the strip decodes to the leaf set";
            expectConforming(tris, side, true);
            expectConsecutiveShareEdge(mesh.indices);
            // every leaf's split vertex is within eps; every split one above it
            for (const Node& nd : expected) {
                if (nd.level < 2 * std::countr_zero(unsigned(side - 1))) {
                    EXPECT_LE(ve.error[(nd.a + nd.b) / 2], eps);
                }
            }
            std::vector<Node> parents;
            leaves(
                side, [&](uint32_t m, int) { return ve.error[m] > eps; }, parents);
            if (eps < 0) {
                EXPECT_EQ(mesh.triangleCount, 2 * int64_t(side - 1) * (side - 1));
                EXPECT_NEAR(sbt::maxVerticalDistance(cs.f, tris), 0.0, 1e-3);
            }
        }
    }
}

// The refiner decides splits on 16-bit keys and reads the float error only when
// the key of epsilon ties; epsilons equal to errors, one float either side of
// them, and the special values must still give exactly the float rule.
TEST(SbtFixed, KeyTiesFallBackToTheExactError) {
    Heightfield f = fractal(129, 21);
    const int side = f.width();
    auto ve = sbt::computeVertexErrors(f);
    sbt::Refiner refiner(f, ve, {.threads = 2});
    std::vector<float> epsilons = {std::numeric_limits<float>::quiet_NaN(),
                                   std::numeric_limits<float>::infinity(), -0.0f,
                                   -std::numeric_limits<float>::infinity()};
    std::mt19937 rng(3);
    for (int k = 0; k < 12; ++k) {
        float e = ve.error[rng() % ve.error.size()];
        epsilons.insert(epsilons.end(), {e, std::nextafter(e, 0.0f), std::nextafter(e, INFINITY)});
    }
    sbt::StripMesh mesh;
    for (float eps : epsilons) {
        SCOPED_TRACE("eps " + std::to_string(eps));
        refiner.refineFixed(eps, mesh);
        std::vector<Node> expected;
        leaves(
            side, [&](uint32_t m, int) { return ve.error[m] > eps; }, expected);
        ASSERT_EQ(mesh.triangleCount, int64_t(expected.size()));
        ASSERT_EQ(sortedTris(sbt::decodeStrip(mesh.indices)), sortedTris(expected));
    }
}

TEST(SbtFixed, SplitTrianglesAreAboveEpsilon) {
    Heightfield f = gaussians(33, 9);
    auto ve = sbt::computeVertexErrors(f);
    sbt::Refiner refiner(f, ve);
    sbt::StripMesh mesh;
    for (float eps : {0.01f, 0.1f, 1.0f, 5.0f}) {
        refiner.refineFixed(eps, mesh);
        std::set<Tri> leafSet;
        for (Tri t : sbt::decodeStrip(mesh.indices)) {
            std::sort(t.begin(), t.end());
            leafSet.insert(t);
        }
        // walk the full tree: a triangle is split iff it is not a leaf of the mesh
        // and it contains leaves; its split vertex must then be above eps
        auto rec = [&](auto&& self, uint32_t a, uint32_t q, uint32_t b, int l) -> void {
            Tri t{a, q, b};
            std::sort(t.begin(), t.end());
            if (leafSet.count(t)) return;
            ASSERT_LT(l, 10);
            EXPECT_GT(ve.error[(a + b) / 2], eps);
            uint32_t m = (a + b) / 2;
            self(self, a, m, q, l + 1);
            self(self, q, m, b, l + 1);
        };
        rec(rec, 0, 32 * 33, 32 * 33 + 32, 0);
        rec(rec, 32 * 33 + 32, 32, 0, 0);
    }
}

TEST(SbtFixed, IdenticalForOneTwoFourThreads) {
    Heightfield f = fractal(257, 21);
    auto ve = sbt::computeVertexErrors(f);
    for (float eps : {-1.0f, 0.5f, 3.0f}) {
        std::vector<uint32_t> reference;
        for (int threads : {1, 2, 4}) {
            sbt::Refiner refiner(f, ve, {.threads = threads});
            sbt::StripMesh mesh;
            refiner.refineFixed(eps, mesh);
            if (threads == 1)
                reference = mesh.indices;
            else
                EXPECT_EQ(mesh.indices, reference) << threads << " threads, eps " << eps;
        }
    }
}

// What a fresh refiner makes on two threads (its first refinement runs in
// parallel, joined at the end) against `reused`, made on one thread.
template <typename Refine>
void expectAsAParallelRefinement(const Heightfield& f, const sbt::VertexErrors& ve,
                                 const sbt::StripMesh& reused, Refine&& refine) {
    sbt::Refiner parallel(f, ve, {.threads = 2});
    sbt::StripMesh fresh;
    refine(parallel, fresh);
    ASSERT_EQ(reused.indices, fresh.indices);
    EXPECT_EQ(reused.triangleCount, fresh.triangleCount);
    EXPECT_EQ(reused.stripCount, fresh.stripCount);
    EXPECT_EQ(reused.culledSubtrees, fresh.culledSubtrees);
}

// One thread joins each chunk into the output as soon as it is walked, and
// the output grows from the size the last refinement wrote; several threads
// join at the end. Both give the same mesh, into a mesh reused across
// refinements that grow (past that size several times over) and shrink.
TEST(SbtFixed, OneThreadJoinsIntoAReusedMeshAsSeveralThreadsDo) {
    Heightfield f = fractal(257, 8);
    auto ve = sbt::computeVertexErrors(f);
    sbt::Refiner serial(f, ve, {.threads = 1});
    sbt::StripMesh reused;
    for (float eps : {20.0f, 0.3f, 5.0f, -1.0f, 40.0f, 1.0f, -1.0f}) {
        SCOPED_TRACE("eps " + std::to_string(eps));
        const size_t before = reused.indices.size();
        serial.refineFixed(eps, reused);
        expectAsAParallelRefinement(
            f, ve, reused, [&](sbt::Refiner& r, sbt::StripMesh& m) { r.refineFixed(eps, m); });
        if (eps == 0.3f) {
            EXPECT_GT(reused.indices.size(), 4 * before) << "the output grew";
        }
    }
    // A mesh of the same size again, on one thread after two: the output is
    // not reallocated (no doubled capacity, no pages faulted in anew).
    sbt::Refiner both(f, ve, {.threads = 2});
    sbt::StripMesh mesh;
    both.refineFixed(-1.0f, mesh);
    const std::vector<uint32_t> full = mesh.indices;
    const size_t capacity = mesh.indices.capacity();
    both.setThreads(1);
    both.refineFixed(-1.0f, mesh);
    EXPECT_EQ(mesh.indices, full);
    EXPECT_EQ(mesh.indices.capacity(), capacity);
}

// The strip of a full (2^n + 1)^2 grid, counted exactly. It has T = 2 * 4^n
// leaf triangles. Every index after the first two closes a triangle, so
// I = 2 + T + D with D the degenerate ones: where the strip turns (two
// appended vertices of the same parity make the walk re-send one) and where
// the two level-0 triangles' strips join. On the 3x3 grid, in (i, j):
//     (0,0) (0,1) (1,1) (0,2) [(1,1)] (1,2) [(1,1)] (2,2) [(2,2)] (2,1) (1,1)
//     (2,0) [(1,1)] (1,0) [(1,1)] (0,0)
// (all 8 triangles are a fan around (1,1), so every other step re-sends it;
// (2,2) twice where the second root's strip joins the first: 6 degenerate
// triangles), I(1) = 16 = 2 + 8 + 6. Two more levels make each leaf triangle four
// in the same Sierpinski pattern: the strip is four copies of the coarser
// pattern sharing 8 indices where they meet, I(n + 1) = 4 I(n) - 8 (5x5: 56
// indices, 32 triangles), whose solution from I(1) = 16 is
//     I0(n) = (10 * 4^n + 8) / 3 = (5 T + 8) / 3,
// 5/3 per triangle plus 8/3 in all. Subtrees at the chunk level c (at
// least two levels tall, c <= 2n - 2, as the default clamp(2n - 10, 0, 6)
// always is) are walked as separate strips, each beginning with its entry
// vertex twice, and joined into one: before a subtree of odd level the
// doubled entry takes the place of the vertex the single walk re-sends there
// (no cost); before one of even level k >= 2 the entry stands three times
// where the single walk has it once (2 more indices). Level k brings 2^k new
// joins, so with e the largest even level <= c
//     I = I0 + 2 (2^2 + 2^4 + ... + 2^e) = I0 + 8 (2^e - 1) / 3.
// The same for one thread and two: the joined strip does not depend on who
// walked which subtree.
TEST(SbtFixed, FullGridStripLengthIsExact) {
    for (int n : {1, 2, 5, 7, 8}) {
        const int size = (1 << n) + 1;
        Heightfield f = fractal(size, 5);
        auto ve = sbt::computeVertexErrors(f);
        for (int chunkLevel : {-1, 0, 1, 2, 3, 4, 6}) {
            if (chunkLevel > 2 * n - 2) continue;
            for (int threads : {1, 2}) {
                sbt::Refiner refiner(f, ve, {.threads = threads, .chunkLevel = chunkLevel});
                sbt::StripMesh mesh;
                refiner.refineFixed(-1.0f, mesh);
                const int64_t t = int64_t(2) << (2 * n);
                const int e = refiner.chunkLevel() & ~1;
                const int64_t indices = (5 * t + 8) / 3 + 8 * ((int64_t(1) << e) - 1) / 3;
                EXPECT_EQ(mesh.triangleCount, t) << size << " chunk level " << chunkLevel;
                EXPECT_EQ(int64_t(mesh.indices.size()), indices)
                    << size << " chunk level " << refiner.chunkLevel() << ", " << threads
                    << " threads";
                EXPECT_EQ(mesh.stripCount, 1);
            }
        }
    }
}

// Adaptive fixed-error meshes: fewer indices per triangle than the full grid's
// 5/3 (fewer turns where the levels are mixed), and well under the paper's 2.
TEST(SbtFixed, IndicesPerTriangleOfAdaptiveMeshes) {
    for (int size : {129, 257}) {
        Heightfield f = size == 129 ? gaussians(size, 4) : fractal(size, 4);
        auto ve = sbt::computeVertexErrors(f);
        sbt::Refiner refiner(f, ve);
        sbt::StripMesh mesh;
        float emax = *std::max_element(ve.error.begin(), ve.error.end());
        for (float eps : {0.0f, emax * 0.001f, emax * 0.01f, emax * 0.05f}) {
            refiner.refineFixed(eps, mesh);
            if (mesh.triangleCount < 1000) continue;
            std::printf("%d eps %g: %lld triangles, %.4f indices per triangle\n", size, eps,
                        (long long)mesh.triangleCount, mesh.indicesPerTriangle());
            EXPECT_LE(mesh.indicesPerTriangle(), 1.7)
                << size << " eps " << eps << " triangles " << mesh.triangleCount;
        }
    }
}

// --- view-dependent ---------------------------------------------------------

struct Camera {
    std::array<float, 3> eye;
    std::array<float, 16> viewProj;  // column-major
};

Camera randomCamera(std::mt19937_64& rng, float extent, float height, float aspect, float fovy) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Camera cam;
    cam.eye = {extent * (1.6f * u(rng) - 0.3f), height * (0.2f + 2.0f * u(rng)),
               extent * (1.6f * u(rng) - 0.3f)};
    std::array<float, 3> target = {extent * u(rng), 0.0f, extent * u(rng)};
    std::array<float, 3> f = {target[0] - cam.eye[0], target[1] - cam.eye[1],
                              target[2] - cam.eye[2]};
    float fl = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (float& x : f) x /= fl;
    std::array<float, 3> up = {0, 1, 0};
    std::array<float, 3> s = {f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2],
                              f[0] * up[1] - f[1] * up[0]};
    float sl = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (float& x : s) x /= sl;
    std::array<float, 3> uu = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2],
                               s[0] * f[1] - s[1] * f[0]};
    float view[16] = {s[0],
                      uu[0],
                      -f[0],
                      0,
                      s[1],
                      uu[1],
                      -f[1],
                      0,
                      s[2],
                      uu[2],
                      -f[2],
                      0,
                      -(s[0] * cam.eye[0] + s[1] * cam.eye[1] + s[2] * cam.eye[2]),
                      -(uu[0] * cam.eye[0] + uu[1] * cam.eye[1] + uu[2] * cam.eye[2]),
                      (f[0] * cam.eye[0] + f[1] * cam.eye[1] + f[2] * cam.eye[2]),
                      1};
    float zn = 0.5f, zf = extent * 4.0f, t = 1.0f / std::tan(fovy / 2);
    float proj[16] = {t / aspect,
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
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            float v = 0;
            for (int k = 0; k < 4; ++k) v += proj[k * 4 + r] * view[c * 4 + k];
            cam.viewProj[c * 4 + r] = v;
        }
    return cam;
}

TEST(SbtView, RandomCamerasConformBoundErrorAndCullOnlyOutside) {
    std::mt19937_64 rng(123);
    for (int trial = 0; trial < 24; ++trial) {
        const int side = trial % 3 == 0 ? 129 : 65;
        Heightfield f = trial % 2 ? fractal(side, trial, 1.0f) : gaussians(side, trial);
        if (trial % 2) f.setVerticalScale(40.0f);
        f.setSpacing(1.0f + 0.1f * (trial % 4), 1.0f);
        auto ve = sbt::computeVertexErrors(f);
        sbt::Refiner refiner(f, ve, {.threads = 1 + trial % 3});
        const float extent = (side - 1) * f.spacingX();
        auto [lo, hi] = f.range();
        Camera cam =
            randomCamera(rng, extent, (hi - lo) * f.verticalScale() + 10.0f, 16.0f / 9.0f, 1.0f);
        sbt::ViewParams vp;
        vp.eye = cam.eye;
        vp.lambda = sbt::projectionLambda(1080.0f, 1.0f);
        vp.tau = std::uniform_real_distribution<float>(0.5f, 16.0f)(rng);
        vp.planes = sbt::frustumPlanes(cam.viewProj.data());
        SCOPED_TRACE("trial " + std::to_string(trial));

        auto posOf = [&](uint32_t v) {
            uint32_t i = v % side, j = v / side;
            return std::array<double, 3>{i * double(f.spacingX()),
                                         double(f.at(i, j)) * double(f.verticalScale()),
                                         j * double(f.spacingZ())};
        };
        const double kE = double(vp.lambda) / double(vp.tau);
        auto active = [&](uint32_t m) {
            auto p = posOf(m);
            double dx = p[0] - vp.eye[0], dy = p[1] - vp.eye[1], dz = p[2] - vp.eye[2];
            double reach = kE * double(ve.error[m]) + double(ve.radius[m]);
            return reach * reach > dx * dx + dy * dy + dz * dz;
        };
        // no culling: the whole conforming mesh, exactly the brute-force leaves
        vp.cull = false;
        sbt::StripMesh all;
        refiner.refineView(vp, all);
        std::vector<Node> expected;
        leaves(
            side, [&](uint32_t m, int) { return active(m); }, expected);
        auto allTris = sbt::decodeStrip(all.indices);
        ASSERT_EQ(sortedTris(allTris), sortedTris(expected));
        expectConforming(allTris, side, true);
        expectConsecutiveShareEdge(all.indices);
        const int n = std::countr_zero(unsigned(side - 1));
        for (const Node& nd : expected) {
            if (nd.level == 2 * n) continue;
            uint32_t m = (nd.a + nd.b) / 2;
            auto p = posOf(m);
            double d = std::sqrt((p[0] - vp.eye[0]) * (p[0] - vp.eye[0]) +
                                 (p[1] - vp.eye[1]) * (p[1] - vp.eye[1]) +
                                 (p[2] - vp.eye[2]) * (p[2] - vp.eye[2]));
            double r = ve.radius[m];
            ASSERT_GT(d, r - 1e-6) << "an inactive vertex cannot hold the eye in its sphere";
            if (d > r) {
                EXPECT_LE(vp.lambda * ve.error[m] / (d - r), vp.tau * (1 + 1e-5));
            }
        }
        // culling: a subset of the same mesh; what is missing is outside a plane
        vp.cull = true;
        sbt::StripMesh visible;
        refiner.refineView(vp, visible);
        auto visTris = sbt::decodeStrip(visible.indices);
        EXPECT_EQ(visible.triangleCount, int64_t(visTris.size()));
        expectConforming(visTris, side, false);
        expectConsecutiveShareEdge(visible.indices);
        auto allSorted = sortedTris(allTris), visSorted = sortedTris(visTris);
        std::vector<Tri> culled;
        std::set_difference(allSorted.begin(), allSorted.end(), visSorted.begin(), visSorted.end(),
                            std::back_inserter(culled));
        ASSERT_EQ(culled.size() + visSorted.size(), allSorted.size()) << "visible is a subset";
        for (const Tri& t : culled) {
            bool outside = false;
            for (const sbt::Plane& pl : vp.planes) {
                bool allOut = true;
                for (uint32_t v : t) {
                    auto p = posOf(v);
                    allOut = allOut && pl.a * p[0] + pl.b * p[1] + pl.c * p[2] + pl.d < 0;
                }
                outside = outside || allOut;
            }
            ASSERT_TRUE(outside) << "a culled triangle is entirely outside one frustum plane";
        }
        // identical for 1, 2 and 4 threads
        for (int threads : {1, 2, 4}) {
            refiner.setThreads(threads);
            sbt::StripMesh again;
            refiner.refineView(vp, again);
            EXPECT_EQ(again.indices, visible.indices);
        }
    }
}

// As SbtFixed.OneThreadJoinsIntoAReusedMeshAsSeveralThreadsDo, for views with
// and without culling: culled gaps restart the strip, so the joins meet
// every kind of seam between chunks.
TEST(SbtView, OneThreadJoinsIntoAReusedMeshAsSeveralThreadsDo) {
    std::mt19937_64 rng(31);
    Heightfield f = fractal(257, 5, 1.0f);
    f.setVerticalScale(30.0f);
    auto ve = sbt::computeVertexErrors(f);
    sbt::Refiner serial(f, ve, {.threads = 1});
    sbt::StripMesh reused;
    int restarts = 0;
    for (int trial = 0; trial < 16; ++trial) {
        SCOPED_TRACE("trial " + std::to_string(trial));
        auto [lo, hi] = f.range();
        Camera cam =
            randomCamera(rng, 256.0f, (hi - lo) * f.verticalScale() + 10.0f, 16.0f / 9.0f, 1.0f);
        sbt::ViewParams vp;
        vp.eye = cam.eye;
        vp.lambda = sbt::projectionLambda(1080.0f, 1.0f);
        vp.tau = std::uniform_real_distribution<float>(0.3f, 8.0f)(rng);
        vp.planes = sbt::frustumPlanes(cam.viewProj.data());
        vp.cull = trial % 4 != 3;
        serial.refineView(vp, reused);
        expectAsAParallelRefinement(
            f, ve, reused, [&](sbt::Refiner& r, sbt::StripMesh& m) { r.refineView(vp, m); });
        restarts += reused.stripCount > 1;
    }
    EXPECT_GT(restarts, 3) << "views whose strip restarts at culled gaps";
}

}  // namespace

namespace {

// The fast view path (float tests with a double fallback in a guard band, one
// record per vertex) against the double-precision baseline: byte-identical
// strips for random cameras, rough and smooth terrain, large world
// coordinates, with and without culling, 1 and 2 threads.
TEST(SbtView, FastPathEmitsTheBaselineStrip) {
    std::mt19937_64 rng(77);
    int64_t triangles = 0;
    for (int trial = 0; trial < 30; ++trial) {
        const int side = trial % 3 == 0 ? 257 : 129;
        Heightfield f =
            trial % 4 == 3
                ? gaussians(side, trial)
                : sierra::terrain::generateDiamondSquare({.size = side,
                                                          .seed = uint64_t(trial),
                                                          .hurst = 0.4f + 0.1f * float(trial % 6)});
        auto [lo, hi] = f.range();
        const float spacing = trial % 5 == 0 ? 30.0f : 1.0f + 0.25f * float(trial % 3);
        f.setSpacing(spacing, spacing * (trial % 2 ? 1.0f : 0.75f));
        f.setVerticalScale(0.2f * float(side - 1) * spacing / std::max(1e-6f, hi - lo));
        auto ve = sbt::computeVertexErrors(f);
        sbt::Refiner refiner(f, ve, {.threads = 1 + trial % 2});
        const float extent = float(side - 1) * spacing;
        Camera cam = randomCamera(rng, extent, 0.2f * extent + 1.0f, 16.0f / 9.0f, 0.8f);
        sbt::ViewParams vp;
        vp.eye = cam.eye;
        vp.lambda = sbt::projectionLambda(1080.0f, 0.8f);
        vp.tau = std::uniform_real_distribution<float>(0.25f, 8.0f)(rng);
        vp.planes = sbt::frustumPlanes(cam.viewProj.data());
        for (bool cull : {false, true}) {
            vp.cull = cull;
            sbt::StripMesh fast, reference;
            refiner.refineView(vp, fast);
            refiner.refineViewReference(vp, reference);
            ASSERT_EQ(fast.indices, reference.indices) << "trial " << trial << " cull " << cull;
            EXPECT_EQ(fast.triangleCount, reference.triangleCount);
            EXPECT_EQ(fast.stripCount, reference.stripCount);
            triangles += fast.triangleCount;
        }
    }
    EXPECT_GT(triangles, 100000) << "the cameras see real meshes";
}

// prepareView builds the view keys once (2 keys of 16 bits per triangle of
// levels 0 ... 2n - 1: 2^(2n+1) - 2 of them, about 8 bytes per sample), with
// the reaches for the lambda / tau it is given, and refineView then neither
// rebuilds them nor emits another strip than a refiner that builds them
// itself; refineFixed adds its split keys (one per triangle).
TEST(SbtView, PrepareViewBuildsTheKeysOnce) {
    const int side = 129;  // n = 7
    Heightfield f = sierra::terrain::generateDiamondSquare({.size = side, .seed = 5});
    f.setVerticalScale(20.0f);
    auto ve = sbt::computeVertexErrors(f);
    const size_t triangles = (size_t(1) << 15) - 2;
    const float lambda = sbt::projectionLambda(1080.0f, 0.8f);
    sbt::Refiner prepared(f, ve, {.threads = 1}), lazy(f, ve, {.threads = 1});
    EXPECT_EQ(prepared.keyBytes(), 0u);
    EXPECT_EQ(prepared.reachKeyFactor(), 0.0);
    prepared.prepareView(double(lambda));
    EXPECT_EQ(prepared.keyBytes(), 2 * 2 * triangles);
    EXPECT_EQ(prepared.reachKeyFactor(), double(lambda));
    prepared.prepareView(2.0 * double(lambda));
    EXPECT_EQ(prepared.keyBytes(), 2 * 2 * triangles);
    EXPECT_EQ(prepared.reachKeyFactor(), double(lambda)) << "prepared once";
    std::mt19937_64 rng(9);
    for (int k = 0; k < 4; ++k) {
        Camera cam = randomCamera(rng, float(side - 1), 30.0f, 16.0f / 9.0f, 0.8f);
        sbt::ViewParams vp;
        vp.eye = cam.eye;
        vp.lambda = lambda;
        vp.tau = 1.0f;
        vp.planes = sbt::frustumPlanes(cam.viewProj.data());
        sbt::StripMesh a, b;
        prepared.refineView(vp, a);
        lazy.refineView(vp, b);
        ASSERT_EQ(a.indices, b.indices) << "camera " << k;
    }
    EXPECT_EQ(prepared.keyBytes(), 2 * 2 * triangles);
    EXPECT_EQ(lazy.keyBytes(), 2 * 2 * triangles);
    EXPECT_EQ(lazy.reachKeyFactor(), double(lambda)) << "made for the first view";
    sbt::StripMesh fixed;
    prepared.refineFixed(0.5f, fixed);
    EXPECT_EQ(prepared.keyBytes(), 3 * 2 * triangles);
}

// The view keys hold reaches for one lambda / tau. A view with another
// factor s times it decides from them with bounds widened by s, exactly as
// the baseline; the reaches are made again only after kReachRebuildAfter (4)
// refinements in a row ask for one other factor, so a tau or zoom that
// changes every frame never pays a rebuild.
TEST(SbtView, ViewKeysServeOtherFactorsAndFollowOneThatStays) {
    Heightfield f = sierra::terrain::generateDiamondSquare({.size = 257, .seed = 3, .hurst = 0.6f});
    auto [lo, hi] = f.range();
    f.setVerticalScale(0.2f * 256.0f / (hi - lo));
    auto ve = sbt::computeVertexErrors(f);
    const float vs = f.verticalScale();
    for (int threads : {1, 2}) {
        SCOPED_TRACE(testing::Message() << "threads " << threads);
        sbt::Refiner refiner(f, ve, {.threads = threads});
        // tau per refinement, and the factor the keys should have after it
        // (in units of lambda: 1 / tau)
        const struct {
            float tau, keysTau;
        } steps[] = {{1.0f, 1.0f},  {0.25f, 1.0f}, {6.0f, 1.0f}, {1.0f, 1.0f}, {1.02f, 1.0f},
                     {0.98f, 1.0f}, {3.0f, 1.0f},  {3.0f, 1.0f}, {3.0f, 1.0f}, {2.0f, 1.0f},
                     {3.0f, 1.0f},  {3.0f, 1.0f},  {3.0f, 1.0f}, {3.0f, 3.0f}, {3.0f, 3.0f},
                     {0.5f, 3.0f},  {1.0f, 3.0f},  {0.3f, 3.0f}, {0.3f, 3.0f}, {0.3f, 3.0f},
                     {0.3f, 0.3f},  {1.0f, 0.3f}};
        int64_t triangles = 0;
        int step = 0;
        for (const auto& s : steps) {
            SCOPED_TRACE(testing::Message() << "step " << step << ", tau " << s.tau);
            const float angle = 0.3f * float(step++);
            const sbt::ViewParams vp = sbt::lookAtView(
                {128.0f + 200.0f * std::cos(angle), hi * vs + 40.0f,
                 128.0f + 200.0f * std::sin(angle)},
                {128.0f, lo * vs, 128.0f}, 0.8f, 16.0f / 9.0f, 1080.0f, 0.5f, 2000.0f, s.tau);
            sbt::StripMesh fast, reference;
            refiner.refineView(vp, fast);
            refiner.refineViewReference(vp, reference);
            ASSERT_EQ(fast.indices, reference.indices);
            EXPECT_EQ(refiner.reachKeyFactor(), double(vp.lambda) / double(s.keysTau));
            triangles += fast.triangleCount;
        }
        EXPECT_GT(triangles, 200000) << "the views see real meshes";
    }
}

// A lambda / tau far above the keys' (a billion times: tau 1e-9 px after
// keys made at 1 px) takes more off the low bound of a reach than a small
// reach's key holds: the bound must stay at 0, not turn into a large
// negative number whose square passes for a reach. The eye looks at the
// edge of a flat plateau, where rough parents (active at any tau) have
// children of error 0, active only if the eye is inside their sphere.
// Without the bound held at 0 the strip differs from the baseline's.
TEST(SbtView, ViewKeysOfAFarSmallerTauStillDecideAsTheBaseline) {
    const int side = 129;
    Heightfield f = fractal(side, 4);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side / 2; ++i) f.at(i, j) = 0.0f;  // error 0 on the west half
    auto ve = sbt::computeVertexErrors(f);
    sbt::Refiner refiner(f, ve, {.threads = 1});
    int64_t triangles = 0;
    for (float tau : {1.0f, 1e-9f, 1e-9f, 1.0f}) {
        SCOPED_TRACE(testing::Message() << "tau " << tau);
        const sbt::ViewParams vp =
            sbt::lookAtView({90.0f, 15.0f, 30.3f}, {64.0f, 0.0f, 64.0f}, 0.8f, 16.0f / 9.0f,
                            1080.0f, 0.01f, 1000.0f, tau);
        sbt::StripMesh fast, reference;
        refiner.refineView(vp, fast);
        refiner.refineViewReference(vp, reference);
        ASSERT_EQ(fast.indices, reference.indices);
        triangles += fast.triangleCount;
    }
    EXPECT_EQ(refiner.reachKeyFactor(), double(sbt::projectionLambda(1080.0f, 0.8f)))
        << "the keys stay those of tau = 1 px";
    EXPECT_GT(triangles, 1000);
}

}  // namespace

// The largest grid is the largest 2^n+1 side whose vertices 32-bit strip
// indices address without reaching the restart index; the next one would wrap.
TEST(SbtLimits, LargestGridFitsThirtyTwoBitIndices) {
    const uint64_t side = uint64_t(sierra::sbt::kMaxSbtSide);
    EXPECT_TRUE(std::has_single_bit(side - 1));
    EXPECT_LT(side * side, uint64_t(sierra::sbt::kRestartIndex));
    EXPECT_GE((2 * side - 1) * (2 * side - 1), uint64_t(sierra::sbt::kRestartIndex));
}
