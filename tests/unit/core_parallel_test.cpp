#include <sierra/core/Error.h>
#include <sierra/core/Parallel.h>
#include <sierra/core/Timer.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include <time.h>

using namespace sierra;

TEST(CoreParallel, EveryIndexOnceForAnyThreadCount) {
    for (int threads : {1, 2, 3, 8}) {
        std::vector<std::atomic<int>> hits(1003);
        parallelFor(
            0, 1003, [&](int64_t i) { ++hits[size_t(i)]; }, threads);
        for (size_t i = 0; i < hits.size(); ++i)
            ASSERT_EQ(hits[i].load(), 1) << "index " << i << ", " << threads << " threads";
    }
}

TEST(CoreParallel, ChunksAreContiguousAndIndependentOfThreads) {
    auto chunks = [](int threads) {
        std::vector<std::pair<int64_t, int64_t>> ranges(7);
        parallelChunks(
            10, 110, 7,
            [&](int64_t lo, int64_t hi, int c) {
                ranges[size_t(c)] = {lo, hi};
            },
            threads);
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
        EXPECT_THROW(parallelFor(
                         0, 100,
                         [](int64_t i) {
                             if (i == 57) throw Error("boom");
                         },
                         threads),
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
    for (const char* bad :
         {"0", "-3", "257", "1000000000", "99999999999999999999", "4x", "", " ", "two"})
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
    parallelFor(
        0, 5000, [&](int64_t i) { ++hits[size_t(i)]; }, 1000000000);
    for (size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i].load(), 1) << i;
    // (end - begin) * chunk index would overflow int64 here.
    int64_t covered = 0, previous = 0;
    bool contiguous = true;
    parallelChunks(
        0, int64_t(1) << 60, 1 << 20,
        [&](int64_t lo, int64_t hi, int) {
            contiguous = contiguous && lo == previous && hi > lo;
            previous = hi;
            covered += hi - lo;
        },
        1);
    EXPECT_TRUE(contiguous);
    EXPECT_EQ(covered, int64_t(1) << 60);
}

TEST(CoreParallel, ShortCallsStayOnTheCallingThread) {
    // Far less than kForkAfterSeconds of work (8 chunks that store one id each,
    // even under a sanitizer): no helper is woken.
    std::vector<std::thread::id> ids(8);
    parallelChunks(
        0, 8, 8, [&](int64_t, int64_t, int c) { ids[size_t(c)] = std::this_thread::get_id(); }, 2);
    for (const std::thread::id& id : ids) EXPECT_EQ(id, std::this_thread::get_id());
}

// CPU time of the calling thread, seconds (what parallelChunks measures its
// lone start in).
static double threadCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

TEST(CoreParallel, LongCallsShareTheWork) {
    // The caller starts alone and takes chunk 0 first; that chunk burns 5 times
    // kForkAfterSeconds of the caller's CPU time, so the call has proved long
    // and the helper is woken. Every later chunk the caller takes then waits
    // until a chunk has run on another thread: the call can finish only by
    // sharing the work, however the machine schedules its threads. The wait is
    // bounded (30 s, once) so that a pool that never forks fails instead of
    // hanging.
    constexpr int kChunks = 40;
    const std::thread::id caller = std::this_thread::get_id();
    std::mutex m;
    std::condition_variable helped;
    bool helperRan = false, callerStarted = false, timedOut = false;
    std::set<std::thread::id> ids;
    std::vector<int> runs(kChunks, 0);
    parallelChunks(
        0, kChunks, kChunks,
        [&](int64_t, int64_t, int c) {
            std::unique_lock lock(m);
            if (std::this_thread::get_id() != caller) {
                helperRan = true;
                helped.notify_all();
            } else if (!callerStarted) {
                callerStarted = true;
                lock.unlock();
                const double t0 = threadCpuSeconds();
                while (threadCpuSeconds() - t0 < 5 * kForkAfterSeconds) {
                }
                lock.lock();
            } else if (!timedOut && !helped.wait_for(lock, std::chrono::seconds(30),
                                                     [&] { return helperRan; })) {
                timedOut = true;
            }
            ids.insert(std::this_thread::get_id());
            ++runs[size_t(c)];
        },
        2);
    EXPECT_FALSE(timedOut) << "no helper ran a chunk within 30 s of being woken";
    EXPECT_EQ(ids.size(), 2u);
    for (int c = 0; c < kChunks; ++c) EXPECT_EQ(runs[size_t(c)], 1) << "chunk " << c;
}

TEST(CoreParallel, ExceptionsFromHelpersReachTheCaller) {
    std::atomic<int> ran{0};
    EXPECT_THROW(parallelChunks(
                     0, 40, 40,
                     [&](int64_t, int64_t, int c) {
                         const auto until =
                             std::chrono::steady_clock::now() + std::chrono::milliseconds(1);
                         while (std::chrono::steady_clock::now() < until) {
                         }
                         ++ran;
                         if (c == 20) throw Error("boom");
                     },
                     2),
                 Error);
    EXPECT_GE(ran.load(), 21);
    // The pool is usable again afterwards.
    std::vector<std::atomic<int>> hits(100);
    parallelFor(
        0, 100, [&](int64_t i) { ++hits[size_t(i)]; }, 2);
    for (auto& h : hits) ASSERT_EQ(h.load(), 1);
}

TEST(CoreParallel, NestedCallsRunSerially) {
    std::vector<std::atomic<int>> hits(64 * 64);
    parallelFor(
        0, 64,
        [&](int64_t i) {
            const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(100);
            while (std::chrono::steady_clock::now() < until) {
            }
            parallelFor(
                0, 64, [&](int64_t k) { ++hits[size_t(i * 64 + k)]; }, 2);
        },
        2);
    for (size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i].load(), 1) << i;
}

// Busy work of `ms` milliseconds of wall time.
static void spinFor(double ms) {
    const auto until =
        std::chrono::steady_clock::now() + std::chrono::duration<double, std::milli>(ms);
    while (std::chrono::steady_clock::now() < until) {
    }
}

TEST(CoreParallel, RescuedChunksNeverWaitForAStalledHelper) {
    // 60 chunks of 1 ms busy work; the helper's first chunk sleeps 1.5 s before
    // its body, as if preempted there. The caller runs that chunk again and
    // returns long before the sleeper wakes; each chunk's result is the output
    // of the slot it names. The outputs live on the heap, shared with the body:
    // the sleeper writes its slot after the call has returned.
    constexpr int kChunks = 60;
    struct Outputs {
        std::atomic<int> value[kChunks][2];
        std::atomic<int> runs[kChunks][2];
    };
    auto out = std::make_shared<Outputs>();
    for (int c = 0; c < kChunks; ++c)
        for (int s = 0; s < 2; ++s) out->value[c][s] = -1, out->runs[c][s] = 0;
    setHelperStallForTesting(1.5);
    const int64_t rescuesBefore = parallelRescueCount();
    std::vector<uint8_t> winners(kChunks, 9);
    const auto t0 = std::chrono::steady_clock::now();
    const bool pooled = parallelRescuedChunks(
        kChunks,
        [out](int c, int slot, const ChunkStop&) {
            spinFor(1.0);
            out->value[c][slot] = c * c + 1;
            ++out->runs[c][slot];
        },
        2, winners.data());
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    setHelperStallForTesting(0.0);
    EXPECT_TRUE(pooled);
    EXPECT_LT(seconds, 0.75) << "the call waited for the sleeping helper";
    EXPECT_EQ(parallelRescueCount() - rescuesBefore, 1) << "one chunk was held by the sleeper";
    int rescued = 0;
    for (int c = 0; c < kChunks; ++c) {
        ASSERT_LE(winners[size_t(c)], 1) << c;
        EXPECT_EQ(out->value[c][winners[size_t(c)]].load(), c * c + 1) << c;
        // the sleeper has not run its body yet
        EXPECT_EQ(out->runs[c][winners[size_t(c)]].load(), 1) << c;
        EXPECT_EQ(out->runs[c][1 - winners[size_t(c)]].load(), 0) << c;
        rescued += winners[size_t(c)];
    }
    EXPECT_EQ(rescued, 1);
    // The sleeper still holds its chunk: a call now runs serially, in slot 0.
    EXPECT_FALSE(parallelHelpersIdle());
    std::vector<uint8_t> serialWinners(8, 9);
    std::vector<int> serialRuns(8, 0);
    EXPECT_FALSE(parallelRescuedChunks(
        8, [&](int c, int slot, const ChunkStop&) { serialRuns[size_t(c)] += 1 + slot; }, 2,
        serialWinners.data()));
    for (int c = 0; c < 8; ++c) {
        EXPECT_EQ(serialRuns[size_t(c)], 1);
        EXPECT_EQ(serialWinners[size_t(c)], 0);
    }
    waitParallelHelpers();
    EXPECT_TRUE(parallelHelpersIdle());
    // The sleeper ran its chunk late, into its own slot; the rescue's output stands.
    for (int c = 0; c < kChunks; ++c) {
        EXPECT_EQ(out->runs[c][0].load(), 1) << c;
        EXPECT_EQ(out->value[c][winners[size_t(c)]].load(), c * c + 1) << c;
    }
}

TEST(CoreParallel, OnlyARunThatFinishedIsTheChunksResult) {
    // Without a stall the caller may rescue the helper's last chunk while the
    // helper runs it; the run that loses sees its ChunkStop and returns early.
    // The slot named for every chunk is one whose run went to the end.
    constexpr int kChunks = 40;
    struct Done {
        std::atomic<bool> finished[kChunks][2];
    };
    auto done = std::make_shared<Done>();
    for (auto& chunk : done->finished) chunk[0] = false, chunk[1] = false;
    std::vector<uint8_t> winners(kChunks, 9);
    parallelRescuedChunks(
        kChunks,
        [done](int c, int slot, const ChunkStop& stop) {
            for (int k = 0; k < 40; ++k) {
                if (stop.requested()) return;
                spinFor(0.05);
            }
            done->finished[c][slot] = true;
        },
        2, winners.data());
    for (int c = 0; c < kChunks; ++c) {
        ASSERT_LE(winners[size_t(c)], 1);
        EXPECT_TRUE(done->finished[c][winners[size_t(c)]].load()) << c;
    }
    waitParallelHelpers();
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
