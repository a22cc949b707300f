#include <sierra/core/Error.h>
#include <sierra/core/Parallel.h>
#include <sierra/core/Timer.h>

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <stdexcept>
#include <vector>

using namespace sierra;

TEST(CoreParallel, EveryIndexOnceForAnyThreadCount) {
    for (int threads : {1, 2, 3, 8}) {
        std::vector<std::atomic<int>> hits(1003);
        parallelFor(0, 1003, [&](int64_t i) { ++hits[size_t(i)]; }, threads);
        for (size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i].load(), 1) << "index " << i << ", " << threads << " threads";
    }
}

TEST(CoreParallel, ChunksAreContiguousAndIndependentOfThreads) {
    auto chunks = [](int threads) {
        std::vector<std::pair<int64_t, int64_t>> ranges(7);
        parallelChunks(10, 110, 7, [&](int64_t lo, int64_t hi, int c) { ranges[size_t(c)] = {lo, hi}; }, threads);
        return ranges;
    };
    auto one = chunks(1);
    EXPECT_EQ(one.front().first, 10);
    EXPECT_EQ(one.back().second, 110);
    for (size_t c = 1; c < one.size(); ++c) EXPECT_EQ(one[c].first, one[c - 1].second);
    EXPECT_EQ(chunks(2), one);
    EXPECT_EQ(chunks(4), one);
}

TEST(CoreParallel, ExceptionsReachTheCaller) {
    for (int threads : {1, 2}) {
        EXPECT_THROW(parallelFor(0, 100, [](int64_t i) {
                         if (i == 57) throw Error("boom");
                     }, threads),
                     Error);
    }
}

TEST(CoreParallel, EmptyRangeCallsNothing) {
    int calls = 0;
    parallelChunks(5, 5, 4, [&](int64_t, int64_t, int) { ++calls; });
    EXPECT_EQ(calls, 0);
}

TEST(CoreTimer, QuantilesInterpolate) {
    std::vector<double> v{4, 1, 3, 2, 5};
    EXPECT_DOUBLE_EQ(median(v), 3.0);
    EXPECT_DOUBLE_EQ(quantile(v, 0.0), 1.0);
    EXPECT_DOUBLE_EQ(quantile(v, 1.0), 5.0);
    EXPECT_DOUBLE_EQ(quantile(v, 0.25), 2.0);
    EXPECT_DOUBLE_EQ(quantile({1, 2}, 0.5), 1.5);
    EXPECT_DOUBLE_EQ(quantile({}, 0.5), 0.0);
}

TEST(CoreError, CheckThrowsWithTheMessage) {
    try {
        SIERRA_CHECK(1 + 1 == 3, "arithmetic is ", "broken");
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "arithmetic is broken");
    }
    EXPECT_NO_THROW(SIERRA_CHECK(true, "never"));
}
