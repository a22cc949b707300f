// Geomorphing inside the error bound (sbt/Morph.h): on rough fractals and
// random cameras, every drawn vertex stays within tau pixels of the
// full-resolution surface, the morph is complete wherever the coarse surface's
// error bound reaches tau, and a small camera move (0.1% of the extent) moves
// no vertex by tau in screen space.
#include <sierra/sbt/Morph.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/DiamondSquare.h>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_map>
#include <vector>

namespace {

namespace sbt = sierra::sbt;
using sierra::terrain::Heightfield;

struct Terrain {
    Heightfield field;
    sbt::VertexErrors errors;
    std::vector<float> base;
    float extent;
};

// A rough fractal (Hurst 0.5) with the renderer's automatic vertical scale
// (relief 20% of the extent).
Terrain roughTerrain(int size, uint64_t seed) {
    Terrain t;
    t.field = sierra::terrain::generateDiamondSquare({.size = size, .seed = seed, .hurst = 0.5f});
    auto [lo, hi] = t.field.range();
    t.field.setVerticalScale(0.2f * float(size - 1) / (hi - lo));
    t.errors = sbt::computeVertexErrors(t.field);
    t.base = sbt::buildMorphBase(t.field);
    t.extent = float(size - 1);
    return t;
}

struct View {
    glm::vec3 eye;
    sbt::ViewParams params;  // refinement at refinementTau(tau)
    float tau;
};

View makeView(const Terrain& t, glm::vec3 eye, glm::vec3 target, float tau) {
    const float fovy = glm::radians(45.0f);
    const glm::mat4 vp = glm::perspective(fovy, 16.0f / 9.0f, t.extent * 1e-3f, t.extent * 4.0f) *
                         glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    View v;
    v.eye = eye;
    v.tau = tau;
    v.params.eye = {eye.x, eye.y, eye.z};
    v.params.lambda = sbt::projectionLambda(1080.0f, fovy);
    v.params.tau = sbt::refinementTau(tau);
    v.params.planes = sbt::frustumPlanes(glm::value_ptr(vp));
    return v;
}

View randomView(const Terrain& t, std::mt19937_64& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto [lo, hi] = t.field.range();
    const float vs = t.field.verticalScale();
    const glm::vec3 eye{t.extent * (1.4f * u(rng) - 0.2f),
                        hi * vs + t.extent * (0.01f + 0.3f * u(rng)),
                        t.extent * (1.4f * u(rng) - 0.2f)};
    const glm::vec3 target{t.extent * u(rng), lo * vs, t.extent * u(rng)};
    return makeView(t, eye, target, 0.5f + 3.0f * u(rng));
}

glm::vec3 truePosition(const Terrain& t, uint32_t v) {
    const int side = t.field.width();
    const int i = int(v % uint32_t(side)), j = int(v / uint32_t(side));
    return {float(i) * t.field.spacingX(), t.field.worldHeight(i, j),
            float(j) * t.field.spacingZ()};
}

// Morphed height of vertex v as the shader computes it (sbt::morphedHeight).
float drawnHeight(const Terrain& t, const View& view, uint32_t v) {
    const glm::vec3 p = truePosition(t, v);
    return sbt::morphedHeight(p.y, t.base[v], t.errors.error[v], t.errors.radius[v],
                              glm::distance(p, view.eye), view.params.lambda / view.tau);
}

std::vector<uint32_t> drawnVertices(const std::vector<uint32_t>& strip) {
    std::vector<uint32_t> v;
    for (uint32_t k : strip)
        if (k != sbt::kRestartIndex) v.push_back(k);
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
}

TEST(SbtMorph, WeightIsZeroAtActivationOneAtTheBudget) {
    const float lambda = 1000.0f, tau = 2.0f, e = 0.5f, r = 3.0f;
    // activation at kMorphStart * tau: lambda e / (d - r) = kMorphStart tau
    const float dActive = lambda * e / (sbt::kMorphStart * tau) + r;
    const float dBudget = lambda * e / tau + r;
    EXPECT_NEAR(sbt::morphWeight(e, r, dActive, lambda / tau), 0.0f, 1e-5f);
    EXPECT_NEAR(sbt::morphWeight(e, r, dBudget, lambda / tau), 1.0f, 1e-5f);
    EXPECT_EQ(sbt::morphWeight(e, r, 2.0f * dActive, lambda / tau), 0.0f);
    EXPECT_EQ(sbt::morphWeight(e, r, 0.5f * dBudget, lambda / tau), 1.0f);
    EXPECT_EQ(sbt::morphWeight(e, r, r * 0.5f, lambda / tau), 1.0f) << "eye inside the sphere";
    float previous = 0.0f;
    for (float d = dActive; d >= dBudget; d -= 0.01f * (dActive - dBudget)) {
        const float w = sbt::morphWeight(e, r, d, lambda / tau);
        EXPECT_GE(w, previous) << "monotone as the eye approaches";
        previous = w;
    }
    EXPECT_FLOAT_EQ(sbt::morphedHeight(10.0f, 4.0f, e, r, 0.5f * dBudget, lambda / tau), 10.0f);
    EXPECT_FLOAT_EQ(sbt::morphedHeight(10.0f, 4.0f, e, r, 2.0f * dActive, lambda / tau), 4.0f);
}

TEST(SbtMorph, DrawnVerticesStayWithinTauAndMorphsEndAtTheBudget) {
    std::mt19937_64 rng(2024);
    int64_t checked = 0, morphing = 0;
    for (int trial = 0; trial < 12; ++trial) {
        const Terrain t = roughTerrain(trial % 2 ? 257 : 513, uint64_t(trial) + 1);
        sbt::Refiner refiner(t.field, t.errors);
        const View view = randomView(t, rng);
        sbt::StripMesh mesh;
        refiner.refineView(view.params, mesh);
        const float lambda = view.params.lambda;
        for (uint32_t v : drawnVertices(mesh.indices)) {
            const glm::vec3 p = truePosition(t, v);
            const float d = glm::distance(p, view.eye);
            const float w =
                sbt::morphWeight(t.errors.error[v], t.errors.radius[v], d, lambda / view.tau);
            const float displacement = std::fabs(drawnHeight(t, view, v) - p.y);
            ASSERT_LE(lambda * displacement / d, view.tau * (1.0f + 1e-4f))
                << "trial " << trial << " vertex " << v << " w " << w;
            // The coarse surface's bound mu = lambda e / (d - r) has reached
            // tau: the vertex must be at its true height.
            const float gap = d - t.errors.radius[v];
            if (gap <= 0.0f || lambda * t.errors.error[v] / gap >= view.tau * (1.0f + 1e-4f)) {
                ASSERT_EQ(w, 1.0f) << "trial " << trial << " vertex " << v;
            }
            morphing += w > 0.0f && w < 1.0f;
            ++checked;
        }
    }
    EXPECT_GT(checked, 100000);
    EXPECT_GT(morphing, checked / 50) << "the cameras see vertices in mid-morph";
}

TEST(SbtMorph, SmallCameraMovesDoNotPop) {
    std::mt19937_64 rng(99);
    int64_t compared = 0;
    float worst = 0, worstPop = 0;
    for (int trial = 0; trial < 10; ++trial) {
        const Terrain t = roughTerrain(257, uint64_t(trial) + 50);
        sbt::Refiner refiner(t.field, t.errors);
        View a = randomView(t, rng);
        std::normal_distribution<float> g(0.0f, 1.0f);
        glm::vec3 dir{g(rng), g(rng), g(rng)};
        const glm::vec3 moved = a.eye + glm::normalize(dir) * (1e-3f * t.extent);
        View b = a;
        b.eye = moved;
        b.params.eye = {moved.x, moved.y, moved.z};
        a.params.cull = b.params.cull = false;  // compare the whole mesh
        sbt::StripMesh ma, mb;
        refiner.refineView(a.params, ma);
        refiner.refineView(b.params, mb);
        const std::vector<uint32_t> va = drawnVertices(ma.indices), vb = drawnVertices(mb.indices);
        std::vector<uint32_t> all;
        std::set_union(va.begin(), va.end(), vb.begin(), vb.end(), std::back_inserter(all));
        const float lambda = a.params.lambda;
        for (uint32_t v : all) {
            const bool inA = std::binary_search(va.begin(), va.end(), v);
            const bool inB = std::binary_search(vb.begin(), vb.end(), v);
            // A vertex missing from one mesh lies on that mesh's coarser
            // surface, at its morph base (its hypotenuse is drawn there).
            const float ha = inA ? drawnHeight(t, a, v) : t.base[v];
            const float hb = inB ? drawnHeight(t, b, v) : t.base[v];
            const glm::vec3 p = truePosition(t, v);
            const float d = std::min(glm::distance(p, a.eye), glm::distance(p, b.eye));
            ASSERT_LT(lambda * std::fabs(ha - hb) / d, a.tau)
                << "trial " << trial << " vertex " << v << (inA ? " in a" : "")
                << (inB ? " in b" : "");
            worst = std::max(worst, lambda * std::fabs(ha - hb) / d / a.tau);
            const float pa = inA ? p.y : t.base[v], pb = inB ? p.y : t.base[v];
            worstPop = std::max(worstPop, lambda * std::fabs(pa - pb) / d / a.tau);
            ++compared;
        }
    }
    EXPECT_GT(compared, 10000);
    // The move does change the mesh: without the morph (vertices at their true
    // height as soon as drawn) the largest jump is close to kMorphStart * tau;
    // with it, a small fraction of tau (measured: 0.024 tau against 0.75).
    EXPECT_GT(worstPop, 0.5f);
    EXPECT_LT(worst, 0.1f);
}

}  // namespace
