#include <sierra/core/Parallel.h>

#include <sierra/core/Log.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include <time.h>

namespace sierra {
namespace {

int initialThreadCount() {
    const int hardware =
        int(std::clamp(std::thread::hardware_concurrency(), 1u, unsigned(kMaxThreads)));
    const char* env = std::getenv("SIERRA_THREADS");
    if (!env) return hardware;
    const int n = parseThreadCount(env);
    if (n == 0) {
        log::warn("SIERRA_THREADS=", env, " is not a thread count in 1..", kMaxThreads, "; using ",
                  hardware, " (the hardware concurrency)");
        return hardware;
    }
    return n;
}

// CPU time of the calling thread: the caller's lone start is measured in work
// done, so a caller that the system preempts does not count the wait as work.
double threadSeconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

std::atomic<int>& threadCount() {
    static std::atomic<int> count{initialThreadCount()};
    return count;
}

// Chunk c of `count` equal parts of [begin, begin + total): the first
// total % count chunks one element longer. No product of two large numbers,
// so no overflow for any count.
std::pair<int64_t, int64_t> chunkRange(int64_t begin, int64_t total, int64_t count, int64_t c) {
    const int64_t q = total / count, r = total % count;
    const int64_t lo = begin + q * c + std::min(c, r);
    return {lo, lo + q + (c < r ? 1 : 0)};
}

// One parallelChunks call (on the caller's stack), or one parallelRescuedChunks
// call (the pool's own rescueJob_, which outlives the call). Chunks are claimed
// in units of `unit` consecutive chunks so the unit count fits the pool's
// 16-bit claim counter; a rescued call has one chunk per unit.
struct Job {
    const std::function<void(int64_t, int64_t, int)>* body = nullptr;
    int64_t begin = 0, total = 0;
    int chunkCount = 0;
    int unit = 1;
    std::atomic<bool> failed{false};
    std::exception_ptr failure;
    std::mutex failureMutex;

    // Rescued calls: the body (a copy: helpers may run it after the call has
    // returned) and per chunk kPending, kStarted (slot 0 running), kDoneFirst or
    // kDoneRescue (the slot whose output counts).
    bool rescued = false;
    RescuedBody rescuedBody;
    std::unique_ptr<std::atomic<uint8_t>[]> states;
    int stateCapacity = 0;

    void fail() {
        std::lock_guard lock(failureMutex);
        if (!failure) failure = std::current_exception();
        failed = true;
    }

    void runUnit(int u) {
        const int c0 = u * unit, c1 = std::min(chunkCount, c0 + unit);
        for (int c = c0; c < c1; ++c) {
            if (failed.load(std::memory_order_relaxed)) return;  // the call fails anyway
            try {
                auto [lo, hi] = chunkRange(begin, total, chunkCount, c);
                (*body)(lo, hi, c);
            } catch (...) {
                fail();
            }
        }
    }

    // Slot 0 of chunk c, unless the caller has taken it over or finished it.
    void runFirst(int c, double stallSeconds) {
        uint8_t expected = kPending;
        if (!states[c].compare_exchange_strong(expected, kStarted, std::memory_order_acq_rel))
            return;
        if (stallSeconds > 0)
            std::this_thread::sleep_for(std::chrono::duration<double>(stallSeconds));
        runSlot(c, 0);
    }
    // The first run of chunk c to finish publishes its slot.
    void runSlot(int c, int slot) {
        try {
            rescuedBody(c, slot, ChunkStop(&states[c]));
        } catch (...) {
            fail();
        }
        uint8_t expected = kStarted;
        states[c].compare_exchange_strong(expected, uint8_t(kDoneFirst + slot),
                                          std::memory_order_acq_rel);
    }

    static constexpr uint8_t kPending = 0, kStarted = 1, kDoneFirst = 2, kDoneRescue = 3;
};

// The helper stall of setHelperStallForTesting, seconds.
std::atomic<double> gHelperStall{0.0};
std::atomic<int64_t> gRescues{0};  // parallelRescueCount

constexpr int kMaxUnits = 0xffff;

// True on the pool's threads and on a caller inside a parallel call: a nested
// call runs serially.
thread_local bool tInsideParallel = false;

// Helper threads and the claim counter. One parallel call at a time (others
// run serially in their caller).
class Pool {
  public:
    static Pool& instance() {
        static Pool pool;
        return pool;
    }

    ~Pool() {
        stop_ = true;
        wake_.fetch_add(1, std::memory_order_release);
        wake_.notify_all();
        for (std::thread& t : workers_) t.join();
    }

    // Makes `job` the pool's call (its `units` open for claiming, `helpers` of the
    // pool's threads allowed in); the caller holds callMutex_.
    void publish(Job& job, int units, int helpers) {
        tInsideParallel = true;
        job_.store(&job, std::memory_order_relaxed);
        helpers_.store(helpers, std::memory_order_relaxed);
        generation_ = (generation_ + 1) & 0xffffffffu;
        state_.store(generation_ << 32 | uint64_t(units) << 16, std::memory_order_release);
    }

    // False when another call holds the pool (the caller then runs serially).
    bool run(Job& job, int units, int helpers) {
        std::unique_lock lock(callMutex_, std::try_to_lock);
        if (!lock.owns_lock()) return false;
        done_.store(0, std::memory_order_relaxed);
        publish(job, units, helpers);

        // Work alone first; wake the helpers once this call has proved long.
        const double t0 = threadSeconds();
        bool woken = false;
        int unit;
        while ((unit = claim(nullptr)) >= 0) {
            job.runUnit(unit);
            done_.fetch_add(1, std::memory_order_acq_rel);
            if (!woken && threadSeconds() - t0 > kForkAfterSeconds) {
                woken = true;
                wakeHelpers(helpers);
            }
        }
        // Wait (asleep) only for the units helpers have started.
        for (int d; (d = done_.load(std::memory_order_acquire)) != units;)
            done_.wait(d, std::memory_order_acquire);
        tInsideParallel = false;
        return true;
    }

    // parallelRescuedChunks on the pool (see Parallel.h); false: run serially.
    bool runRescued(int chunkCount, const RescuedBody& body, int helpers, uint8_t* winners) {
        std::unique_lock lock(callMutex_, std::try_to_lock);
        // Helpers still inside an earlier call's body: the pool's job is theirs
        // until they leave, and they are busy anyway.
        if (!lock.owns_lock() || inFlight_.load(std::memory_order_acquire) != 0) return false;
        Job& job = rescueJob_;
        if (job.stateCapacity < chunkCount) {
            job.states = std::make_unique<std::atomic<uint8_t>[]>(size_t(chunkCount));
            job.stateCapacity = chunkCount;
        }
        for (int c = 0; c < chunkCount; ++c)
            job.states[c].store(Job::kPending, std::memory_order_relaxed);
        job.rescued = true;
        job.rescuedBody = body;
        job.chunkCount = chunkCount;
        job.failed = false;
        job.failure = nullptr;
        publish(job, chunkCount, helpers);

        const double t0 = threadSeconds();
        bool woken = false;
        for (int c; (c = claim(nullptr)) >= 0;) {
            job.runFirst(c, 0.0);
            if (!woken && threadSeconds() - t0 > kForkAfterSeconds) {
                woken = true;
                wakeHelpers(helpers);
            }
        }
        // Nothing left to claim. A chunk a helper claimed but has not started is
        // taken over; one it is running is run again here, and whichever run
        // finishes first counts. The caller never sleeps on a helper.
        for (int c = 0; c < chunkCount; ++c) {
            job.runFirst(c, 0.0);
            if (job.states[c].load(std::memory_order_acquire) == Job::kStarted) {
                gRescues.fetch_add(1, std::memory_order_relaxed);
                job.runSlot(c, 1);
            }
            winners[c] = job.states[c].load(std::memory_order_acquire) == Job::kDoneRescue ? 1 : 0;
        }
        tInsideParallel = false;
        if (job.failed.load(std::memory_order_acquire)) {
            std::lock_guard failureLock(job.failureMutex);
            if (job.failure) std::rethrow_exception(job.failure);
        }
        return true;
    }

    bool idle() const { return inFlight_.load(std::memory_order_acquire) == 0; }
    void waitIdle() {
        for (int n; (n = inFlight_.load(std::memory_order_acquire)) != 0;)
            inFlight_.wait(n, std::memory_order_acquire);
    }

  private:
    Pool() = default;

    // The next unit of the current call (its job through `job`), or -1 when all
    // are taken. state_: generation (32 bits) | unit count (16) | next unit (16).
    int claim(Job** job) {
        uint64_t s = state_.load(std::memory_order_acquire);
        for (;;) {
            const int count = int((s >> 16) & 0xffff), next = int(s & 0xffff);
            if (next >= count) return -1;
            // Read before the exchange: if it succeeds the state has not moved, so
            // this call is still running and the pointer is its job.
            Job* j = job_.load(std::memory_order_acquire);
            if (state_.compare_exchange_weak(s, s + 1, std::memory_order_acq_rel,
                                             std::memory_order_acquire)) {
                if (job) *job = j;
                return next;
            }
        }
    }

    void wakeHelpers(int helpers) {
        const uint32_t seen = wake_.load(std::memory_order_acquire);
        try {
            while (int(workers_.size()) < helpers)
                workers_.emplace_back(
                    [this, index = int(workers_.size()), seen] { loop(index, seen); });
        } catch (const std::system_error&) {
            // no more threads to be had: the ones there (or the caller alone) do the work
        }
        wake_.fetch_add(1, std::memory_order_release);
        wake_.notify_all();
    }

    void loop(int index, uint32_t seen) {
        tInsideParallel = true;
        for (;;) {
            wake_.wait(seen, std::memory_order_acquire);
            seen = wake_.load(std::memory_order_acquire);
            if (stop_) return;
            if (index >= helpers_.load(std::memory_order_relaxed)) continue;
            // Counted from before the claim: a helper that has claimed a chunk of
            // a rescued call may start it after that call has returned.
            inFlight_.fetch_add(1, std::memory_order_acq_rel);
            Job* job = nullptr;
            double stall = gHelperStall.load(std::memory_order_relaxed);
            for (int unit; (unit = claim(&job)) >= 0;) {
                if (job->rescued) {
                    job->runFirst(unit, stall);
                    stall = 0.0;
                    continue;
                }
                job->runUnit(unit);
                const int count = int((state_.load(std::memory_order_relaxed) >> 16) & 0xffff);
                if (done_.fetch_add(1, std::memory_order_acq_rel) + 1 == count) done_.notify_all();
            }
            if (inFlight_.fetch_sub(1, std::memory_order_acq_rel) == 1) inFlight_.notify_all();
        }
    }

    std::mutex callMutex_;
    std::vector<std::thread> workers_;  // grown under callMutex_
    uint64_t generation_ = 0;           // under callMutex_
    std::atomic<uint64_t> state_{0};
    std::atomic<Job*> job_{nullptr};
    std::atomic<int> helpers_{0};
    std::atomic<int> done_{0};      // units finished in this call
    std::atomic<int> inFlight_{0};  // helpers between waking for a call and running out of chunks
    Job rescueJob_;                 // the job of parallelRescuedChunks
    std::atomic<uint32_t> wake_{0};
    std::atomic<bool> stop_{false};
};

}  // namespace

int parseThreadCount(const char* text) {
    if (!text) return 0;
    errno = 0;
    char* end = nullptr;
    const long n = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno == ERANGE || n < 1 || n > kMaxThreads) return 0;
    return int(n);
}

int defaultThreadCount() {
    return threadCount();
}
void setDefaultThreadCount(int threads) {
    threadCount() = std::clamp(threads, 1, kMaxThreads);
}

void parallelChunks(int64_t begin, int64_t end, int chunkCount,
                    const std::function<void(int64_t, int64_t, int)>& body, int threads) {
    if (end <= begin || chunkCount <= 0) return;
    if (threads <= 0) threads = defaultThreadCount();
    threads = std::min(threads, kMaxThreads);
    const int64_t total = end - begin;
    chunkCount = int(std::min<int64_t>(chunkCount, total));
    const int unit = (chunkCount + kMaxUnits - 1) / kMaxUnits;
    const int units = (chunkCount + unit - 1) / unit;
    threads = std::min(threads, units);
    if (threads > 1 && !tInsideParallel) {
        Job job{&body, begin, total, chunkCount, unit};
        if (Pool::instance().run(job, units, threads - 1)) {
            if (job.failure) std::rethrow_exception(job.failure);
            return;
        }
    }
    for (int c = 0; c < chunkCount; ++c) {
        auto [lo, hi] = chunkRange(begin, total, chunkCount, c);
        body(lo, hi, c);
    }
}

bool parallelRescuedChunks(int chunkCount, const RescuedBody& body, int threads, uint8_t* winners) {
    if (chunkCount <= 0) return false;
    if (threads <= 0) threads = defaultThreadCount();
    threads = std::min({threads, kMaxThreads, chunkCount});
    if (threads > 1 && chunkCount <= kMaxUnits && !tInsideParallel &&
        Pool::instance().runRescued(chunkCount, body, threads - 1, winners))
        return true;
    for (int c = 0; c < chunkCount; ++c) {
        body(c, 0, ChunkStop());
        winners[c] = 0;
    }
    return false;
}

int64_t parallelRescueCount() {
    return gRescues.load(std::memory_order_relaxed);
}
bool parallelHelpersIdle() {
    return Pool::instance().idle();
}
bool parallelHelpersIdleWithin(double seconds) {
    const Pool& pool = Pool::instance();
    if (pool.idle()) return true;
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (!pool.idle()) {
        if (std::chrono::steady_clock::now() >= until) return false;
        std::this_thread::yield();
    }
    return true;
}
void waitParallelHelpers() {
    Pool::instance().waitIdle();
}
void setHelperStallForTesting(double seconds) {
    gHelperStall = std::max(0.0, seconds);
}

void parallelFor(int64_t begin, int64_t end, const std::function<void(int64_t)>& body,
                 int threads) {
    if (threads <= 0) threads = defaultThreadCount();
    threads = std::min(threads, kMaxThreads);
    // 16 chunks per thread: the caller's lone start (kForkAfterSeconds) and the
    // last chunk each cost at most a sixteenth of a thread's share.
    parallelChunks(
        begin, end, threads * 16,
        [&](int64_t lo, int64_t hi, int) {
            for (int64_t i = lo; i < hi; ++i) body(i);
        },
        threads);
}

}  // namespace sierra
