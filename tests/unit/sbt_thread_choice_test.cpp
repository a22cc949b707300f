// The adaptive default thread count (sbt::ThreadChoice): what it decides from
// the wall times it is given, and that a refiner consults it only with the
// default count (threads 0), never with a count given explicitly.
#include <sierra/core/Parallel.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/DiamondSquare.h>

#include <gtest/gtest.h>

namespace {

namespace sbt = sierra::sbt;

// Feeds `choice` n refinements of `triangles` triangles, each taking
// serialSeconds on one thread or parallelSeconds on several; returns how many
// ran on one thread.
int run(sbt::ThreadChoice& choice, int n, double serialSeconds, double parallelSeconds,
        int64_t triangles = 1000) {
    int serial = 0;
    for (int k = 0; k < n; ++k) {
        const bool one = choice.serial();
        serial += one;
        choice.record(!one, one ? serialSeconds : parallelSeconds, triangles);
    }
    return serial;
}

// Refinements before ThreadChoice chooses: kLearn counted each way, after
// one uncounted each way.
constexpr int kLearning = 2 * (sbt::ThreadChoice::kLearn + 1);

TEST(SbtThreadChoice, TriesBothWaysThenKeepsTheFasterOne) {
    sbt::ThreadChoice choice;
    // The two ways alternate, several threads first, whatever the times,
    // until each has kLearn counted refinements (the first of each is not
    // counted).
    for (int k = 0; k < kLearning; ++k) {
        const bool one = choice.serial();
        EXPECT_EQ(one, k % 2 == 1) << "refinement " << k;
        // a first refinement's one-off costs: 9 s in parallel, 7 s on one thread
        choice.record(!one, k < 2 ? 9.0 - 2.0 * k : one ? 3.0 : 2.0, 1000);
    }
    EXPECT_EQ(choice.samples[0], sbt::ThreadChoice::kLearn + 1);
    EXPECT_EQ(choice.samples[1], sbt::ThreadChoice::kLearn + 1);
    // Parallel is faster (2 against 3): kept, one thread probed now and then.
    const int serial = run(choice, 96, 3.0, 2.0);
    EXPECT_GE(serial, 1);
    EXPECT_LE(serial, 96 / 32 + 1);
}

TEST(SbtThreadChoice, OneSlowRefinementWhileLearningDoesNotDecide) {
    // The first counted parallel refinement is slowed 3 times (a preempted
    // helper); the others take 0.6 of one thread's time. Decided from that
    // one refinement, one thread would be kept for kProbeFar (32)
    // refinements; from kLearn each way, the median ignores it.
    sbt::ThreadChoice choice;
    int parallelSeen = 0;
    for (int k = 0; k < kLearning; ++k) {
        const bool one = choice.serial();
        const bool slowed = !one && parallelSeen++ == 1;
        choice.record(!one, one ? 1.0 : slowed ? 1.8 : 0.6, 1000);
    }
    EXPECT_LE(run(choice, 24, 1.0, 0.6), 24 / 32 + 1);
}

TEST(SbtThreadChoice, FollowsTheLoadWhenItChanges) {
    sbt::ThreadChoice choice;
    run(choice, kLearning, 1.0, 1.0);
    // The other core gets busy: two threads now lose by 30%.
    run(choice, 64, 1.0, 1.3);
    EXPECT_GE(run(choice, 64, 1.0, 1.3), 64 - 64 / 32 - 1);
    // It frees up: two threads win by 40%. Within a few probes the choice
    // turns, and then stays.
    run(choice, 96, 1.0, 0.6);
    EXPECT_LE(run(choice, 64, 1.0, 0.6), 64 / 32 + 1);
}

TEST(SbtThreadChoice, ANearTieGoesToOneThread) {
    // Two threads 5% faster per triangle: within the margin, one thread is
    // kept (its times scatter less), the other way probed now and then.
    sbt::ThreadChoice near;
    run(near, kLearning, 1.0, 0.95);
    EXPECT_GE(run(near, 64, 1.0, 0.95), 64 - 64 / 8 - 1);
    // 15% faster: past the margin, two threads are kept.
    sbt::ThreadChoice past;
    run(past, kLearning, 1.0, 0.85);
    EXPECT_LE(run(past, 64, 1.0, 0.85), 64 / 8 + 1);
}

TEST(SbtThreadChoice, OneSlowRefinementDoesNotTurnIt) {
    sbt::ThreadChoice choice;
    run(choice, 64, 1.0, 0.6);
    // A page fault storm or a preempted helper: one parallel refinement 100
    // times slower. The median of the last five ignores it.
    ASSERT_FALSE(choice.serial());
    choice.record(true, 60.0, 1000);
    EXPECT_LE(run(choice, 32, 1.0, 0.6), 1);
}

TEST(SbtThreadChoice, ComparesTimePerTriangle) {
    sbt::ThreadChoice choice;
    // The parallel refinements are larger meshes: 2 s for 2000 triangles is
    // faster per triangle than 1.5 s for 1000.
    for (int k = 0; k < kLearning; ++k) {
        const bool one = choice.serial();
        choice.record(!one, one ? 1.5 : 2.0, one ? 1000 : 2000);
    }
    int serial = 0;
    for (int k = 0; k < 64; ++k) {
        const bool one = choice.serial();
        serial += one;
        choice.record(!one, one ? 1.5 : 2.0, one ? 1000 : 2000);
    }
    EXPECT_LE(serial, 64 / 32 + 1);
}

TEST(SbtThreadChoice, OnlyTheDefaultThreadCountAdapts) {
    const int saved = sierra::defaultThreadCount();
    sierra::setDefaultThreadCount(2);
    sierra::terrain::Heightfield f =
        sierra::terrain::generateDiamondSquare({.size = 513, .seed = 2, .hurst = 0.7f});
    const sbt::VertexErrors ve = sbt::computeVertexErrors(f);
    sbt::Refiner adaptive(f, ve, {.threads = 0}), explicitTwo(f, ve, {.threads = 2});
    sbt::StripMesh a, b;
    int adaptiveOnOne = 0, explicitOnTwo = 0;
    for (int k = 0; k < 6; ++k) {
        adaptive.refineFixed(-1.0f,
                             a);  // the full grid: 524 288 triangles, above kParallelTriangles
        explicitTwo.refineFixed(-1.0f, b);
        EXPECT_EQ(a.indices, b.indices);
        // StripMesh::threads says how each ran: 1, or the 2 threads given
        EXPECT_TRUE(a.threads == 1 || a.threads == 2) << a.threads;
        EXPECT_TRUE(b.threads == 1 || b.threads == 2) << b.threads;
        adaptiveOnOne += a.threads == 1;
        explicitOnTwo += b.threads == 2;
    }
    const sbt::ThreadChoice& learned = adaptive.threadChoice(false);
    EXPECT_EQ(learned.samples[0] + learned.samples[1], 6);
    EXPECT_GE(learned.samples[0], 2);  // both ways tried
    EXPECT_GE(learned.samples[1], 2);
    // What the choice recorded as one thread is what the meshes say (a
    // parallel refinement whose helpers took no part counts as one thread).
    EXPECT_EQ(adaptiveOnOne, learned.samples[0]);
    EXPECT_GE(explicitOnTwo, 1);  // helpers took part in at least one of 6 ~2 ms refinements
    EXPECT_EQ(
        explicitTwo.threadChoice(false).samples[0] + explicitTwo.threadChoice(false).samples[1], 0);
    EXPECT_EQ(adaptive.threadChoice(true).samples[1], 0);  // view mode not touched
    sierra::setDefaultThreadCount(saved);
}

}  // namespace
