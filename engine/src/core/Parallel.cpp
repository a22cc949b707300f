#include <sierra/core/Parallel.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace sierra {
namespace {

int initialThreadCount() {
    if (const char* env = std::getenv("SIERRA_THREADS")) {
        int n = std::atoi(env);
        if (n > 0) return n;
    }
    return std::max(1u, std::thread::hardware_concurrency());
}

std::atomic<int>& threadCount() {
    static std::atomic<int> count{initialThreadCount()};
    return count;
}

}  // namespace

int defaultThreadCount() { return threadCount(); }
void setDefaultThreadCount(int threads) { threadCount() = std::max(1, threads); }

void parallelChunks(int64_t begin, int64_t end, int chunkCount,
                    const std::function<void(int64_t, int64_t, int)>& body, int threads) {
    if (end <= begin || chunkCount <= 0) return;
    if (threads <= 0) threads = defaultThreadCount();
    int64_t total = end - begin;
    chunkCount = int(std::min<int64_t>(chunkCount, total));
    auto chunkRange = [&](int c) {
        int64_t lo = begin + total * c / chunkCount;
        int64_t hi = begin + total * (c + 1) / chunkCount;
        return std::pair{lo, hi};
    };
    threads = std::min(threads, chunkCount);
    if (threads <= 1) {
        for (int c = 0; c < chunkCount; ++c) {
            auto [lo, hi] = chunkRange(c);
            body(lo, hi, c);
        }
        return;
    }
    // OpenMP keeps its worker threads between calls, so a frame pays no thread
    // creation. Chunks are handed out one at a time (dynamic schedule); an
    // exception cannot leave a parallel region, so the first one is kept and
    // rethrown after it.
    std::exception_ptr failure;
    std::mutex failureMutex;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (int c = 0; c < chunkCount; ++c) {
        try {
            auto [lo, hi] = chunkRange(c);
            body(lo, hi, c);
        } catch (...) {
            std::lock_guard lock(failureMutex);
            if (!failure) failure = std::current_exception();
        }
    }
    if (failure) std::rethrow_exception(failure);
}

void parallelFor(int64_t begin, int64_t end, const std::function<void(int64_t)>& body,
                 int threads) {
    if (threads <= 0) threads = defaultThreadCount();
    parallelChunks(
        begin, end, threads * 4,
        [&](int64_t lo, int64_t hi, int) {
            for (int64_t i = lo; i < hi; ++i) body(i);
        },
        threads);
}

}  // namespace sierra
