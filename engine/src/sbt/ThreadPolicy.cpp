// The thread policy of the refiner (Refiner.h): ThreadChoice, the adaptive
// default's choice between one thread and several from the measured time per
// triangle of the recent refinements each way, and Refiner::chooseThreads,
// which applies it with the rules that keep small refinements and those that
// meet a busy helper on one thread. Refiner.cpp runs the chunks on the
// threads chosen.
#include <sierra/sbt/Refiner.h>

#include <sierra/core/Parallel.h>

#include <algorithm>
#include <cstdint>

namespace sierra::sbt {

// Probe the way not taken every kProbeClose refinements while the two are
// within 20%, every kProbeFar refinements otherwise: a probe costs a
// refinement at the slower speed, and a wide gap rarely closes at once.
constexpr int kProbeClose = 8, kProbeFar = 32;
// Several threads are taken only when their median is faster per triangle by
// this factor: near a tie the parallel times scatter more (a preempted helper
// costs the caller its chunk, BM_RefineFixed/1025/-1/2 with one core busy had
// a coefficient of variation of 8% against 0.7% on one thread), so a tie
// called either way by noise made the default 2-7% slower than one thread.
constexpr double kParallelMargin = 1.1;

double ThreadChoice::estimate(int way) const {
    const int n = int(std::min<int64_t>(samples[way] - 1, kKept));
    double kept[kKept];
    for (int k = 0; k < n; ++k) {  // insertion sort of at most kKept values
        int at = k;
        for (; at > 0 && kept[at - 1] > recent[way][k]; --at) kept[at] = kept[at - 1];
        kept[at] = recent[way][k];
    }
    return n % 2 ? kept[n / 2] : 0.5 * (kept[n / 2 - 1] + kept[n / 2]);
}

bool ThreadChoice::serial() {
    if (samples[0] <= kLearn || samples[1] <= kLearn) return samples[0] < samples[1];
    const double one = estimate(0), several = estimate(1);
    const bool serialChosen = one <= several * kParallelMargin;
    const double gap = std::max(one, several) / std::max(1e-30, std::min(one, several));
    if (++sinceProbe >= (gap < 1.2 ? kProbeClose : kProbeFar)) {
        sinceProbe = 0;
        return !serialChosen;
    }
    return serialChosen;
}

void ThreadChoice::record(bool parallel, double seconds, int64_t triangles) {
    const int way = parallel ? 1 : 0;
    // The first refinement each way is not counted: it grows buffers, starts
    // threads and faults pages in.
    const int64_t counted = samples[way]++;
    if (counted == 0) return;
    recent[way][(counted - 1) % kKept] = seconds / double(std::max<int64_t>(triangles, 1));
}

// The thread count of the next refinement in view (true) or fixed mode;
// *adaptive: the adaptive default chose it (ThreadChoice records the time).
int Refiner::chooseThreads(bool view, bool helperBusy, bool* adaptive) {
    // Threads earn their keep: a refinement that made fewer than
    // kParallelTriangles triangles last time in this mode runs serially. One
    // thread does that many in 1.3-2.6 ms (50-100 M triangles/s); a helper
    // could save at most half of it but, on a busy machine, can cost a whole
    // scheduler time slice (3-6 ms) when it is preempted inside a chunk.
    int threads = threads_ > 0 ? threads_ : defaultThreadCount();
    const int64_t lastTriangles = view ? lastViewTriangles_ : lastFixedTriangles_;
    if (lastTriangles >= 0 && lastTriangles < kParallelTriangles) threads = 1;
    ThreadChoice& choice = view ? viewThreads_ : fixedThreads_;
    *adaptive = threads_ <= 0 && threads > 1;
    if (*adaptive && choice.serial()) threads = 1;
    // A helper of the last refinement is still inside a chunk (preempted, or
    // finishing a chunk the caller ran again): this refinement runs on one
    // thread, through the other frame's one small buffer. The pool would most
    // likely run it serially anyway (it does while a helper is busy), but on
    // that frame's chunk buffers, which may never have been grown: a full
    // 2049^2 grid's 56 MB, faulted in, took 155 ms where one thread takes 30.
    // So the other frame never holds chunk strips.
    if (helperBusy) threads = 1;
    return threads;
}

}  // namespace sierra::sbt
