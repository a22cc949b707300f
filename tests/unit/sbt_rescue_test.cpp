// A helper thread stalled inside a refinement chunk (the test hook of
// parallelRescuedChunks makes it sleep there, as a preempted thread would):
// the refinement returns without waiting for it, its output is byte-identical
// to one thread's, and the refinements made while the sleeper still holds the
// previous one's data are identical too and run on one thread, without a
// second set of chunk buffers.
#include <sierra/core/Parallel.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/DiamondSquare.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

namespace {

namespace sbt = sierra::sbt;
using sierra::terrain::Heightfield;

double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void expectSame(const sbt::StripMesh& a, const sbt::StripMesh& b) {
    EXPECT_EQ(a.indices, b.indices);
    EXPECT_EQ(a.triangleCount, b.triangleCount);
    EXPECT_EQ(a.stripCount, b.stripCount);
    EXPECT_EQ(a.culledSubtrees, b.culledSubtrees);
}

TEST(SbtRescue, AStalledHelperNeitherChangesTheOutputNorHoldsTheRefinement) {
    Heightfield f = sierra::terrain::generateDiamondSquare({.size = 513, .seed = 5, .hurst = 0.7f});
    auto [lo, hi] = f.range();
    f.setVerticalScale(0.2f * 512.0f / (hi - lo));
    const sbt::VertexErrors ve = sbt::computeVertexErrors(f);
    const float vs = f.verticalScale();
    const sbt::ViewParams view =
        sbt::lookAtView({-60.0f, hi * vs + 80.0f, -40.0f}, {256.0f, lo * vs, 256.0f}, 0.8f,
                        16.0f / 9.0f, 1080.0f, 0.5f, 2000.0f, 0.5f);
    sbt::StripMesh fixedSerial, viewSerial;
    double serialSeconds = 0;
    {
        sbt::Refiner serial(f, ve, {.threads = 1});
        serial.refineFixed(-1.0f, fixedSerial);  // the full grid: 524 288 triangles, parallel
        const auto t0 = std::chrono::steady_clock::now();
        serial.refineFixed(-1.0f, fixedSerial);
        serial.refineView(view, viewSerial);
        serialSeconds = secondsSince(t0);
    }
    ASSERT_EQ(fixedSerial.triangleCount, int64_t(2) * 512 * 512);
    ASSERT_GT(viewSerial.triangleCount, sbt::kParallelTriangles) << "the view refines in parallel";

    // The helper sleeps in the first chunk it takes, at least 1 s and far longer
    // than the refinements take on one thread (sanitizer builds are slow), so a
    // caller that waited for it cannot stay under half the sleep. Whether it
    // takes a chunk before the caller has taken them all depends on the
    // scheduler: a few tries, until one refinement has had a chunk run again.
    const double kStall = std::max(1.0, 10.0 * serialSeconds);
    sierra::setHelperStallForTesting(kStall);
    const int64_t rescuesBefore = sierra::parallelRescueCount();
    for (int attempt = 0; attempt < 8 && sierra::parallelRescueCount() == rescuesBefore;
         ++attempt) {
        SCOPED_TRACE(testing::Message() << "attempt " << attempt);
        sierra::waitParallelHelpers();
        sbt::Refiner refiner(f, ve, {.threads = 2});
        sbt::StripMesh fixed, again, viewed;
        auto t0 = std::chrono::steady_clock::now();
        refiner.refineFixed(-1.0f, fixed);
        EXPECT_LT(secondsSince(t0), 0.5 * kStall)
            << "the refinement waited for the sleeping helper";
        expectSame(fixed, fixedSerial);
        const size_t bytes = refiner.bufferBytes();
        // At once again (the sleeper, if any, still holds the first one's data),
        // then a view.
        t0 = std::chrono::steady_clock::now();
        refiner.refineFixed(-1.0f, again);
        refiner.refineView(view, viewed);
        EXPECT_LT(secondsSince(t0), 0.5 * kStall);
        expectSame(again, fixedSerial);
        expectSame(viewed, viewSerial);
        // While the sleeper holds the first refinement's chunk strips, the
        // others run on one thread through one small buffer: they do not grow
        // a second set of chunk strips (the whole output's size again).
        EXPECT_LT(refiner.bufferBytes(), bytes + fixed.indices.size() * sizeof(uint32_t) / 4);
    }  // the refiner's destructor waits for the sleeper
    sierra::setHelperStallForTesting(0.0);
    EXPECT_GT(sierra::parallelRescueCount(), rescuesBefore) << "no helper ever took a chunk";

    // With no stall, two threads still give the same meshes.
    sbt::Refiner refiner(f, ve, {.threads = 2});
    sbt::StripMesh fixed, viewed;
    for (int k = 0; k < 3; ++k) {
        refiner.refineFixed(-1.0f, fixed);
        refiner.refineView(view, viewed);
        expectSame(fixed, fixedSerial);
        expectSame(viewed, viewSerial);
    }
}

}  // namespace
