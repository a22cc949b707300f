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

#include <atomic>
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

// --- chunks that can be run twice --------------------------------------------
// parallelChunks still waits for a chunk a helper has started. When that
// helper is preempted inside it (another process busy on its core) the call
// waits for up to a scheduler time slice (3-6 ms, measured on a 2-core machine
// with one core busy). parallelRescuedChunks does not wait: when the caller
// finds no chunk left to claim but one still running on a helper, it runs that
// chunk again itself (the rescue run, slot 1), and the first of the two runs
// to finish is the chunk's result. Bodies must therefore write a run's output
// only to storage of their (chunk, slot), and compute the same output in both
// slots.
//
// The call can return while a helper is still inside a body (its run lost, or
// it has not noticed): that helper keeps reading whatever the body reads until
// it finishes. So the body is copied into the pool and must capture nothing
// that dies with the call; the caller must leave the data a body reads (and
// the slot-0 outputs) alone until parallelHelpersIdle() is true, and wait with
// waitParallelHelpers() before freeing it. ChunkStop tells a run that its
// chunk is done: a body should check it every so often and return early (its
// output is discarded).

class ChunkStop {
  public:
    ChunkStop() = default;
    explicit ChunkStop(const std::atomic<uint8_t>* state) : state_(state) {}
    // True once the other run of this chunk has finished: this run's output will not be used.
    bool requested() const { return state_ && state_->load(std::memory_order_relaxed) >= 2; }
    // False when the run cannot be stopped (a serial call): no need to check.
    bool possible() const { return state_ != nullptr; }

  private:
    const std::atomic<uint8_t>* state_ = nullptr;
};

using RescuedBody = std::function<void(int chunk, int slot, const ChunkStop& stop)>;

// Runs body(c, slot, stop) for every chunk c in [0, chunkCount) on up to
// `threads` threads (0 = default), each chunk once in slot 0 and, when the
// caller rescues it, a second time in slot 1. winners[c] (chunkCount entries)
// receives the slot whose output is chunk c's result. Returns true when
// helpers took part (their slot-0 data may still be in use, see above), false
// when it ran serially (always slot 0): too few threads or chunks, a call from
// inside a body, another call running, or a helper of an earlier call not yet
// done. The first exception thrown by a body is rethrown.
bool parallelRescuedChunks(int chunkCount, const RescuedBody& body, int threads, uint8_t* winners);

// True when no helper thread is inside a body of any earlier call.
bool parallelHelpersIdle();
// True when parallelHelpersIdle() is or becomes true within `seconds` (polled,
// the calling thread yielding in between): a helper that has done its last
// unit of work leaves the call a moment after its caller has returned.
bool parallelHelpersIdleWithin(double seconds);
// Sleeps until parallelHelpersIdle().
void waitParallelHelpers();

// Chunks the callers of parallelRescuedChunks have run again (slot 1) since
// start-up: a diagnostic.
int64_t parallelRescueCount();

// Test hook: the first chunk each helper thread takes in every
// parallelRescuedChunks call sleeps `seconds` before its body runs, as if the
// helper were preempted there. 0 (the default) turns it off.
void setHelperStallForTesting(double seconds);

}  // namespace sierra
