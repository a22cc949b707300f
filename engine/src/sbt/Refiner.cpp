// The refiner (Refiner.h): a refinement from its request to its strip mesh.
//
//   refineFixed / refineView / refineViewReference   check the request
//   run                 one refinement, in these steps:
//     takeFrame         the working data no helper of the last one still reads
//     setUpWalker       the walker's configuration for this mode and view
//     setUpViewKeys     ... and for the keyed walk (followReachFactor: which
//                       lambda / tau the reach keys are made for)
//     recordTop         the serial top of the tree, cut into chunks
//     chooseThreads     one thread or several (ThreadPolicy.cpp)
//     refineSerially    one thread: the chunks in turn, joined in place
//     runChunksPooled   several: the chunks on the pool, then
//     joinPooledChunks  joined by copies into the output
//
// The walks a chunk runs are in the headers beside this file (Walker.h maps
// them), the strip writer and the join in StripWriter.h, the keys' building
// in RefinerKeys.cpp, the thread policy in ThreadPolicy.cpp, the view
// helpers in View.cpp and the output checks in MeshChecks.cpp.
#include <sierra/sbt/Refiner.h>

#include "sbt/ExactWalk.h"
#include "sbt/FastWalk.h"
#include "sbt/KeyedWalk.h"
#include "sbt/Rounding.h"
#include "sbt/SplitKeyWalk.h"
#include "sbt/StripWriter.h"
#include "sbt/Walker.h"

#include <sierra/core/Error.h>
#include <sierra/core/Parallel.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

namespace sierra::sbt {

namespace {

// How long a refinement waits for a helper still leaving the last one.
constexpr double kHelperSettleSeconds = 200e-6;
// Refinements in a row with one lambda / tau other than the view keys' before
// the reaches are made again for it (Refiner::followReachFactor).
constexpr int kReachRebuildAfter = 4;

}  // namespace

// One refinement's working data (see Refiner::frames_).
struct Refiner::Frame {
    std::vector<Op> ops;
    std::vector<size_t> cuts;          // chunk c runs ops[cuts[c], cuts[c + 1])
    std::vector<Chunk> chunks[2];      // per slot of parallelRescuedChunks: first runs, rescues
    std::vector<int> order;            // chunks in the order they are handed out
    std::vector<uint8_t> winners;      // per place in `order`: the slot whose strip counts
    std::vector<uint8_t> slotOf;       // per chunk: the slot whose strip counts
    std::vector<float> eyeTerms;       // view keys: squared eye distances along x, then z
    std::vector<int64_t> chunkLeaves;  // per chunk: the triangles of the run that counts
    Chunk serialChunk;                 // the one buffer of a refinement on one thread
    // The walker set up for this refinement (a Walker<kView, kFast>, copied per chunk).
    alignas(64) unsigned char walker[1024];
};

Refiner::Refiner(const terrain::Heightfield& field, const VertexErrors& errors, RefinerDesc desc)
    : field_(&field), errors_(&errors), threads_(desc.threads) {
    int n = 0;
    SIERRA_CHECK(isSbtGrid(field, &n), "Refiner: the SBT needs a (2^n+1)^2 grid, got ",
                 field.width(), "x", field.height());
    SIERRA_CHECK(errors.n == n && errors.side == field.width() &&
                     errors.error.size() == size_t(field.sampleCount()) &&
                     errors.radius.size() == size_t(field.sampleCount()),
                 "Refiner: the vertex errors do not belong to this ", field.width(), "x",
                 field.height(), " grid");
    SIERRA_CHECK(field.width() <= kMaxSbtSide, "Refiner: a ", field.width(), "x", field.width(),
                 " grid has more vertices than 32-bit strip indices address (at most ", kMaxSbtSide,
                 "x", kMaxSbtSide, ")");
    n_ = n;
    side_ = field.width();
    chunkLevel_ =
        desc.chunkLevel >= 0 ? std::min(desc.chunkLevel, 2 * n - 1) : std::clamp(2 * n - 10, 0, 6);
}

Refiner::~Refiner() {
    // A helper may still be inside a chunk of the last refinement.
    if (busyFrame_ >= 0) waitParallelHelpers();
}

void Refiner::refineFixed(float epsilon, StripMesh& out) {
    // The keys serve only this mode: a refiner used for views never pays their
    // 4 bytes per sample.
    if (!keysBuilt_ && epsilon >= 0.0f) {  // epsilon < 0 splits everything: no keys read
        buildSplitKeys();
        keysBuilt_ = true;
    }
    run<false>(nullptr, epsilon, out);
}

namespace {
void checkView(const ViewParams& view) {
    SIERRA_CHECK(view.tau > 0 && std::isfinite(view.tau),
                 "refineView: tau must be > 0 pixels, got ", view.tau);
    SIERRA_CHECK(view.lambda > 0 && std::isfinite(view.lambda),
                 "refineView: lambda must be > 0, got ", view.lambda);
    for (float c : view.eye)
        SIERRA_CHECK(std::isfinite(c), "refineView: the eye must be finite, got (", view.eye[0],
                     ", ", view.eye[1], ", ", view.eye[2], ")");
}
}  // namespace

size_t Refiner::bufferBytes() const {
    auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    auto chunkBytes = [&](const Chunk& c) { return bytes(c.buffer) + bytes(c.starts); };
    size_t total = bytes(copies_);
    for (const std::unique_ptr<Frame>& f : frames_) {
        if (!f) continue;
        total += sizeof(Frame) + bytes(f->ops) + bytes(f->cuts) + bytes(f->order) +
                 bytes(f->winners) + bytes(f->slotOf) + bytes(f->eyeTerms) + bytes(f->chunkLeaves) +
                 chunkBytes(f->serialChunk);
        for (const std::vector<Chunk>& slot : f->chunks) {
            total += bytes(slot);
            for (const Chunk& c : slot) total += chunkBytes(c);
        }
    }
    return total;
}

void Refiner::refineView(const ViewParams& view, StripMesh& out) {
    checkView(view);
    prepareView();
    run<true, true>(&view, 0.0f, out);
}

void Refiner::refineViewReference(const ViewParams& view, StripMesh& out) {
    checkView(view);
    run<true, false>(&view, 0.0f, out);
}

// The frame this refinement works in (its index in frames_): the one a helper
// of the last refinement may still read is left alone (*helperBusy then).
int Refiner::takeFrame(bool* helperBusy) {
    int frameIndex = 0;
    // A helper of the last refinement may still be leaving it: it has finished
    // its last copy a moment before, or stops within kStopEvery indices of a
    // chunk the caller ran again. Worth a short wait: 6 of 200 refinements of
    // a full 2049^2 grid on 2 threads found one there without it, none with
    // it; a refinement that finds one takes the other frame on one thread.
    *helperBusy = busyFrame_ >= 0 && !parallelHelpersIdleWithin(kHelperSettleSeconds);
    if (*helperBusy)
        frameIndex = 1 - busyFrame_;
    else
        busyFrame_ = -1;
    if (!frames_[frameIndex]) frames_[frameIndex] = std::make_unique<Frame>();
    return frameIndex;
}

// The walker's configuration: the grid and epsilon (fixed mode), the view in
// double (view mode), and in float with its slacks (fast view mode), the view
// keys' part set by setUpViewKeys.
template <typename W>
void Refiner::setUpWalker(W& proto, const ViewParams* view, float epsilon, Frame& frame) {
    proto.err = errors_->error.data();
    proto.rad = errors_->radius.data();
    proto.height = field_->samples().data();
    proto.side = uint32_t(side_);
    proto.finest = 2 * n_;
    proto.eps = epsilon;
    proto.epsKey = epsilonKey(epsilon);
    proto.keys = splitKeys_.empty() ? nullptr : splitKeys_.data();
    proto.splitNodes = splitKeys_.size();
    if constexpr (W::kIsView) {
        proto.ex = view->eye[0], proto.ey = view->eye[1], proto.ez = view->eye[2];
        proto.sx = field_->spacingX(), proto.sz = field_->spacingZ();
        proto.vs = field_->verticalScale();
        proto.kE = double(view->lambda) / double(view->tau);
        for (int k = 0; k < 6; ++k) proto.planes[k] = view->planes[k];
        if constexpr (W::kIsFast) {
            // Float slack (see Walker::activeFast): every coordinate, eye and
            // radius is at most M in magnitude; a float coordinate difference is
            // then within 3 M 2^-24 of the double one, a squared distance within
            // 2^-18 d^2 + 2^-24 M^2, a plane distance within 2^-24 (18 M + 4 |d|).
            // The slacks below are 4 to 8 times these bounds.
            const double M = std::max(
                {magnitude_, std::fabs(proto.ex), std::fabs(proto.ey), std::fabs(proto.ez), 1.0});
            proto.fex = view->eye[0], proto.fey = view->eye[1], proto.fez = view->eye[2];
            proto.fsx = field_->spacingX(), proto.fsz = field_->spacingZ();
            proto.fkE = float(proto.kE);
            proto.fvs = field_->verticalScale();
            proto.distanceSlack = float(0x1.0p-22 * M * M);
            for (int k = 0; k < 6; ++k)
                proto.planeSlack[k] =
                    float(0x1.0p-19 * (3.0 * M + std::fabs(double(view->planes[k].d))));
            if (!viewKeys_.empty()) setUpViewKeys(proto, M, frame);
        }
    }
}

// The reaches are made for the first view's lambda / tau, and again once
// kReachRebuildAfter refinements in a row asked for one other (a viewport,
// field of view or tau that changed and stays): a rebuild costs about ten
// refinements, and the keys of another factor still decide most vertices.
void Refiner::followReachFactor(double kE) {
    // A helper of the last refinement may still read the keys (once they have
    // reaches: the first build has no reader).
    auto rebuild = [&] {
        if (keyReachFactor_ != 0.0 && busyFrame_ >= 0) {
            waitParallelHelpers();
            busyFrame_ = -1;
        }
        buildReachKeys(kE);
    };
    if (keyReachFactor_ == 0.0) {
        rebuild();
    } else if (kE == keyReachFactor_) {
        otherReachCount_ = 0;
    } else {
        otherReachCount_ = kE == otherReachFactor_ ? otherReachCount_ + 1 : 1;
        otherReachFactor_ = kE;
        if (otherReachCount_ >= kReachRebuildAfter) rebuild();
    }
}

// The keyed walk's configuration (Walker::walkKeyed), M the magnitude bound
// of the float slacks (setUpWalker). The key bounds are rounded in float like
// the exact operands, to within 2^-21 of the reach plus keyYError; keyYError
// is at most M / 65535, so its square is far below distanceSlack and the same
// slack covers both.
template <typename W>
void Refiner::setUpViewKeys(W& proto, double M, Frame& frame) {
    followReachFactor(proto.kE);
    proto.viewKeys = viewKeys_.data();
    proto.keyYBase = keyYBase_, proto.keyYStep = keyYStep_, proto.keyYError = keyYError_;
    proto.keyReachBase = keyReachBase_;
    // s = this factor over the keys' (see Walker::keyScaled), the
    // four factors rounded outwards
    const double scale = proto.kE / keyReachFactor_;
    proto.keyScaled = scale != 1.0;
    proto.keyScaleLo = roundDown(scale), proto.keyScaleHi = roundUp(scale);
    proto.keyRatioLo = roundUp(std::max(scale - 1.0, 0.0));
    proto.keyRatioHi = roundUp(std::max(1.0 - scale, 0.0));
    const double below =
        double(keyYError_) + (double(proto.keyScaleHi) + double(proto.keyRatioHi)) *
                                 double(std::bit_cast<float>(keyReachBase_));
    proto.keyLowError =
        std::nextafter(float(below * (1.0 + 0x1.0p-20)), std::numeric_limits<float>::infinity());
    proto.keyDy0 = float(double(keyYBase_) - proto.ey);
    // The column and row terms are rounded once from double; dy is
    // within 2^-21 M of the decoded height's distance (three
    // roundings of values below 3 M), so every squared distance is
    // within 2^-21 (d^2 + M^2): the slack is 4 times that and more.
    proto.keySlack = float(0x1.0p-16 * M * M);
    proto.keyGrow = float(1.0 + 0x1.0p-13);
    std::vector<float>& eyeTerms = frame.eyeTerms;
    eyeTerms.resize(2 * size_t(side_));
    for (int k = 0; k < side_; ++k) {
        const double dx = k * proto.sx - proto.ex, dz = k * proto.sz - proto.ez;
        eyeTerms[size_t(k)] = float(dx * dx);
        eyeTerms[size_t(side_ + k)] = float(dz * dz);
    }
    proto.dxx = eyeTerms.data();
    proto.dzz = eyeTerms.data() + side_;
}

namespace {

// The serial top of the tree, from the two level-0 triangles down to the
// chunk level, recorded as the frame's ops and cut into chunks (frame.cuts);
// the walker set up for the chunks is stored in the frame.
template <typename W>
void recordTop(const W& proto, unsigned rootMask, int side, int chunkLevel, Refiner::Frame& frame) {
    using V = typename W::V;
    using Op = Refiner::Op;
    // Vertices of the two level-0 triangles: entry (0,0), apex (0,S), exit (S,S);
    // entry (S,S), apex (S,0), exit (0,0).
    const uint32_t S = uint32_t(side - 1);
    auto vert = [&](uint32_t i, uint32_t j) -> V {
        if constexpr (W::kIsView)
            return V(i) | (V(j) << 32);
        else
            return j * uint32_t(side) + i;
    };
    const V v00 = vert(0, 0), v0S = vert(0, S), vSS = vert(S, S), vS0 = vert(S, 0);

    std::vector<Op>& ops = frame.ops;
    ops.clear();
    TopWalker<W> top{&proto, chunkLevel, &ops};
    top.refine(v00, v0S, vSS, 0, rootMask, 0);
    top.push(Op::kAppend, 0, 0, proto.index(vSS), 0, 0);
    top.refine(vSS, vS0, v00, 0, rootMask, 1);
    top.push(Op::kAppend, 0, 0, proto.index(v00), 0, 0);

    // Chunks: cut before every subtree op (the ops before the first form chunk 0).
    std::vector<size_t>& cuts = frame.cuts;  // small: at most 2^(chunkLevel+1) + 1 entries
    cuts.clear();
    cuts.push_back(0);
    for (size_t k = 1; k < ops.size(); ++k)
        if (ops[k].kind == Op::kSubtree) cuts.push_back(k);
    cuts.push_back(ops.size());
    std::memcpy(frame.walker, &proto, sizeof(W));
}

// Chunk c's place in a per-subtree work array (Refiner::viewChunkWork_): its
// subtree's index within the chunk level (UINT64_MAX when the chunk holds no
// subtree).
uint64_t workSlot(const Refiner::Frame& frame, int c, int chunkLevel) {
    const uint64_t levelFirst = (uint64_t(2) << chunkLevel) - 2;  // first tree node of the level
    for (size_t k = frame.cuts[size_t(c)]; k < frame.cuts[size_t(c) + 1]; ++k)
        if (frame.ops[k].kind == Refiner::Op::kSubtree) return frame.ops[k].node - levelFirst;
    return UINT64_MAX;
}

// One thread: the chunks write their strips straight into the output, one
// after the other, and each is joined where it lies: a strip moves down by
// the indices the join drops before it (a restart between merged strips, an
// entry vertex dropped for the winding), within data still in the cache, and
// not at all when none are. Each chunk starts one index past the joined
// output, so a strip never moves up. The output is first made as large as
// what the last refinement in this mode wrote (lastIndices), and a little
// more, as far as it holds without reallocating, then grows by a quarter
// whenever a chunk needs it (growBuffer).
template <typename W>
void refineSerially(Refiner::Frame& frame, int64_t lastIndices, StripJoin& join, StripMesh& out) {
    const int chunkCount = int(frame.cuts.size()) - 1;
    const size_t guess = size_t(lastIndices + lastIndices / 32 + 4096);
    Refiner::Chunk& chunk = frame.serialChunk;
    std::vector<uint32_t>& v = chunk.buffer;
    v.swap(out.indices);
    if (v.size() < guess) v.resize(std::max(v.size(), std::min(guess, v.capacity())));
    chunk.isOutput = true;
    const Refiner::Op* ops = frame.ops.data();
    W w;
    for (int c = 0; c < chunkCount; ++c) {
        chunk.offset = size_t(join.pos) + 1;
        std::memcpy(&w, frame.walker, sizeof(W));
        w.bind(chunk, nullptr);
        w.execute(ops + frame.cuts[size_t(c)], ops + frame.cuts[size_t(c) + 1]);
        w.finish();
        frame.chunkLeaves[size_t(c)] = chunk.leaves;
        uint32_t* const first = v.data();
        join.place(chunk, [first](const Refiner::Copy& cp) {
            if (cp.restart) first[cp.dst - 1] = kRestartIndex;
            if (cp.src != first + cp.dst)
                std::memmove(first + cp.dst, cp.src, size_t(cp.length) * sizeof(uint32_t));
        });
    }
    v.resize(size_t(join.pos));
    v.swap(out.indices);
}

// The chunks on `threads` threads, each into a chunk buffer of the frame,
// largest first by the triangles each subtree made last time (`work`): the
// chunks left at the end, which a preempted helper may hold or the caller run
// twice, are the small ones. The output does not depend on the order. Chunks
// a preempted helper holds are run again by the caller
// (parallelRescuedChunks): the join never waits for a helper. Whether helpers
// took part; frame.slotOf then says whose strip counts for each chunk.
// busyFrame: Refiner::busyFrame_, cleared when the pool throws.
template <typename W>
bool runChunksPooled(Refiner::Frame& frame, int threads, int chunkLevel,
                     const std::vector<int64_t>& work, int& busyFrame) {
    const int chunkCount = int(frame.cuts.size()) - 1;
    for (std::vector<Refiner::Chunk>& slot : frame.chunks)
        if (slot.size() < size_t(chunkCount)) slot.resize(size_t(chunkCount));
    frame.winners.resize(size_t(chunkCount));
    frame.slotOf.resize(size_t(chunkCount));
    auto workOf = [&](int c) -> int64_t {
        const uint64_t slot = workSlot(frame, c, chunkLevel);
        return slot < work.size() ? work[slot] : 0;
    };
    frame.order.resize(size_t(chunkCount));
    for (int c = 0; c < chunkCount; ++c) frame.order[size_t(c)] = c;
    if (!work.empty())
        std::stable_sort(frame.order.begin(), frame.order.end(),
                         [&](int x, int y) { return workOf(x) > workOf(y); });
    // The body reads only the frame, which outlives the call.
    Refiner::Frame* const f = &frame;
    bool pooled = false;
    try {
        pooled = parallelRescuedChunks(
            chunkCount,
            [f](int unit, int slot, const ChunkStop& stop) {
                const size_t c = size_t(f->order[size_t(unit)]);
                W w;
                std::memcpy(&w, f->walker, sizeof(W));
                w.bind(f->chunks[slot][c], stop.possible() ? &stop : nullptr);
                try {
                    w.execute(f->ops.data() + f->cuts[c], f->ops.data() + f->cuts[c + 1]);
                    w.finish();
                } catch (const Stopped&) {
                    // the other run of this chunk finished first; this output is not used
                }
            },
            threads, frame.winners.data());
    } catch (...) {
        // Which frame a helper may still read is unknown here: wait (a
        // body throws only when memory runs out).
        waitParallelHelpers();
        busyFrame = -1;
        throw;
    }
    for (int u = 0; u < chunkCount; ++u)
        frame.slotOf[size_t(frame.order[size_t(u)])] = frame.winners[size_t(u)];
    return pooled;
}

// The join of the pooled chunks: a serial pass decides every strip's place
// (`copies`), and the copies run in parallel (on a full 2049^2 grid they move
// 56 MB, a seventh of a thread's refinement time).
void joinPooledChunks(Refiner::Frame& frame, int threads, std::vector<Refiner::Copy>& copies,
                      StripJoin& join, StripMesh& out) {
    const int chunkCount = int(frame.cuts.size()) - 1;
    copies.clear();
    for (int c = 0; c < chunkCount; ++c) {
        const Refiner::Chunk& ch = frame.chunks[frame.slotOf[size_t(c)]][size_t(c)];
        frame.chunkLeaves[size_t(c)] = ch.leaves;
        join.place(ch, [&](const Refiner::Copy& cp) { copies.push_back(cp); });
    }
    // room for a refinement on one thread of the same size (refineSerially),
    // growing by a quarter at least
    const size_t room = size_t(join.pos + join.pos / 32 + 4096);
    if (out.indices.capacity() < room)
        out.indices.reserve(std::max(room, out.indices.capacity() + out.indices.capacity() / 4));
    out.indices.resize(size_t(join.pos));
    uint32_t* const first = out.indices.data();
    const int64_t copyCount = int64_t(copies.size());
    // A copy cannot be run twice (it writes the caller's output), so a helper
    // preempted inside one holds the join: only copies of at least 2^22 indices
    // (16 MB, 1-3 ms of one thread) are shared.
    parallelChunks(
        0, copyCount, int(std::min<int64_t>(copyCount, 256)),
        [&](int64_t lo, int64_t hi, int) {
            for (int64_t k = lo; k < hi; ++k) copyStrip(first, copies[size_t(k)]);
        },
        join.pos >= (int64_t(1) << 22) ? threads : 1);
}

}  // namespace

template <bool kView, bool kFast>
void Refiner::run(const ViewParams* view, float epsilon, StripMesh& out) {
    using W = Walker<kView, kFast>;
    static_assert(std::is_trivially_copyable_v<W> && sizeof(W) <= sizeof(Frame::walker));
    bool helperBusy = false;
    const int frameIndex = takeFrame(&helperBusy);
    Frame& frame = *frames_[frameIndex];
    W proto{};
    setUpWalker(proto, view, epsilon, frame);
    const unsigned rootMask = kView && view->cull ? kAllPlanes : 0;
    recordTop(proto, rootMask, side_, chunkLevel_, frame);
    const int chunkCount = int(frame.cuts.size()) - 1;
    // Per subtree at the chunk level, the triangles it made last time (its
    // tree node at the chunk level identifies it).
    std::vector<int64_t>& work = kView ? viewChunkWork_ : fixedChunkWork_;

    bool adaptive = false;
    const int threads = chooseThreads(kView, helperBusy, &adaptive);
    const auto started = std::chrono::steady_clock::now();
    StripJoin join{uint32_t(side_)};
    std::vector<int64_t>& chunkLeaves = frame.chunkLeaves;
    chunkLeaves.resize(size_t(chunkCount));
    bool pooled = false;
    if (threads == 1) {
        refineSerially<W>(frame, kView ? lastViewIndices_ : lastFixedIndices_, join, out);
    } else {
        pooled = runChunksPooled<W>(frame, threads, chunkLevel_, work, busyFrame_);
        if (pooled) busyFrame_ = frameIndex;
        joinPooledChunks(frame, threads, copies_, join, out);
    }
    const int64_t leaves = join.leaves;
    out.triangleCount = leaves;
    out.stripCount = join.strips;
    out.culledSubtrees = join.culled;
    out.threads = pooled ? threads : 1;
    (kView ? lastViewTriangles_ : lastFixedTriangles_) = leaves;
    (kView ? lastViewIndices_ : lastFixedIndices_) = join.pos;
    if (adaptive)
        (kView ? viewThreads_ : fixedThreads_)
            .record(
                pooled,  // false: one thread (chosen, forced by a busy helper, or the pool's)
                std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
                leaves);
    // Each subtree's triangles, for the next refinement's chunk order (levels
    // up to 12: at most 8192 subtrees).
    if (chunkLevel_ <= 12) {
        work.assign(size_t(2) << chunkLevel_, 0);
        for (int c = 0; c < chunkCount; ++c)
            if (const uint64_t slot = workSlot(frame, c, chunkLevel_); slot < work.size())
                work[size_t(slot)] = chunkLeaves[size_t(c)];
    }
}

}  // namespace sierra::sbt
