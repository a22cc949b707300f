// Budget stops (tin::BudgetStop): with BestMax a triangle or point budget keeps
// the mesh of smallest max error among those the run went through, so the max
// error at a budget is the running minimum and never grows with the budget.
// The reference is built independently: a Last run at every smaller budget,
// each measured over every sample.
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/tin/Tin.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <vector>

namespace {

using namespace sierra;

terrain::Heightfield fractal(int size, uint64_t seed) {
    return terrain::generateDiamondSquare({.size = size, .seed = seed, .threads = 1});
}

void expectSameMesh(const tin::TinMesh& a, const tin::TinMesh& b, const char* what) {
    EXPECT_EQ(a.vertices, b.vertices) << what;
    EXPECT_EQ(a.triangles, b.triangles) << what;
    EXPECT_EQ(a.constrainedEdges, b.constrainedEdges) << what;
    EXPECT_EQ(a.edgeZones, b.edgeZones) << what;
    EXPECT_EQ(a.zone, b.zone) << what;
}

// Two borderlines on a 65^2 grid: one across it with collinear steps, one bent
// from the top edge to its middle vertex (three zones), so the journal also
// sees exact edge splits and snap splits of constrained edges.
tin::Constraints borderlines() {
    tin::Constraints c;
    c.vertices = {{0, 20}, {16, 24}, {32, 28}, {64, 36}, {40, 0}, {30, 14.4}};
    c.segments = {{0, 1, 1, 2}, {1, 2, 1, 2}, {2, 3, 1, 3}, {4, 5, 2, 3}, {5, 2, 2, 3}};
    return c;
}

// With a point budget: the kept mesh's max error is the smallest of the Last
// runs' at every budget up to it, and the kept mesh is exactly the Last run's
// at the kept size (going back is the same as stopping there).
TEST(TinBudget, BestMaxKeepsTheSmallestMaxErrorSoFar) {
    for (uint64_t seed : {1, 2}) {
        const terrain::Heightfield field = fractal(65, seed);
        constexpr int kFirst = 5, kLast = 160;
        std::vector<double> lastMax(kLast + 1, 0.0);
        std::vector<tin::TinResult> last(kLast + 1);
        for (int p = kFirst; p <= kLast; ++p) {
            last[size_t(p)] =
                tin::buildTin(field, {}, {.maxPoints = p, .budgetStop = tin::BudgetStop::Last});
            ASSERT_EQ(last[size_t(p)].mesh.vertices.size(), size_t(p));
            lastMax[size_t(p)] = tin::measureError(last[size_t(p)].mesh, field).maxError;
        }
        int wentBack = 0;
        double runningMin = std::numeric_limits<double>::infinity();
        for (int p = kFirst; p <= kLast; ++p) {
            runningMin = std::min(runningMin, lastMax[size_t(p)]);
            const tin::TinResult best = tin::buildTin(field, {}, {.maxPoints = p});
            ASSERT_EQ(best.stats.stop, tin::StopReason::Points);
            const size_t kept = best.mesh.vertices.size();
            ASSERT_GE(kept, size_t(kFirst));
            ASSERT_LE(kept, size_t(p));
            // The max over every sample is the smallest so far, and on a tie the
            // largest mesh that has it is kept.
            const double max = tin::measureError(best.mesh, field).maxError;
            EXPECT_EQ(max, runningMin) << "seed " << seed << ", " << p << " points";
            for (size_t q = kept + 1; q <= size_t(p); ++q)
                EXPECT_GT(lastMax[q], max) << "seed " << seed << ", " << p << " points";
            expectSameMesh(best.mesh, last[kept].mesh, "kept mesh against the Last run");
            EXPECT_NEAR(best.stats.worstError, max, 1e-6 * std::max(1.0, max));
            EXPECT_EQ(best.stats.inserted, int64_t(kept) - 4);
            EXPECT_EQ(best.stats.budgetInserted, int64_t(p) - 4);
            EXPECT_EQ(best.stats.budgetWorstError, last[size_t(p)].stats.worstError);
            EXPECT_EQ(best.stats.flips, last[kept].stats.flips);
            wentBack += kept < size_t(p);
        }
        // The fractal has budgets where the last mesh is not the best one.
        EXPECT_GT(wentBack, 5) << "seed " << seed;
    }
}

// With borderlines and a triangle budget, over a sequence of budgets: the max
// error never grows with BestMax (it does with Last on the same field), both
// triangulations; the same run twice gives the same mesh, and it is the Last
// run's at the kept size.
TEST(TinBudget, MaxErrorIsMonotoneOverBudgetsWithBorderlines) {
    const terrain::Heightfield field = fractal(65, 3);
    const tin::Constraints c = borderlines();
    for (auto triangulation : {tin::Triangulation::Delaunay, tin::Triangulation::DataDependent}) {
        double previousBest = std::numeric_limits<double>::infinity();
        double previousLast = std::numeric_limits<double>::infinity();
        int lastGrew = 0, wentBack = 0;
        int64_t snapSplits = 0, edgeSplits = 0;
        for (int64_t n = 40; n <= 700; n += 4) {
            const tin::TinDesc best{.maxTriangles = n, .triangulation = triangulation};
            const tin::TinResult r = tin::buildTin(field, c, best);
            ASSERT_EQ(r.stats.stop, tin::StopReason::Triangles);
            ASSERT_LE(r.mesh.triangles.size(), size_t(n));
            const double max = tin::measureError(r.mesh, field).maxError;
            EXPECT_LE(max, previousBest) << n << " triangles";
            previousBest = max;
            EXPECT_NEAR(r.stats.worstError, max, 1e-6 * std::max(1.0, max));
            EXPECT_EQ(r.stats.zoneConflicts, 0);
            snapSplits += r.stats.snapSplits;
            edgeSplits += r.stats.edgeSplits;

            const tin::TinResult l = tin::buildTin(field, c,
                                                   {.maxTriangles = n,
                                                    .budgetStop = tin::BudgetStop::Last,
                                                    .triangulation = triangulation});
            const double lastMax = tin::measureError(l.mesh, field).maxError;
            EXPECT_LE(max, lastMax) << n << " triangles";
            lastGrew += lastMax > previousLast;
            previousLast = lastMax;
            if (r.stats.inserted == l.stats.inserted) {
                expectSameMesh(r.mesh, l.mesh, "no going back: the Last run's mesh");
                continue;
            }
            ++wentBack;
            EXPECT_LT(r.stats.inserted, r.stats.budgetInserted);
            EXPECT_EQ(r.stats.budgetInserted, l.stats.inserted);
            expectSameMesh(r.mesh, tin::buildTin(field, c, best).mesh, "the same run again");
            // Stopping at the kept number of points instead gives the same mesh.
            const tin::TinResult atKept =
                tin::buildTin(field, c,
                              {.maxPoints = int64_t(r.mesh.vertices.size()),
                               .budgetStop = tin::BudgetStop::Last,
                               .triangulation = triangulation});
            expectSameMesh(r.mesh, atKept.mesh, "the Last run at the kept size");
        }
        EXPECT_GT(lastGrew, 0) << "the field never made the Last max error grow";
        EXPECT_GT(wentBack, 0);
        EXPECT_GT(snapSplits + edgeSplits, 0) << "no constrained edge was split";
    }
}

// An error target, or no limit, stops at a mesh whose max error is already the
// smallest so far: BestMax and Last give the same mesh.
TEST(TinBudget, ErrorTargetsAreUnchanged) {
    const terrain::Heightfield field = fractal(65, 4);
    for (double rel : {0.01, 0.05}) {
        const auto best =
            tin::buildTin(field, borderlines(), {.maxErrorRel = rel, .maxTriangles = 100000});
        const auto last = tin::buildTin(
            field, borderlines(),
            {.maxErrorRel = rel, .maxTriangles = 100000, .budgetStop = tin::BudgetStop::Last});
        EXPECT_EQ(best.stats.stop, tin::StopReason::Error);
        expectSameMesh(best.mesh, last.mesh, "error target");
        EXPECT_EQ(best.stats.budgetInserted, best.stats.inserted);
    }
    EXPECT_STREQ(tin::toString(tin::BudgetStop::BestMax), "best-max");
    EXPECT_STREQ(tin::toString(tin::BudgetStop::Last), "last");
}

}  // namespace
