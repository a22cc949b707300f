#pragma once
// parallelFor over an index range on OpenMP's thread pool. The range is cut into
// contiguous chunks, one per thread, so per-chunk results joined in chunk order
// do not depend on scheduling.

#include <cstdint>
#include <functional>

namespace sierra {

// Threads used when a call passes threads = 0. Defaults to the hardware
// concurrency; SIERRA_THREADS=<n> overrides it at start-up.
int defaultThreadCount();
void setDefaultThreadCount(int threads);

// Calls body(begin, end, chunkIndex) for chunkCount contiguous chunks of
// [begin, end), running up to `threads` of them at once (0 = default).
void parallelChunks(int64_t begin, int64_t end, int chunkCount,
                    const std::function<void(int64_t, int64_t, int)>& body, int threads = 0);

// Calls body(i) for every i in [begin, end) on up to `threads` threads.
void parallelFor(int64_t begin, int64_t end, const std::function<void(int64_t)>& body,
                 int threads = 0);

}  // namespace sierra
