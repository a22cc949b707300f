#include <sierra/core/Error.h>
#include <sierra/core/Parallel.h>
#include <sierra/core/Timer.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
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

TEST(CoreParallel, ThreadCountsAreBounded) {
    EXPECT_EQ(parseThreadCount("1"), 1);
    EXPECT_EQ(parseThreadCount("256"), kMaxThreads);
    for (const char* bad : {"0", "-3", "257", "1000000000", "99999999999999999999", "4x", "", " ", "two"})
        EXPECT_EQ(parseThreadCount(bad), 0) << bad;
    EXPECT_EQ(parseThreadCount(nullptr), 0);
    const int before = defaultThreadCount();
    setDefaultThreadCount(1000000000);
    EXPECT_EQ(defaultThreadCount(), kMaxThreads);
    setDefaultThreadCount(-5);
    EXPECT_EQ(defaultThreadCount(), 1);
    setDefaultThreadCount(before);
    // A huge request neither overflows the chunk arithmetic nor starts a
    // billion threads.
    std::vector<std::atomic<int>> hits(5000);
    parallelFor(0, 5000, [&](int64_t i) { ++hits[size_t(i)]; }, 1000000000);
    for (size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i].load(), 1) << i;
    // (end - begin) * chunk index would overflow int64 here.
    int64_t covered = 0, previous = 0;
    bool contiguous = true;
    parallelChunks(0, int64_t(1) << 60, 1 << 20, [&](int64_t lo, int64_t hi, int) {
        contiguous = contiguous && lo == previous && hi > lo;
        previous = hi;
        covered += hi - lo;
    }, 1);
    EXPECT_TRUE(contiguous);
    EXPECT_EQ(covered, int64_t(1) << 60);
}

TEST(CoreParallel, ShortCallsStayOnTheCallingThread) {
    // Far less than kForkAfterSeconds of work (8 chunks that store one id each,
    // even under a sanitizer): no helper is woken.
    std::vector<std::thread::id> ids(8);
    parallelChunks(0, 8, 8, [&](int64_t, int64_t, int c) { ids[size_t(c)] = std::this_thread::get_id(); }, 2);
    for (const std::thread::id& id : ids) EXPECT_EQ(id, std::this_thread::get_id());
}

TEST(CoreParallel, LongCallsShareTheWork) {
    // Chunks of 2 ms busy work: after the first, a helper is woken; it sleeps
    // in between, so even a busy machine schedules it before the 40 are done.
    std::mutex m;
    std::set<std::thread::id> ids;
    std::vector<int> order;
    parallelChunks(0, 40, 40, [&](int64_t, int64_t, int c) {
        const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(2);
        while (std::chrono::steady_clock::now() < until) {}
        std::lock_guard lock(m);
        ids.insert(std::this_thread::get_id());
        order.push_back(c);
    }, 2);
    EXPECT_EQ(order.size(), 40u);
    EXPECT_EQ(ids.size(), 2u);
}

TEST(CoreParallel, ExceptionsFromHelpersReachTheCaller) {
    std::atomic<int> ran{0};
    EXPECT_THROW(parallelChunks(0, 40, 40, [&](int64_t, int64_t, int c) {
        const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(1);
        while (std::chrono::steady_clock::now() < until) {}
        ++ran;
        if (c == 20) throw Error("boom");
    }, 2), Error);
    EXPECT_GE(ran.load(), 21);
    // The pool is usable again afterwards.
    std::vector<std::atomic<int>> hits(100);
    parallelFor(0, 100, [&](int64_t i) { ++hits[size_t(i)]; }, 2);
    for (auto& h : hits) ASSERT_EQ(h.load(), 1);
}

TEST(CoreParallel, NestedCallsRunSerially) {
    std::vector<std::atomic<int>> hits(64 * 64);
    parallelFor(0, 64, [&](int64_t i) {
        const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(100);
        while (std::chrono::steady_clock::now() < until) {}
        parallelFor(0, 64, [&](int64_t k) { ++hits[size_t(i * 64 + k)]; }, 2);
    }, 2);
    for (size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i].load(), 1) << i;
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
