#pragma once
// The refiner's walker (private to the sbt module): the state of one chunk's
// walk down the SBT, shared by the recursions over the tree, each in a file
// of its own:
//
//   ExactWalk.h     refine(): the reference walk, every test in double
//                   (refineViewReference; fixed mode without split keys), and
//                   TopWalker, the serial top above the chunk level
//   SplitKeyWalk.h  refineKeyed(): fixed mode on the split keys
//   FastWalk.h      node() / split(): view mode in float with guard bands,
//                   double inside them (refineView)
//   KeyedWalk.h     walkKeyed(): the per-level walk below a sphere inside
//                   the frustum, decided from the view keys (refineView)
//
// This file holds the walker's configuration (set by Refiner::setUpWalker in
// Refiner.cpp), its output (a chunk's strip, written through the strip writer
// of StripWriter.h) and execute(), which runs a chunk's ops through the walk
// its mode takes. Every walk makes the same decisions as the reference walk,
// so every mode's output is byte-identical to it.
//
// Everything here has internal linkage: these headers are included by
// Refiner.cpp alone, and the compiler specialises the walks for it.

#include "sbt/Keys.h"
#include "sbt/StripWriter.h"

#include <sierra/core/Parallel.h>
#include <sierra/sbt/Refiner.h>

#include <array>
#include <cstdint>
#include <type_traits>
#include <utility>

// The view keys' paired test uses SSE2 (every x86-64 has it); elsewhere, or
// with SIERRA_SBT_NO_SIMD defined, a scalar loop makes the same decisions.
#if defined(__SSE2__) && !defined(SIERRA_SBT_NO_SIMD)
#define SIERRA_SBT_SSE2 1
#include <emmintrin.h>
#endif

namespace sierra::sbt {

// One step of the serial top of the recursion (levels < chunkLevel).
struct Refiner::Op {
    enum Kind : uint8_t { kSubtree, kLeaf, kAppend, kBreak };
    Kind kind;
    uint8_t level;     // level of the triangle, or the parity of an append
    uint8_t mask;      // planes still to test below (view mode)
    uint64_t a, q, b;  // vertices (linear index in fixed mode, packed (i, j) in view mode)
    uint64_t node;     // tree index of the triangle (see splitKeys_), subtrees only
};

namespace {

constexpr unsigned kAllPlanes = 0x3f;
constexpr unsigned kCulled = 0x80;

// Thrown inside a walker whose chunk another run has finished (ChunkStop):
// unwinds the recursion, caught by the chunk's body.
struct Stopped {};

// A walker with a stop request checks it every this many output indices
// (about 40-100 microseconds of refinement): at the buffer check it makes
// anyway, so the hot path pays nothing.
constexpr int64_t kStopEvery = 4096;

// The recursion state of one chunk. kView selects the vertex representation:
// a linear index j * side + i in fixed mode (the midpoint of a and b is
// (a + b) / 2 because both coordinate sums are even), packed (i | j << 32) in
// view mode (the same midpoint rule holds lane-wise).
template <bool kView, bool kFast = false>
struct Walker {
    using V = std::conditional_t<kView, uint64_t, uint32_t>;
    static constexpr bool kIsView = kView;
    static constexpr bool kIsFast = kFast;

    // configuration
    const float* err;
    const float* rad;
    const float* height;
    const uint16_t* keys;  // splitKeys_ (fixed mode)
    uint64_t splitNodes;   // triangles of levels 0..2n-1 = size of keys
    uint32_t side;
    int finest;
    float eps;
    int32_t epsKey;
    double ex, ey, ez, sx, sz, vs, kE;
    Plane planes[6];
    // fast view path (kFast): the view in float, and the guard bands below
    // which the float result could differ from the double one.
    float fex, fey, fez, fsx, fsz, fkE, fvs;
    float distanceSlack;  // absolute slack on squared distances (world units^2)
    float planeSlack[6];  // absolute slack on plane distances (world units)
    // view keys (Refiner::viewKeys_), null when there are none: 2 per tree node
    const uint16_t* viewKeys;
    float keyYBase, keyYStep, keyYError;  // world y = keyYBase + key * keyYStep, +- keyYError
    uint32_t keyReachBase;                // lengthKey base of the reaches
    // keyScaled: this view's lambda / tau is s != 1 times the keys'. A vertex
    // whose radius is at most rho times its reach R for the keys (rho = 2^-12,
    // 2^-8, 2^-4 or 1 by the ratio class in the low 2 bits of its height
    // key) then has a reach between (s - max(s - 1, 0) rho) R and
    // (s + max(1 - s, 0) rho) R: the walk takes s as keyScaleLo and
    // keyScaleHi, and max(s - 1, 0) and max(1 - s, 0) as keyRatioLo and
    // keyRatioHi, each rounded outwards.
    bool keyScaled;
    float keyScaleLo, keyScaleHi, keyRatioLo, keyRatioHi;
    // keyYError + the largest high scale times the base's float, rounded up:
    // what the low bound of a reach subtracts (a key 0 stands for any reach
    // below the base's float)
    float keyLowError;
    const float* dxx;  // (i * spacingX - eye x)^2 for every column i, rounded to float
    const float* dzz;  // (j * spacingZ - eye z)^2 for every row j
    float keyDy0;      // keyYBase - eye y
    float keySlack;    // absolute slack of the keyed test's squared distances (world units^2)
    float keyGrow;     // relative slack: (1 + 2^-15) / (1 - 2^-15), rounded up

    // output
    Refiner::Chunk* chunk;
    uint32_t* base;
    uint32_t* out;
    uint32_t* cap;  // where ensure() calls grow(): the buffer's end, or before it (stop)
    uint32_t* end;  // the buffer's end
    const sierra::ChunkStop* stop;  // this run's stop request; null: none
    int parity = -1;  // of the strip's last append (StripParity); -1: none since its start
    bool needStart = true;
    int64_t leaves = 0;
    int64_t culled = 0;  // culled subtrees, summed over the chunks at the end

    void bind(Refiner::Chunk& c, const sierra::ChunkStop* s) {
        chunk = &c;
        stop = s;
        c.starts.clear();
        if (c.buffer.size() < c.offset + 4096) growBuffer(c.buffer, c.offset + 4096, c.isOutput);
        base = out = c.buffer.data() + c.offset;
        end = c.buffer.data() + c.buffer.size();
        setCap();
    }
    void setCap() { cap = stop && end - out > kStopEvery ? out + kStopEvery : end; }
    void finish() {
        chunk->used = out - base;
        chunk->leaves = leaves;
        chunk->culled = culled;
    }
    // Out of line and cold: the hot recursions stay small.
    [[gnu::noinline, gnu::cold]] void grow(size_t need) {
        if (stop && stop->requested()) throw Stopped{};
        if (size_t(end - out) < need) {
            auto& buf = chunk->buffer;
            const size_t at = size_t(out - buf.data());
            growBuffer(buf, at + need + 4096, chunk->isOutput);
            base = buf.data() + chunk->offset;
            out = buf.data() + at;
            end = buf.data() + buf.size();
        }
        setCap();
    }
    inline void ensure(size_t k) {
        if (size_t(cap - out) < k) [[unlikely]]
            grow(k);
    }

    inline uint32_t index(V v) const {
        if constexpr (kView)
            return uint32_t(v >> 32) * side + uint32_t(v);
        else
            return v;
    }

    // Vertex v of level parity p onto the strip (view mode: once it has started).
    [[gnu::always_inline]] inline void append(uint32_t v, int p) {
        if constexpr (kView) {
            if (needStart) return;
        }
        appendToStrip(out, v, p, StripParity{parity});
    }

    void start(uint32_t a) {
        ensure(8);
        if (out != base) *out++ = kRestartIndex;
        chunk->starts.push_back(uint32_t(out - base));
        out[0] = a;
        out[1] = a;
        out += 2;
        parity = -1;
        needStart = false;
    }

    // --- the reference walk (ExactWalk.h) ---------------------------------
    inline unsigned cull(double x, double y, double z, float r, unsigned mask) const;
    void refine(V a, V q, V b, int l, unsigned mask);

    // --- fast view walk (FastWalk.h) ----------------------------------------
    inline unsigned cullFast(uint32_t i, uint32_t j, float x, float y, float z, float r,
                             unsigned mask) const;
    inline bool activeFast(uint32_t i, uint32_t j, float x, float y, float z, float e,
                           float r) const;
    inline void prefetch(V v) const;
    inline void leafFast(V a, V q, int l);
    inline void node(V a, V q, V b, int l, unsigned mask, uint64_t k);
    void split(V a, V q, V b, int l, unsigned mask, V m, uint64_t k);
    void refineFast(V a, V q, V b, int l, unsigned mask, uint64_t k) { node(a, q, b, l, mask, k); }

    // --- keyed view walk (KeyedWalk.h) --------------------------------------
    // --- keyed view path: below a sphere fully inside the frustum -----------
    static constexpr int kPrefetchDepth = 3;
    // Subtrees of at most this many levels below their node make one room
    // check for all their appends (fewer than 4 << depth indices).
    static constexpr int kRoomDepth = 6;
    // The most levels a keyed subtree has below its node: one keyedLevel per
    // depth, for either parity of the finest level and either keyScaled. A
    // node higher up (only on grids above 2049², whose chunks start at level
    // 6) takes the exact path, node(), down to that depth.
    static constexpr int kMaxKeyedDepth = 16;

    // The keyed walk's constants, set by walkKeyed for the walk below it.
    struct KeyedWalk {
#if SIERRA_SBT_SSE2
        __m128 yErr, loErr, slack, yStep, dy0, grow, scaleLo, scaleHi, ratioLo, ratioHi, band;
        __m128i ratioClass, rho, nextKey, reachBase;
#endif
        const float* xx;
        const float* zz;
        uintptr_t keys;  // viewKeys
        uint32_t side;
    };
    KeyedWalk kw_;
    // What a keyed subtree hands back: the output pointer, and its leaves
    // times 4 plus the strip's parity + 1 after it.
    struct Walked {
        uint32_t* out;
        int64_t state;
    };
    // A tree node's keys: the pair of its children's keys starts kPair * (k + 1)
    // bytes into the view keys (its "key offset"); its children's own pairs
    // then start at 2 kb + kPair (left) and 2 kb + 2 kPair (right).
    static constexpr uint64_t kPair = 8;  // bytes of a sibling pair's keys
    [[gnu::noinline]] bool activeExact(V m) const;
    template <bool kScaled>
    void walkKeyed(V a, V q, V b, int l, uint64_t node);
    template <bool kScaled>
    [[gnu::always_inline]] inline unsigned activePair(V vl, V vr, uint64_t kb) const;
    template <bool kScaled, bool kOdd, int depth>
    Walked keyedLevel(V a, V q, V b, uint64_t kb, uint32_t* o, int64_t state);
    using KeyedLevel = Walked (Walker::*)(V, V, V, uint64_t, uint32_t*, int64_t);
    template <bool kScaled, bool kOdd, size_t... depthLess1>
    static constexpr std::array<KeyedLevel, sizeof...(depthLess1)> keyedLevels(
        std::index_sequence<depthLess1...>);
    // keyedLevels(kDepths): keyedLevel for depth 1..kMaxKeyedDepth, at index depth - 1
    static constexpr std::make_index_sequence<kMaxKeyedDepth> kDepths{};

    // --- fixed mode on the split keys (SplitKeyWalk.h) ----------------------
    template <bool kAll>
    inline bool splits(uint64_t node, uint32_t a, uint32_t b) const;
    inline void leaf(uint32_t q, int l);
    void refineKeyed(uint32_t a, uint32_t q, uint32_t b, int l, uint64_t node);
    template <bool kAll>
    void descend(uint32_t a, uint32_t q, uint32_t b, int l, uint64_t node);

    // A chunk's ops [op, end), each subtree through the walk of this mode.
    void execute(const Refiner::Op* op, const Refiner::Op* end) {
        for (; op != end; ++op) {
            switch (op->kind) {
                case Refiner::Op::kSubtree:
                    if (!kView && needStart) start(index(V(op->a)));
                    if constexpr (kFast) {
                        if (op->level < finest)
                            refineFast(V(op->a), V(op->q), V(op->b), op->level, op->mask, op->node);
                        else
                            leafFast(V(op->a), V(op->q), op->level);
                    } else if (!kView && keys) {
                        refineKeyed(uint32_t(op->a), uint32_t(op->q), uint32_t(op->b), op->level,
                                    op->node);
                    } else {
                        refine(V(op->a), V(op->q), V(op->b), op->level, op->mask);
                    }
                    break;
                case Refiner::Op::kLeaf:
                    if (needStart) start(index(V(op->a)));
                    ensure(4);
                    append(index(V(op->q)), op->level & 1);
                    ++leaves;
                    break;
                case Refiner::Op::kAppend:
                    ensure(4);
                    append(uint32_t(op->a), op->level);
                    break;
                case Refiner::Op::kBreak:  // a subtree culled above the chunk level
                    needStart = true;
                    ++culled;
                    break;
            }
        }
    }
};

}  // namespace
}  // namespace sierra::sbt
