#pragma once
// parallelChunks / parallelFor over an index range on a small pool of worker
// threads. The range is cut into contiguous chunks, so per-chunk results joined
// in chunk order do not depend on scheduling or on the thread count.
//
// Threads earn their keep (measured on a 2-core machine whose other core is
// busy, see docs/refinement.md):
// - the calling thread works too, and starts alone: helpers are woken only
//   once it has spent kForkAfterSeconds on the chunks, so a short call never
//   forks and costs what the serial loop costs;
// - a helper takes chunks one at a time from a shared counter, and the caller
//   waits only for chunks a helper has actually started. A helper that the
//   operating system has not scheduled yet (the other core busy) delays
//   nothing: the caller takes its chunks. This is what a fork-join barrier
//   (OpenMP's parallel for) cannot do: it waits for every thread to arrive,
//   spinning meanwhile, which made 2 threads up to 10x slower than 1 on a busy
//   machine;
// - nobody spins: idle helpers and a waiting caller sleep in the kernel
//   (std::atomic wait), so a busy core is not taken from the other process.

#include <cstdint>
#include <functional>

namespace sierra {

// Thread counts are 1..kMaxThreads (like the apps' --threads).
inline constexpr int kMaxThreads = 256;

// CPU time the caller works alone before it wakes helpers: 0.2 ms, about 40 times
// the cost of waking one, so a call that cannot gain that much stays serial.
inline constexpr double kForkAfterSeconds = 2e-4;

// Threads used when a call passes threads = 0. Defaults to the hardware
// concurrency; SIERRA_THREADS=<n> (1..256) overrides it at start-up (any other
// value is ignored with a warning on the log).
int defaultThreadCount();
// The thread count written in `text` (decimal, nothing else) when it is in
// 1..kMaxThreads, else 0.
int parseThreadCount(const char* text);
// Clamped to 1..kMaxThreads.
void setDefaultThreadCount(int threads);

// Calls body(begin, end, chunkIndex) for chunkCount contiguous chunks of
// [begin, end), running up to `threads` of them at once (0 = default, at most
// kMaxThreads). Chunks are taken in index order. The first exception thrown by
// a body is rethrown once every started chunk has finished. A call made from
// inside a body, or while another thread's call is running, runs serially.
void parallelChunks(int64_t begin, int64_t end, int chunkCount,
                    const std::function<void(int64_t, int64_t, int)>& body, int threads = 0);

// Calls body(i) for every i in [begin, end) on up to `threads` threads.
void parallelFor(int64_t begin, int64_t end, const std::function<void(int64_t)>& body,
                 int threads = 0);

}  // namespace sierra
