#include <sierra/sbt/Refiner.h>

#include "sbt/Rounding.h"

#include <sierra/core/Error.h>
#include <sierra/core/Parallel.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
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

struct Refiner::Chunk {
    std::vector<uint32_t> buffer;  // strip indices from `offset` on, capacity reused
    std::vector<uint32_t> starts;  // offset of every strip, from buffer.data() + offset
    size_t offset = 0;             // where the chunk's strips start in buffer
    // The buffer is the refinement's output (one thread): it grows by a
    // quarter, not twice its size (see Refiner::run).
    bool isOutput = false;
    int64_t used = 0;
    int64_t leaves = 0;
    int64_t culled = 0;  // subtrees culled in this chunk (view mode)
};

namespace {

constexpr unsigned kAllPlanes = 0x3f;

// Thrown inside a walker whose chunk another run has finished (ChunkStop):
// unwinds the recursion, caught by the chunk's body.
struct Stopped {};

// A walker with a stop request checks it every this many output indices
// (about 40-100 microseconds of refinement): at the buffer check it makes
// anyway, so the hot path pays nothing.
constexpr int64_t kStopEvery = 4096;
// How long a refinement waits for a helper still leaving the last one.
constexpr double kHelperSettleSeconds = 200e-6;
constexpr unsigned kCulled = 0x80;
// Refinements in a row with one lambda / tau other than the view keys' before
// the reaches are made again for it (Refiner::run).
constexpr int kReachRebuildAfter = 4;

// Split keys: the top 16 bits of a non-negative float's bit pattern (sign 0,
// 8 exponent bits, 7 mantissa bits: bfloat16 rounded towards zero). The map is
// monotone, so for e, eps >= 0:  key(e) > key(eps) implies e > eps and
// key(e) < key(eps) implies e <= eps; only equal keys need the exact float.
inline uint32_t floatKey(float x) {
    return std::bit_cast<uint32_t>(x) >> 16;
}

// View keys of lengths (errors and radii, >= 0): the float's bit pattern
// above a base, shifted right by kLengthKeyShift: 5 exponent and 11 mantissa
// bits, sixteen times finer than the top 16 bits of the float (on a rough
// 2049^2 fractal at tau = 1 the vertices the keys leave undecided per
// refinement fell from 6 738 of 1.1 M to 1 126 with 10 mantissa bits and to
// 660 with 11). The base lies 32 binades below the largest value keyed
// (lengthKeyBase): every value down to 2^-32 of the largest has a key (the
// radii of a 32769^2 grid span 15 binades); a value below the base's float
// gets key 0. The map is monotone: a value with key k lies in
// [float of (k << shift) + base, float of ((k + 1) << shift) + base), except
// with key 0, where it lies in [0, float of base): the walker's low bound
// subtracts the base's float (Walker::keyLowError).
constexpr int kLengthKeyShift = 12;
inline uint32_t lengthKeyBase(float largest) {
    const uint32_t top = std::bit_cast<uint32_t>(largest);
    constexpr uint32_t span = uint32_t(0xFFFF) << kLengthKeyShift;
    return top > span ? top - span : 0;
}
inline uint16_t lengthKey(float x, uint32_t base) {
    const uint32_t b = std::bit_cast<uint32_t>(x);
    return b < base ? 0 : uint16_t((b - base) >> kLengthKeyShift);
}

// The key epsilon is compared with, as a signed int so that "everything
// splits" (eps < 0) and "nothing splits" (eps NaN) need no special case in the
// hot loop: -1 is below every key, 0x10000 above every key.
inline int32_t epsilonKey(float eps) {
    if (std::isnan(eps)) return 0x10000;
    if (eps < 0.0f) return -1;
    return int32_t(floatKey(eps + 0.0f));  // + 0.0f: -0 becomes +0
}

// Grows a buffer to at least `need` indices: by a quarter of its size, or
// within its capacity, for the refinement's output (isOutput), which would
// otherwise double its capacity when resized past it (56 MB more on a full
// 2049^2 grid, written once over and so faulted in); twice its size for a
// chunk's own buffer.
void growBuffer(std::vector<uint32_t>& buf, size_t need, bool isOutput) {
    if (!isOutput) {
        buf.resize(std::max(buf.size() * 2, need));
        return;
    }
    const size_t quarter = buf.size() + buf.size() / 4;
    if (need <= buf.capacity()) {
        buf.resize(std::min(buf.capacity(), std::max(need, quarter)));
        return;
    }
    buf.reserve(std::max(need, quarter));
    buf.resize(buf.capacity());
}

// The recursion state of one chunk. kView selects the vertex representation:
// a linear index j * side + i in fixed mode (the midpoint of a and b is
// (a + b) / 2 because both coordinate sums are even), packed (i | j << 32) in
// view mode (the same midpoint rule holds lane-wise).
template <bool kView, bool kFast = false>
struct Walker {
    using V = std::conditional_t<kView, uint64_t, uint32_t>;
    static constexpr bool kIsView = kView;

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
    int parity = -1;
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

    [[gnu::always_inline]] inline void append(uint32_t v, int p) {
        if constexpr (kView) {
            if (needStart) return;
        }
        if (v == out[-1] || v == out[-2]) return;
        if (p == parity) {
            out[0] = out[-2];  // re-send: the strip turns
            ++out;
        } else {
            parity = p;
        }
        *out++ = v;
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

    // Sphere of vertex m against the planes still in `mask`: kCulled when fully
    // outside one, else the planes it still straddles.
    inline unsigned cull(double x, double y, double z, float r, unsigned mask) const {
        for (int k = 0; k < 6; ++k) {
            if (!(mask & (1u << k))) continue;
            const Plane& p = planes[k];
            double s = p.a * x + p.b * y + p.c * z + p.d;
            if (s < -double(r)) return kCulled;
            if (s >= double(r)) mask &= ~(1u << k);
        }
        return mask;
    }

    // Triangle with hypotenuse endpoints a (entry) and b (exit), apex q.
    void refine(V a, V q, V b, int l, unsigned mask) {
        ensure(4);
        if (l < finest) {
            const V m = (a + b) >> 1;
            const uint32_t mi = index(m);
            if constexpr (kView) {
                const uint32_t i = uint32_t(m), j = uint32_t(m >> 32);
                const double x = i * sx, y = double(height[mi]) * vs, z = j * sz;
                const float r = rad[mi];
                if (mask) {
                    mask = cull(x, y, z, r, mask);
                    if (mask == kCulled) {
                        ++culled;
                        needStart = true;
                        return;
                    }
                }
                if (needStart) start(index(a));
                const double dx = x - ex, dy = y - ey, dz = z - ez;
                const double reach = kE * double(err[mi]) + double(r);
                if (reach * reach > dx * dx + dy * dy + dz * dz) {
                    refine(a, m, q, l + 1, mask);
                    append(index(q), l & 1);
                    refine(q, m, b, l + 1, mask);
                    return;
                }
            } else {
                if (err[mi] > eps) {
                    if (l + 1 == finest) {
                        // Both children are leaves: emitted here, not through two
                        // calls (half of all triangles; 19% of the full grid's
                        // instructions once GCC stopped inlining this recursion).
                        ensure(6);
                        append(m, (l + 1) & 1);
                        append(q, l & 1);
                        append(m, (l + 1) & 1);
                        leaves += 2;
                        return;
                    }
                    refine(a, m, q, l + 1, mask);
                    append(q, l & 1);
                    refine(q, m, b, l + 1, mask);
                    return;
                }
            }
        } else if constexpr (kView) {
            if (needStart) start(index(a));
        }
        append(index(q), l & 1);
        ++leaves;
    }

    // --- fast view path -------------------------------------------------
    // The same decisions as refine() (the double-precision baseline), taken in
    // float where the float result is certain: a float value v of a quantity
    // computed exactly as w in double satisfies |v - w| <= slack (bounds in
    // Refiner::run), so a comparison whose float margin exceeds the slack has
    // the same outcome in double; the few inside the band are recomputed in
    // double. The children's data are prefetched while the parent is decided.
    // (An interleaved 12-byte record per vertex, one cache line instead of
    // three, was measured no faster on the orbit case and cost 12 bytes per
    // sample: not kept.)

    // Plane tests of vertex m's sphere, in float with a double fallback.
    inline unsigned cullFast(uint32_t i, uint32_t j, float x, float y, float z, float r,
                             unsigned mask) const {
        for (int k = 0; k < 6; ++k) {
            if (!(mask & (1u << k))) continue;
            const Plane& p = planes[k];
            const float s = p.a * x + p.b * y + p.c * z + p.d;
            const float slack = planeSlack[k];
            if (s < -r - slack) return kCulled;
            if (s >= r + slack) {
                mask &= ~(1u << k);
                continue;
            }
            if (s >= -r + slack && s < r - slack) continue;  // straddles for sure
            // the band: exactly the baseline's double test
            const uint32_t mi = j * side + i;
            const double xd = i * sx, yd = double(height[mi]) * vs, zd = j * sz;
            const double sd = p.a * xd + p.b * yd + p.c * zd + p.d;
            if (sd < -double(r)) return kCulled;
            if (sd >= double(r)) mask &= ~(1u << k);
        }
        return mask;
    }

    // Is vertex (i, j) active? reach^2 > d^2 in float, double in the band.
    inline bool activeFast(uint32_t i, uint32_t j, float x, float y, float z, float e,
                           float r) const {
        const float dx = x - fex, dy = y - fey, dz = z - fez;
        const float d2 = dx * dx + dy * dy + dz * dz;
        const float reach = fkE * e + r;
        const float r2 = reach * reach;
        const float slack = 0x1.0p-17f * (r2 + d2) + distanceSlack;
        if (r2 > d2 + slack) return true;
        if (r2 < d2 - slack) return false;
        const uint32_t mi = j * side + i;
        const double xd = i * sx, yd = double(height[mi]) * vs, zd = j * sz;
        const double ddx = xd - ex, ddy = yd - ey, ddz = zd - ez;
        const double reachD = kE * double(err[mi]) + double(rad[mi]);
        return reachD * reachD > ddx * ddx + ddy * ddy + ddz * ddz;
    }

    inline void prefetch(V v) const {
        const uint32_t i = uint32_t(v), j = uint32_t(v >> 32);
        const size_t mi = j * side + i;
        __builtin_prefetch(height + mi);
        __builtin_prefetch(err + mi);
        __builtin_prefetch(rad + mi);
    }

    // Leaf at level l with apex q (entry a): what refine() does for a leaf.
    inline void leafFast(V a, V q, int l) {
        if (needStart) start(index(a));
        ensure(4);
        append(index(q), l & 1);
        ++leaves;
    }

    // Triangle (a, q, b) at level l < finest: culled, a leaf, or split. Its
    // children are decided here too (node() is inlined into split()), so a
    // call is made only for a child that splits: half of the visited
    // triangles are leaves.
    inline void node(V a, V q, V b, int l, unsigned mask, uint64_t k) {
        ensure(4);
        const V m = (a + b) >> 1;
        const uint32_t i = uint32_t(m), j = uint32_t(m >> 32);
        const uint32_t mi = j * side + i;
        const float x = float(i) * fsx, y = height[mi] * fvs, z = float(j) * fsz, r = rad[mi];
        if (mask) {
            mask = cullFast(i, j, x, y, z, r, mask);
            if (mask == kCulled) {
                ++culled;
                needStart = true;
                return;
            }
        }
        if (needStart) start(index(a));
        if (!activeFast(i, j, x, y, z, err[mi], r)) {
            append(index(q), l & 1);
            ++leaves;
            return;
        }
        if (mask == 0 && viewKeys && finest - l <= kMaxKeyedDepth) {
            if (keyScaled)
                walkKeyed<true>(a, q, b, l, k);
            else
                walkKeyed<false>(a, q, b, l, k);
        } else {
            split(a, q, b, l, mask, m, k);
        }
    }

    void split(V a, V q, V b, int l, unsigned mask, V m, uint64_t k) {
        if (l + 1 < finest) {
            // the children's data, needed right after this call's frame set-up
            prefetch((a + q) >> 1);
            prefetch((q + b) >> 1);
            node(a, m, q, l + 1, mask, 2 * k + 2);
            ensure(4);
            append(index(q), l & 1);
            node(q, m, b, l + 1, mask, 2 * k + 3);
        } else {
            leafFast(a, m, l + 1);
            ensure(4);
            append(index(q), l & 1);
            leafFast(q, m, l + 1);
        }
    }

    void refineFast(V a, V q, V b, int l, unsigned mask, uint64_t k) { node(a, q, b, l, mask, k); }

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

    // activePair's exact fallback, out of line: the keyed walk's common path
    // makes no call but the next level's.
    [[gnu::noinline]] bool activeExact(V m) const {
        const uint32_t i = uint32_t(m), j = uint32_t(m >> 32);
        const uint32_t mi = j * side + i;
        return activeFast(i, j, float(i) * fsx, height[mi] * fvs, float(j) * fsz, err[mi], rad[mi]);
    }

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

    // Triangle (a, q, b), tree node k, at level l < finest, whose split vertex
    // m is active and whose sphere lies inside every plane (nothing below is
    // culled, so the strip has started): its descendants are decided from the
    // view keys (Refiner::viewKeys_), the keys kPrefetchDepth levels below
    // prefetched (a subtree's keys lie level by level in contiguous runs).
    //
    // A node's split vertex from its keys: the world y to within keyYError,
    // the reach for the keys' lambda / tau between the float of its key and
    // that of the next key, and this view's reach between keyScaleLo times
    // the first and keyScaleHi times the second. It is active for sure when the smallest reach
    // exceeds the distance computed with the decoded y by more than keyYError (the true distance
    // differs by at most that) plus the float slack of activeFast; inactive for sure when the
    // largest reach falls short by as much; else activeFast decides from the exact arrays.
    //
    // The walk is a recursion with one function per level (keyedLevel<D>, D
    // the levels below the node), so the branch predictor sees each level's
    // decisions at branches of their own: how often a child splits differs
    // from level to level (at 2049² and tau 1, the left child of a node on
    // level 14 splits 96% of the time, on level 17 41%, on level 20 7%). It
    // replaced a loop over an explicit stack, whose one decision branch
    // served every level, though the loop ran 6% fewer instructions (its
    // constants lived in registers): the frame loop of sierra-bench frames
    // refines 8-11% faster (docs/refinement.md). Both children are decided
    // together (activePair, two SSE2 lanes over the sibling pair's keys).
    template <bool kScaled>
    void walkKeyed(V a, V q, V b, int l, uint64_t node) {
        KeyedWalk& w = kw_;
#if SIERRA_SBT_SSE2
        w.yErr = _mm_set1_ps(keyYError);
        w.loErr = _mm_set1_ps(keyLowError);
        w.slack = _mm_set1_ps(keySlack);
        w.yStep = _mm_set1_ps(keyYStep);
        w.dy0 = _mm_set1_ps(keyDy0);
        w.grow = _mm_set1_ps(keyGrow);
        w.scaleLo = _mm_set1_ps(keyScaleLo);
        w.scaleHi = _mm_set1_ps(keyScaleHi);
        w.ratioLo = _mm_set1_ps(keyRatioLo);
        w.ratioHi = _mm_set1_ps(keyRatioHi);
        w.band = _mm_set1_ps(0x1.0p-15f);
        w.ratioClass = _mm_set1_epi32(3);
        w.rho = _mm_set1_epi32((127 - 12) << 23);
        w.nextKey = _mm_set1_epi32(1 << kLengthKeyShift);
        w.reachBase = _mm_set1_epi32(int32_t(keyReachBase));
#endif
        w.xx = dxx;
        w.zz = dzz;
        w.keys = reinterpret_cast<uintptr_t>(viewKeys);
        w.side = side;
        // the node's levels below: its subtree reaches the finest level
        const int depth = finest - l;
        if (depth < kRoomDepth) ensure(size_t(4) << depth);
        static constexpr auto evenFinest = keyedLevels<kScaled, false>(kDepths);
        static constexpr auto oddFinest = keyedLevels<kScaled, true>(kDepths);
        const auto& levels = finest & 1 ? oddFinest : evenFinest;
        const Walked r =
            (this->*levels[depth - 1])(a, q, b, kPair * (node + 1), out, 4 * leaves + (parity + 1));
        out = r.out;
        leaves = r.state >> 2;
        parity = int(r.state & 3) - 1;
    }

    // A tree node's keys: the pair of its children's keys starts kPair * (k + 1)
    // bytes into the view keys (its "key offset"); its children's own pairs
    // then start at 2 kb + kPair (left) and 2 kb + 2 kPair (right).
    static constexpr uint64_t kPair = 8;  // bytes of a sibling pair's keys

    // Both children of tree node k (key offset kb) at once: bit 0 left (split
    // vertex vl), bit 1 right (vr). Each lane computes the same float
    // operations in the same order as one child's scalar test; the vertices
    // in neither sure band go to activeExact.
    template <bool kScaled>
    [[gnu::always_inline]] inline unsigned activePair(V vl, V vr, uint64_t kb) const {
        const KeyedWalk& w = kw_;
        const uint16_t* key = reinterpret_cast<const uint16_t*>(w.keys + kb);
#if SIERRA_SBT_SSE2
        uint64_t word;  // u16 lanes: y0 y1 R0 R1
        std::memcpy(&word, key, 8);
        const __m128i yr = _mm_unpacklo_epi16(_mm_cvtsi64_si128(int64_t(word)),
                                              _mm_setzero_si128());  // u32: y0 y1 R0 R1
        // lanes 0 and 1: the reach keys' floats (lengthKey); 2 and 3 are
        // never read (the masks keep bits 0 and 1)
        const __m128i reach =
            _mm_add_epi32(_mm_slli_epi32(_mm_srli_si128(yr, 8), kLengthKeyShift), w.reachBase);
        const __m128 dy = _mm_add_ps(_mm_mul_ps(_mm_cvtepi32_ps(yr), w.yStep), w.dy0);
        const __m128 xz = _mm_add_ps(
            _mm_unpacklo_ps(_mm_load_ss(w.xx + uint32_t(vl)), _mm_load_ss(w.xx + uint32_t(vr))),
            _mm_unpacklo_ps(_mm_load_ss(w.zz + uint32_t(vl >> 32)),
                            _mm_load_ss(w.zz + uint32_t(vr >> 32))));
        const __m128 d2 = _mm_add_ps(xz, _mm_mul_ps(dy, dy));
        const __m128i next = _mm_add_epi32(reach, w.nextKey);  // the next keys' floats
        __m128 low = _mm_castsi128_ps(reach), high = _mm_castsi128_ps(next);
        if constexpr (kScaled) {
            // rho = 2^(-12 + 4 c) for the ratio class c of each lane
            const __m128 rho = _mm_castsi128_ps(
                _mm_add_epi32(_mm_slli_epi32(_mm_and_si128(yr, w.ratioClass), 25), w.rho));
            low = _mm_mul_ps(low, _mm_sub_ps(w.scaleLo, _mm_mul_ps(w.ratioLo, rho)));
            high = _mm_mul_ps(high, _mm_add_ps(w.scaleHi, _mm_mul_ps(w.ratioHi, rho)));
        }
        // the low bound, at least 0: a view whose lambda / tau is far
        // above the keys' subtracts more than a small reach's key holds
        const __m128 lo = _mm_max_ps(_mm_sub_ps(low, w.loErr), _mm_setzero_ps());
        const __m128 sureMask =
            _mm_cmpgt_ps(_mm_mul_ps(lo, lo), _mm_add_ps(_mm_mul_ps(d2, w.grow), w.slack));
        const __m128 hi = _mm_add_ps(high, w.yErr);
        const __m128 hi2 = _mm_mul_ps(hi, hi);
        const __m128 bound =
            _mm_sub_ps(d2, _mm_add_ps(_mm_mul_ps(w.band, _mm_add_ps(hi2, d2)), w.slack));
        // both bands at once, no branch: in 64% of the pairs on the orbit
        // case a child is a leaf and needs the second band anyway
        unsigned sure = unsigned(_mm_movemask_ps(sureMask)) & 3u;
        const unsigned decided =
            unsigned(_mm_movemask_ps(_mm_or_ps(sureMask, _mm_cmplt_ps(hi2, bound))));
        const unsigned undecided = ~decided & 3u;
        if (undecided == 0) [[likely]]
            return sure;
#else
        unsigned sure = 0, undecided = 0;
        for (unsigned c = 0; c < 2; ++c) {
            const V v = c ? vr : vl;
            const float dy = float(int32_t(key[c])) * keyYStep + keyDy0;
            const float d2 = w.xx[uint32_t(v)] + w.zz[uint32_t(v >> 32)] + dy * dy;
            const uint32_t rk = (uint32_t(key[2 + c]) << kLengthKeyShift) + keyReachBase;
            float low = std::bit_cast<float>(rk),
                  high = std::bit_cast<float>(rk + (1u << kLengthKeyShift));
            if constexpr (kScaled) {
                const float rho =
                    std::bit_cast<float>(((uint32_t(key[c]) & 3u) << 25) + ((127u - 12u) << 23));
                low *= keyScaleLo - keyRatioLo * rho;
                high *= keyScaleHi + keyRatioHi * rho;
            }
            const float lo = std::max(low - keyLowError, 0.0f);
            if (lo * lo > d2 * keyGrow + keySlack) {
                sure |= 1u << c;
                continue;
            }
            const float hi = high + keyYError;
            const float hi2 = hi * hi;
            if (!(hi2 < d2 - (0x1.0p-15f * (hi2 + d2) + keySlack))) undecided |= 1u << c;
        }
#endif
        if (undecided & 1u) sure |= unsigned(activeExact(vl));
        if (undecided & 2u) sure |= unsigned(activeExact(vr)) << 1;
        return sure;
    }

    // Split node (a, q, b) with key offset kb, depth levels above the finest
    // (kOdd: the finest level is odd, so the node's level has parity
    // kOdd ^ (depth & 1)): its children decided from their keys, each
    // that splits walked at the next level, the leaves appended. state: the
    // leaves so far times 4 plus the strip's parity + 1.
    template <bool kScaled, bool kOdd, int depth>
    Walked keyedLevel(V a, V q, V b, uint64_t kb, uint32_t* o, int64_t state) {
        const V m = (a + b) >> 1;
        const uint32_t sd = kw_.side;
        auto idx = [sd](V v) { return uint32_t(v >> 32) * sd + uint32_t(v); };
        auto put = [&](uint32_t v, int p) {
            if (v == o[-1] || v == o[-2]) return;
            if (p + 1 == int(state & 3)) {
                o[0] = o[-2];  // re-send: the strip turns
                ++o;
            } else {
                state = (state & ~int64_t(3)) | (p + 1);
            }
            *o++ = v;
        };
        auto room = [&](size_t need) {
            if (size_t(cap - o) < need) [[unlikely]] {
                out = o;
                grow(need);
                o = out;
            }
        };
        if constexpr (depth > kRoomDepth)
            room(6);  // this node's own appends
        else if constexpr (depth == kRoomDepth)
            room(size_t(4) << depth);  // the whole subtree's
        constexpr int parity = int(kOdd) ^ (depth & 1), childParity = parity ^ 1;
        if constexpr (depth >= 2) {
            if constexpr (depth - 1 > kPrefetchDepth) {
                // A prefetch never faults: no pointer is formed out of range.
                const uintptr_t p = kw_.keys + ((kb + kPair) << (kPrefetchDepth - 1)) - kPair;
                __builtin_prefetch(reinterpret_cast<const void*>(p));
                __builtin_prefetch(
                    reinterpret_cast<const void*>(p + (kPair << (kPrefetchDepth - 1)) - 1));
            }
            const unsigned act = activePair<kScaled>((a + q) >> 1, (q + b) >> 1, kb);
            if (act & 1u) {
                const Walked r =
                    keyedLevel<kScaled, kOdd, depth - 1>(a, m, q, 2 * kb + kPair, o, state);
                o = r.out;
                state = r.state;
                if constexpr (depth > kRoomDepth) room(4);
            } else {
                put(idx(m), childParity);
                state += 4;
            }
            put(idx(q), parity);
            if (act & 2u) {
                const Walked r =
                    keyedLevel<kScaled, kOdd, depth - 1>(q, m, b, 2 * kb + 2 * kPair, o, state);
                o = r.out;
                state = r.state;
            } else {
                put(idx(m), childParity);
                state += 4;
            }
        } else {  // both children lie on the finest level: leaves
            put(idx(m), childParity);
            put(idx(q), parity);
            put(idx(m), childParity);
            state += 8;
        }
        return {o, state};
    }

    using KeyedLevel = Walked (Walker::*)(V, V, V, uint64_t, uint32_t*, int64_t);
    template <bool kScaled, bool kOdd, size_t... depthLess1>
    static constexpr std::array<KeyedLevel, sizeof...(depthLess1)> keyedLevels(
        std::index_sequence<depthLess1...>) {
        return {&Walker::keyedLevel<kScaled, kOdd, int(depthLess1) + 1>...};
    }
    // keyedLevels(kDepths): keyedLevel for depth 1..kMaxKeyedDepth, at index depth - 1
    static constexpr std::make_index_sequence<kMaxKeyedDepth> kDepths{};

    // Fixed mode on the split keys: does triangle `node` (tree index, see
    // Refiner::splitKeys_) with hypotenuse (a, b) split? The exact float is read
    // only when the keys tie. kAll: epsilon < 0, every triangle splits.
    template <bool kAll>
    inline bool splits(uint64_t node, uint32_t a, uint32_t b) const {
        if constexpr (kAll) return true;
        const int32_t k = keys[node];
        return k > epsKey || (k == epsKey && err[(a + b) >> 1] > eps);
    }
    inline void leaf(uint32_t q, int l) {
        append(q, l & 1);
        ++leaves;
    }
    // Triangle `node` with entry a, apex q, exit b at level l.
    void refineKeyed(uint32_t a, uint32_t q, uint32_t b, int l, uint64_t node) {
        ensure(4);
        if (epsKey < 0) {
            if (node < splitNodes)
                descend<true>(a, q, b, l, node);
            else
                leaf(q, l);
        } else {
            if (node < splitNodes && splits<false>(node, a, b))
                descend<false>(a, q, b, l, node);
            else
                leaf(q, l);
        }
    }
    // A triangle that splits: children that are leaves are emitted here rather
    // than through a call (half of all visited triangles are leaves).
    template <bool kAll>
    void descend(uint32_t a, uint32_t q, uint32_t b, int l, uint64_t node) {
        const uint32_t m = (a + b) >> 1;
        const uint64_t left = 2 * node + 2, right = left + 1;
        const bool inner = right < splitNodes;  // children can split
        ensure(4);
        if (inner && splits<kAll>(left, a, q))
            descend<kAll>(a, m, q, l + 1, left);
        else
            leaf(m, l + 1);
        ensure(6);
        append(q, l & 1);
        if (inner && splits<kAll>(right, q, b))
            descend<kAll>(q, m, b, l + 1, right);
        else
            leaf(m, l + 1);
    }

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

// Serial recursion over the levels above the chunk level, recording ops.
template <typename W>
struct TopWalker {
    using V = typename W::V;
    static constexpr bool kView = W::kIsView;
    const W* w;  // decisions only (exact double, as the baseline)
    int chunkLevel;
    std::vector<Refiner::Op>* ops;

    void push(Refiner::Op::Kind kind, int level, unsigned mask, uint64_t a, uint64_t q, uint64_t b,
              uint64_t node = 0) {
        ops->push_back(Refiner::Op{kind, uint8_t(level), uint8_t(mask), a, q, b, node});
    }

    void refine(V a, V q, V b, int l, unsigned mask, uint64_t node) {
        if (l == chunkLevel) {
            push(Refiner::Op::kSubtree, l, mask, a, q, b, node);
            return;
        }
        if (l < w->finest) {
            const V m = (a + b) >> 1;
            const uint32_t mi = w->index(m);
            bool split;
            if constexpr (kView) {
                const uint32_t i = uint32_t(m), j = uint32_t(m >> 32);
                const double x = i * w->sx, y = double(w->height[mi]) * w->vs, z = j * w->sz;
                const float r = w->rad[mi];
                if (mask) {
                    mask = w->cull(x, y, z, r, mask);
                    if (mask == kCulled) {
                        push(Refiner::Op::kBreak, l, 0, 0, 0, 0);
                        return;
                    }
                }
                const double dx = x - w->ex, dy = y - w->ey, dz = z - w->ez;
                const double reach = w->kE * double(w->err[mi]) + double(r);
                split = reach * reach > dx * dx + dy * dy + dz * dz;
            } else {
                split = w->err[mi] > w->eps;
            }
            if (split) {
                refine(a, m, q, l + 1, mask, 2 * node + 2);
                push(Refiner::Op::kAppend, l & 1, 0, w->index(q), 0, 0);
                refine(q, m, b, l + 1, mask, 2 * node + 3);
                return;
            }
        }
        push(Refiner::Op::kLeaf, l, mask, a, q, b);
    }
};

// The first non-degenerate triangle (s[k], s[k+1], s[k+2]) of the strip
// s[0..count): its offset k and its orientation in the (i, j) plane as written
// (> 0 counter-clockwise); 0 when the strip draws nothing.
int64_t firstTriangle(const uint32_t* s, int64_t count, uint32_t side, int64_t* offset) {
    for (int64_t k = 0; k + 2 < count; ++k) {
        uint32_t v0 = s[k], v1 = s[k + 1], v2 = s[k + 2];
        if (v0 == v1 || v1 == v2 || v0 == v2) continue;
        *offset = k;
        int64_t i0 = v0 % side, j0 = v0 / side, i1 = v1 % side, j1 = v1 / side, i2 = v2 % side,
                j2 = v2 / side;
        return (i1 - i0) * (j2 - j0) - (j1 - j0) * (i2 - i0);
    }
    return 0;
}

// Joins the chunks' strips, in chunk order, into one strip mesh. Every strip
// starts with its entry vertex twice (a, a); dropping one copy flips the GL
// parity of the whole strip, which is how each strip is made to decode
// clockwise in (i, j). A strip whose entry is the previous strip's last vertex
// and whose first triangle shares an edge with the previous one (consecutive
// subtrees on the curve, no culled gap between them) continues that strip
// through degenerate triangles instead of a restart. `place` decides where each
// strip of a chunk goes (it needs only the last three indices written, kept in
// `tail`) and hands that to `emit`, which copies it at once or later.
struct StripJoin {
    uint32_t side;
    int64_t pos = 0, stripStart = 0;
    uint32_t tail[3] = {kRestartIndex, kRestartIndex,
                        kRestartIndex};  // last, second-last, third-last
    int64_t leaves = 0, culled = 0;
    int strips = 0;

    template <typename Emit>
    void place(const Refiner::Chunk& ch, Emit&& emit) {
        leaves += ch.leaves;
        culled += ch.culled;
        const uint32_t* src = ch.buffer.data() + ch.offset;
        for (size_t s = 0; s < ch.starts.size(); ++s) {
            const int64_t begin = ch.starts[s];
            const int64_t end = s + 1 < ch.starts.size() ? int64_t(ch.starts[s + 1]) - 1 : ch.used;
            int64_t k0 = 0;  // first non-degenerate triangle, relative to begin
            const int64_t g = firstTriangle(src + begin, end - begin, side, &k0);
            if (g == 0) continue;  // nothing drawn
            bool merge = false;
            if (pos - stripStart >= 3 && tail[0] == src[begin]) {
                int shared = 0;
                for (int x = 0; x < 3; ++x)
                    for (int y = 0; y < 3; ++y) shared += tail[x] == src[begin + k0 + y];
                merge = shared == 2;
            }
            // decoded clockwise iff (g > 0) == (position odd)
            const int64_t want = g > 0 ? 1 : 0;
            int64_t drop;
            bool restart = false;
            if (merge) {
                const int64_t p0 = pos - stripStart;  // where src[begin + drop] lands
                drop = ((p0 + k0 - 1) & 1) == want ? 1 : 0;
            } else {
                if (pos != 0) restart = true, ++pos;
                stripStart = pos;
                drop = (k0 & 1) == want ? 0 : 1;
                ++strips;
            }
            const uint32_t* from = src + begin + drop;
            const int64_t length = end - begin - drop;
            // the tail first: emit may move the strip over its source
            if (length >= 3) {
                tail[0] = from[length - 1], tail[1] = from[length - 2], tail[2] = from[length - 3];
            } else {
                for (int64_t k = 0; k < length; ++k)
                    tail[2] = tail[1], tail[1] = tail[0], tail[0] = from[k];
            }
            emit(Refiner::Copy{from, length, pos, restart});
            pos += length;
        }
    }
};

inline void copyStrip(uint32_t* first, const Refiner::Copy& cp) {
    if (cp.restart) first[cp.dst - 1] = kRestartIndex;
    std::memcpy(first + cp.dst, cp.src, size_t(cp.length) * sizeof(uint32_t));
}

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

float projectionLambda(float viewportHeightPx, float fovyRadians) {
    SIERRA_CHECK(viewportHeightPx > 0 && fovyRadians > 0 && fovyRadians < 3.14159f,
                 "projectionLambda: need a positive viewport height and 0 < fovy < pi, got ",
                 viewportHeightPx, " px, ", fovyRadians, " rad");
    return viewportHeightPx / (2.0f * std::tan(0.5f * fovyRadians));
}

std::array<Plane, 6> frustumPlanes(const float m[16]) {
    // row k of the matrix (column-major storage): m[k], m[4 + k], m[8 + k], m[12 + k]
    auto row = [&](int k, float out[4]) {
        for (int c = 0; c < 4; ++c) out[c] = m[4 * c + k];
    };
    float r0[4], r1[4], r2[4], r3[4];
    row(0, r0), row(1, r1), row(2, r2), row(3, r3);
    std::array<Plane, 6> planes;
    const float* rows[3] = {r0, r1, r2};
    for (int k = 0; k < 6; ++k) {
        const float* r = rows[k / 2];
        float sgn = (k & 1) ? -1.0f : 1.0f;
        Plane p{r3[0] + sgn * r[0], r3[1] + sgn * r[1], r3[2] + sgn * r[2], r3[3] + sgn * r[3]};
        float len = std::sqrt(p.a * p.a + p.b * p.b + p.c * p.c);
        if (len > 0) p = Plane{p.a / len, p.b / len, p.c / len, p.d / len};
        planes[k] = p;
    }
    return planes;
}

ViewParams lookAtView(const std::array<float, 3>& eye, const std::array<float, 3>& target,
                      float fovyRadians, float aspect, float viewportHeightPx, float nearPlane,
                      float farPlane, float tau, bool cull) {
    using V3 = std::array<double, 3>;
    auto dot = [](const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
    auto cross = [](const V3& a, const V3& b) {
        return V3{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    };
    auto normalised = [&](V3 a) {
        const double length = std::sqrt(dot(a, a));
        for (double& x : a) x /= length;
        return a;
    };
    const V3 e{eye[0], eye[1], eye[2]};
    const V3 forward{target[0] - e[0], target[1] - e[1], target[2] - e[2]};
    SIERRA_CHECK(dot(forward, forward) > 0 && std::abs(normalised(forward)[1]) < 1.0,
                 "lookAtView: the camera must look somewhere other than straight up or down");
    SIERRA_CHECK(aspect > 0 && nearPlane > 0 && farPlane > nearPlane,
                 "lookAtView: need aspect > 0 and 0 < near < far, got ", aspect, ", ", nearPlane,
                 ", ", farPlane);
    // The OpenGL look-at view (right-handed, +y up) and perspective projection
    // (clip z in [-w, w]), column-major: m[column * 4 + row].
    const V3 f = normalised(forward), side = normalised(cross(f, V3{0, 1, 0})), up = cross(side, f);
    double viewM[16] = {side[0], up[0], -f[0], 0, side[1],       up[1],       -f[1],     0,
                        side[2], up[2], -f[2], 0, -dot(side, e), -dot(up, e), dot(f, e), 1};
    const double t = std::tan(0.5 * double(fovyRadians)), n = nearPlane, fa = farPlane;
    double proj[16] = {};
    proj[0] = 1.0 / (double(aspect) * t);
    proj[5] = 1.0 / t;
    proj[10] = -(fa + n) / (fa - n);
    proj[11] = -1.0;
    proj[14] = -2.0 * fa * n / (fa - n);
    float vp[16];
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            double sum = 0;
            for (int k = 0; k < 4; ++k) sum += proj[k * 4 + r] * viewM[c * 4 + k];
            vp[c * 4 + r] = float(sum);
        }
    ViewParams view;
    view.eye = eye;
    view.lambda = projectionLambda(viewportHeightPx, fovyRadians);
    view.tau = tau;
    view.cull = cull;
    view.planes = frustumPlanes(vp);
    return view;
}

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

// Calls visit(node, m) for every triangle of levels 0..2n-1 (tree index, linear
// index of its split vertex): a top-down pass over the whole tree, subtrees at
// a fixed level spread over the threads.
template <typename Visit>
void Refiner::forEachNode(Visit&& visit) {
    const uint64_t nodes = (uint64_t(2) << (2 * n_)) - 2;
    auto fill = [&](auto&& self, uint32_t a, uint32_t q, uint32_t b, uint64_t node) -> void {
        if (node >= nodes) return;
        const uint32_t m = (a + b) >> 1;
        visit(node, m);
        self(self, a, m, q, 2 * node + 2);
        self(self, q, m, b, 2 * node + 3);
    };
    // the top levels serially, recording the triangles of level `cut`
    const int cut = std::min(2 * n_ - 1, 6);
    struct Sub {
        uint32_t a, q, b;
        uint64_t node;
    };
    std::vector<Sub> subs;
    auto top = [&](auto&& self, uint32_t a, uint32_t q, uint32_t b, int l, uint64_t node) -> void {
        if (l == cut) {
            subs.push_back({a, q, b, node});
            return;
        }
        const uint32_t m = (a + b) >> 1;
        visit(node, m);
        self(self, a, m, q, l + 1, 2 * node + 2);
        self(self, q, m, b, l + 1, 2 * node + 3);
    };
    const uint32_t side = uint32_t(side_), S = side - 1;
    top(top, 0, S * side, S * side + S, 0, 0);
    top(top, S * side + S, S, 0, 0, 1);
    parallelChunks(
        0, int64_t(subs.size()), int(subs.size()),
        [&](int64_t lo, int64_t hi, int) {
            for (int64_t k = lo; k < hi; ++k)
                fill(fill, subs[k].a, subs[k].q, subs[k].b, subs[k].node);
        },
        threads_ > 0 ? threads_ : defaultThreadCount());
}

// Keys of every triangle of levels 0..2n-1 in tree order.
void Refiner::buildSplitKeys() {
    const float* err = errors_->error.data();
    for (float e : errors_->error)
        if (std::isnan(e) || std::signbit(e)) return;  // keys would not be monotone: exact path
    const uint64_t nodes = (uint64_t(2) << (2 * n_)) - 2;
    splitKeys_.resize(nodes);
    uint16_t* keys = splitKeys_.data();
    forEachNode([&](uint64_t node, uint32_t m) { keys[node] = uint16_t(floatKey(err[m])); });
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

// The largest magnitude of a world coordinate or radius of the grid: the scale
// of the fast view path's float slack.
void Refiner::measureMagnitude() {
    const size_t count = size_t(side_) * side_;
    const float* h = field_->samples().data();
    const float* r = errors_->radius.data();
    const double vs = std::fabs(double(field_->verticalScale()));
    double maxAbs = 0.0;
    for (size_t k = 0; k < count; ++k)
        maxAbs = std::max({maxAbs, std::fabs(double(h[k])) * vs, double(r[k])});
    magnitude_ = std::max(
        {maxAbs, double(side_ - 1) * field_->spacingX(), double(side_ - 1) * field_->spacingZ()});
}

namespace {
// The 16-bit height key nearest to q (the height in steps above the base)
// whose low 2 bits are `ratioClass` (see viewKeys_).
inline uint16_t heightKey(double q, uint32_t ratioClass) {
    const double k = std::clamp((q - double(ratioClass)) * 0.25 + 0.5, 0.0, 16383.0);
    return uint16_t(uint32_t(k) * 4 + ratioClass);  // k >= 0: truncation rounds to the nearest
}
}  // namespace

// The height scale of the view keys (see viewKeys_), and the largest distance
// between a decoded height (in float, as the walker decodes it) and the exact
// world height (in double, as the baseline computes it) over every sample and
// every ratio class; the keys themselves are written by buildReachKeys.
void Refiner::buildViewKeys() {
    const size_t count = size_t(side_) * side_;
    const float* h = field_->samples().data();
    const float* err = errors_->error.data();
    const float* rad = errors_->radius.data();
    float lo = h[0], hi = h[0];
    for (size_t k = 0; k < count; ++k) {
        if (!std::isfinite(h[k]) || !(err[k] >= 0.0f) || !(rad[k] >= 0.0f) ||
            std::signbit(err[k]) || std::signbit(rad[k]) || !std::isfinite(rad[k]) ||
            !std::isfinite(err[k]))
            return;  // keys would not bound the exact values: exact path only
        lo = std::min(lo, h[k]), hi = std::max(hi, h[k]);
    }
    const double vs = field_->verticalScale();
    const float base = float(double(lo) * vs);
    const float step = float((double(hi) - double(lo)) * vs / 65535.0);
    if (!std::isfinite(base) || !std::isfinite(step)) return;
    const double inverse = step != 0.0f ? 1.0 / double(step) : 0.0;
    double worst = 0.0;
    for (size_t k = 0; k < count; ++k) {
        const double exact = double(h[k]) * vs;
        const double q = (exact - double(base)) * inverse;
        for (uint32_t c = 0; c < 4; ++c) {
            const float decoded = base + float(int32_t(heightKey(q, c))) * step;
            worst = std::max(worst, std::fabs(double(decoded) - exact));
        }
    }
    keyYBase_ = base, keyYStep_ = step;
    keyYError_ =
        std::nextafter(float(worst * (1.0 + 0x1.0p-20)), std::numeric_limits<float>::infinity());
    const uint64_t nodes = (uint64_t(2) << (2 * n_)) - 2;
    viewKeys_.assign(2 * nodes, 0);
    keyReachFactor_ = 0.0;
}

// The view keys of every triangle (see viewKeys_) for lambda / tau = kE: the
// reach kE * e + r in double, as the baseline computes it, rounded towards
// zero to a float, so that a key's float is at most the reach and the next
// key's float above it; the height with the vertex's ratio class.
void Refiner::buildReachKeys(double kE) {
    const size_t count = size_t(side_) * side_;
    const float* h = field_->samples().data();
    const float* err = errors_->error.data();
    const float* rad = errors_->radius.data();
    const double vs = field_->verticalScale();
    const double inverse = keyYStep_ != 0.0f ? 1.0 / double(keyYStep_) : 0.0;
    const int threads = threads_ > 0 ? threads_ : defaultThreadCount();
    // A sample's reach, and the float no larger than it: roundDown for a
    // reach >= 0, the next float towards zero taken as the bit pattern one
    // lower rather than by nextafterf (whose call was most of a rebuild).
    struct Reach {
        double exact;
        float below;
    };
    auto reachOf = [&](size_t k) {
        const double r = kE * double(err[k]) + double(rad[k]);
        const float f = float(r);
        return Reach{r, std::bit_cast<float>(std::bit_cast<uint32_t>(f) - uint32_t(double(f) > r))};
    };
    std::vector<float> largest(size_t(side_), 0.0f);
    parallelFor(
        0, side_,
        [&](int64_t row) {
            const size_t j = size_t(row);
            float rowLargest = 0.0f;
            for (size_t k = j * side_, e = k + side_; k < e; ++k)
                rowLargest = std::max(rowLargest, reachOf(k).below);
            largest[j] = rowLargest;
        },
        threads);
    keyReachBase_ = lengthKeyBase(*std::max_element(largest.begin(), largest.end()));
    // Per sample both keys (height | reach << 16), then gathered in tree
    // order: 4 bytes a sample rather than the height, error and radius (12).
    std::vector<uint32_t> sampleKeys(count);
    parallelFor(
        0, side_,
        [&](int64_t row) {
            const size_t j = size_t(row);
            for (size_t k = j * side_, rowEnd = k + side_; k < rowEnd; ++k) {
                const Reach reach = reachOf(k);
                // the ratio class: the smallest c with radius <= 2^(-12 + 4 c) reach
                const double r = double(rad[k]), e = reach.exact;
                const uint32_t c = uint32_t(r > e * 0x1.0p-12) + uint32_t(r > e * 0x1.0p-8) +
                                   uint32_t(r > e * 0x1.0p-4);
                const double q = (double(h[k]) * vs - double(keyYBase_)) * inverse;
                sampleKeys[k] = uint32_t(heightKey(q, c)) |
                                uint32_t(lengthKey(reach.below, keyReachBase_)) << 16;
            }
        },
        threads);
    uint16_t* keys = viewKeys_.data();
    forEachNode([&](uint64_t node, uint32_t m) {
        uint16_t* pair = keys + 4 * (node >> 1) + (node & 1);
        const uint32_t both = sampleKeys[m];
        pair[0] = uint16_t(both);
        pair[2] = uint16_t(both >> 16);
    });
    keyReachFactor_ = kE;
    otherReachCount_ = 0;
}

void Refiner::prepareView(double lambdaOverTau) {
    if (magnitude_ < 0.0) {
        measureMagnitude();
        buildViewKeys();
    }
    if (!viewKeys_.empty() && keyReachFactor_ == 0.0 && lambdaOverTau > 0.0 &&
        std::isfinite(lambdaOverTau))
        buildReachKeys(lambdaOverTau);
}

size_t Refiner::keyBytes() const {
    return (splitKeys_.size() + viewKeys_.size()) * sizeof(uint16_t);
}

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

template <bool kView, bool kFast>
void Refiner::run(const ViewParams* view, float epsilon, StripMesh& out) {
    using W = Walker<kView, kFast>;
    using V = typename W::V;
    static_assert(std::is_trivially_copyable_v<W> && sizeof(W) <= sizeof(Frame::walker));
    // The frame a helper of the last refinement may still read is left alone.
    int frameIndex = 0;
    // A helper of the last refinement may still be leaving it: it has finished
    // its last copy a moment before, or stops within kStopEvery indices of a
    // chunk the caller ran again. Worth a short wait: 6 of 200 refinements of
    // a full 2049^2 grid on 2 threads found one there without it, none with
    // it; a refinement that finds one takes the other frame on one thread.
    const bool helperBusy = busyFrame_ >= 0 && !parallelHelpersIdleWithin(kHelperSettleSeconds);
    if (helperBusy)
        frameIndex = 1 - busyFrame_;
    else
        busyFrame_ = -1;
    if (!frames_[frameIndex]) frames_[frameIndex] = std::make_unique<Frame>();
    Frame& frame = *frames_[frameIndex];
    W proto{};
    proto.err = errors_->error.data();
    proto.rad = errors_->radius.data();
    proto.height = field_->samples().data();
    proto.side = uint32_t(side_);
    proto.finest = 2 * n_;
    proto.eps = epsilon;
    proto.epsKey = epsilonKey(epsilon);
    proto.keys = splitKeys_.empty() ? nullptr : splitKeys_.data();
    proto.splitNodes = splitKeys_.size();
    unsigned rootMask = 0;
    if constexpr (kView) {
        proto.ex = view->eye[0], proto.ey = view->eye[1], proto.ez = view->eye[2];
        proto.sx = field_->spacingX(), proto.sz = field_->spacingZ();
        proto.vs = field_->verticalScale();
        proto.kE = double(view->lambda) / double(view->tau);
        for (int k = 0; k < 6; ++k) proto.planes[k] = view->planes[k];
        rootMask = view->cull ? kAllPlanes : 0;
        if constexpr (kFast) {
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
            // Keyed path (Walker::activeKeyed): the key bounds are rounded in
            // float like the exact operands, to within 2^-21 of the reach plus
            // keyYError; keyYError is at most M / 65535, so its square is far
            // below distanceSlack and the same slack covers both.
            if (!viewKeys_.empty()) {
                // The reaches are made for the first view's lambda / tau, and
                // again once kReachRebuildAfter refinements in a row asked for
                // one other (a viewport, field of view or tau that changed and
                // stays): a rebuild costs about ten refinements, and the keys
                // of another factor still decide most vertices.
                // A helper of the last refinement may still read the keys
                // (once they have reaches: the first build has no reader).
                auto rebuild = [&] {
                    if (keyReachFactor_ != 0.0 && busyFrame_ >= 0) {
                        waitParallelHelpers();
                        busyFrame_ = -1;
                    }
                    buildReachKeys(proto.kE);
                };
                if (keyReachFactor_ == 0.0) {
                    rebuild();
                } else if (proto.kE == keyReachFactor_) {
                    otherReachCount_ = 0;
                } else {
                    otherReachCount_ = proto.kE == otherReachFactor_ ? otherReachCount_ + 1 : 1;
                    otherReachFactor_ = proto.kE;
                    if (otherReachCount_ >= kReachRebuildAfter) rebuild();
                }
                proto.viewKeys = viewKeys_.data();
                proto.keyYBase = keyYBase_, proto.keyYStep = keyYStep_,
                proto.keyYError = keyYError_;
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
                proto.keyLowError = std::nextafter(float(below * (1.0 + 0x1.0p-20)),
                                                   std::numeric_limits<float>::infinity());
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
        }
    }

    // Vertices of the two level-0 triangles: entry (0,0), apex (0,S), exit (S,S);
    // entry (S,S), apex (S,0), exit (0,0).
    const uint32_t S = uint32_t(side_ - 1);
    auto vert = [&](uint32_t i, uint32_t j) -> V {
        if constexpr (kView)
            return V(i) | (V(j) << 32);
        else
            return j * uint32_t(side_) + i;
    };
    const V v00 = vert(0, 0), v0S = vert(0, S), vSS = vert(S, S), vS0 = vert(S, 0);

    std::vector<Op>& ops = frame.ops;
    ops.clear();
    TopWalker<W> top{&proto, chunkLevel_, &ops};
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
    const int chunkCount = int(cuts.size()) - 1;
    std::memcpy(frame.walker, &proto, sizeof(W));
    // Per subtree at the chunk level, the triangles it made last time (its
    // tree node at the chunk level identifies it).
    std::vector<int64_t>& work = kView ? viewChunkWork_ : fixedChunkWork_;
    const uint64_t levelFirst =
        (uint64_t(2) << chunkLevel_) - 2;  // first tree node of the chunk level
    // Chunk c's place in `work`: its subtree's index within the chunk level
    // (UINT64_MAX when the chunk holds no subtree).
    auto workSlot = [&](int c) -> uint64_t {
        for (size_t k = cuts[size_t(c)]; k < cuts[size_t(c) + 1]; ++k)
            if (ops[k].kind == Op::kSubtree) return ops[k].node - levelFirst;
        return UINT64_MAX;
    };

    // Threads earn their keep: a refinement that made fewer than
    // kParallelTriangles triangles last time in this mode runs serially. One
    // thread does that many in 1.3-2.6 ms (50-100 M triangles/s); a helper
    // could save at most half of it but, on a busy machine, can cost a whole
    // scheduler time slice (3-6 ms) when it is preempted inside a chunk.
    int threads = threads_ > 0 ? threads_ : defaultThreadCount();
    int64_t& lastTriangles = kView ? lastViewTriangles_ : lastFixedTriangles_;
    if (lastTriangles >= 0 && lastTriangles < kParallelTriangles) threads = 1;
    ThreadChoice& choice = kView ? viewThreads_ : fixedThreads_;
    const bool adaptive = threads_ <= 0 && threads > 1;
    if (adaptive && choice.serial()) threads = 1;
    // A helper of the last refinement is still inside a chunk (preempted, or
    // finishing a chunk the caller ran again): this refinement runs on one
    // thread, through the other frame's one small buffer. The pool would most
    // likely run it serially anyway (it does while a helper is busy), but on
    // that frame's chunk buffers, which may never have been grown: a full
    // 2049^2 grid's 56 MB, faulted in, took 155 ms where one thread takes 30.
    // So the other frame never holds chunk strips.
    if (helperBusy) threads = 1;
    const auto started = std::chrono::steady_clock::now();
    StripJoin join{uint32_t(side_)};
    std::vector<int64_t>& chunkLeaves = frame.chunkLeaves;
    chunkLeaves.resize(size_t(chunkCount));
    bool pooled = false;
    if (threads == 1) {
        // One thread: the chunks write their strips straight into the
        // output, one after the other, and each is joined where it lies: a
        // strip moves down by the indices the join drops before it (a
        // restart between merged strips, an entry vertex dropped for the
        // winding), within data still in the cache, and not at all when
        // none are. Each chunk starts one index past the joined output, so
        // a strip never moves up. The output is first made as large as what
        // the last refinement in this mode wrote, and a little more, as far
        // as it holds without reallocating, then grows by a quarter whenever
        // a chunk needs it (growBuffer).
        const int64_t lastIndices = kView ? lastViewIndices_ : lastFixedIndices_;
        const size_t guess = size_t(lastIndices + lastIndices / 32 + 4096);
        Chunk& chunk = frame.serialChunk;
        std::vector<uint32_t>& v = chunk.buffer;
        v.swap(out.indices);
        if (v.size() < guess) v.resize(std::max(v.size(), std::min(guess, v.capacity())));
        chunk.isOutput = true;
        W w;
        for (int c = 0; c < chunkCount; ++c) {
            chunk.offset = size_t(join.pos) + 1;
            std::memcpy(&w, frame.walker, sizeof(W));
            w.bind(chunk, nullptr);
            w.execute(ops.data() + cuts[size_t(c)], ops.data() + cuts[size_t(c) + 1]);
            w.finish();
            chunkLeaves[size_t(c)] = chunk.leaves;
            uint32_t* const first = v.data();
            join.place(chunk, [first](const Copy& cp) {
                if (cp.restart) first[cp.dst - 1] = kRestartIndex;
                if (cp.src != first + cp.dst)
                    std::memmove(first + cp.dst, cp.src, size_t(cp.length) * sizeof(uint32_t));
            });
        }
        v.resize(size_t(join.pos));
        v.swap(out.indices);
    } else {
        for (std::vector<Chunk>& slot : frame.chunks)
            if (slot.size() < size_t(chunkCount)) slot.resize(size_t(chunkCount));
        frame.winners.resize(size_t(chunkCount));
        frame.slotOf.resize(size_t(chunkCount));
        // Largest chunks first, by the triangles each subtree made last time:
        // the chunks left at the end, which a preempted helper may hold or the
        // caller run twice, are the small ones. The output does not depend on
        // the order.
        auto workOf = [&](int c) -> int64_t {
            const uint64_t slot = workSlot(c);
            return slot < work.size() ? work[slot] : 0;
        };
        frame.order.resize(size_t(chunkCount));
        for (int c = 0; c < chunkCount; ++c) frame.order[size_t(c)] = c;
        if (!work.empty())
            std::stable_sort(frame.order.begin(), frame.order.end(),
                             [&](int x, int y) { return workOf(x) > workOf(y); });
        // Chunks a preempted helper holds are run again by the caller
        // (parallelRescuedChunks): the join never waits for a helper. The
        // body reads only the frame, which outlives the call.
        Frame* const f = &frame;
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
            busyFrame_ = -1;
            throw;
        }
        if (pooled) busyFrame_ = frameIndex;
        for (int u = 0; u < chunkCount; ++u)
            frame.slotOf[size_t(frame.order[size_t(u)])] = frame.winners[size_t(u)];
        // Then the join: a serial pass decides every strip's place, and the
        // copies run in parallel (on a full 2049^2 grid they move 56 MB, a
        // seventh of a thread's refinement time).
        copies_.clear();
        for (int c = 0; c < chunkCount; ++c) {
            const Chunk& ch = frame.chunks[frame.slotOf[size_t(c)]][size_t(c)];
            chunkLeaves[size_t(c)] = ch.leaves;
            join.place(ch, [&](const Copy& cp) { copies_.push_back(cp); });
        }
        // room for a refinement on one thread of the same size (see above),
        // growing by a quarter at least
        const size_t room = size_t(join.pos + join.pos / 32 + 4096);
        if (out.indices.capacity() < room)
            out.indices.reserve(
                std::max(room, out.indices.capacity() + out.indices.capacity() / 4));
        out.indices.resize(size_t(join.pos));
        uint32_t* const first = out.indices.data();
        const int64_t copyCount = int64_t(copies_.size());
        // A copy cannot be run twice (it writes the caller's output), so a helper
        // preempted inside one holds the join: only copies of at least 2^22 indices
        // (16 MB, 1-3 ms of one thread) are shared.
        parallelChunks(
            0, copyCount, int(std::min<int64_t>(copyCount, 256)),
            [&](int64_t lo, int64_t hi, int) {
                for (int64_t k = lo; k < hi; ++k) copyStrip(first, copies_[size_t(k)]);
            },
            join.pos >= (int64_t(1) << 22) ? threads : 1);
    }
    const int64_t leaves = join.leaves;
    out.triangleCount = leaves;
    out.stripCount = join.strips;
    out.culledSubtrees = join.culled;
    out.threads = pooled ? threads : 1;
    lastTriangles = leaves;
    (kView ? lastViewIndices_ : lastFixedIndices_) = join.pos;
    if (adaptive)
        choice.record(
            pooled,  // false: one thread (chosen, forced by a busy helper, or the pool's)
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
            leaves);
    // Each subtree's triangles, for the next refinement's chunk order (levels
    // up to 12: at most 8192 subtrees).
    if (chunkLevel_ <= 12) {
        work.assign(size_t(2) << chunkLevel_, 0);
        for (int c = 0; c < chunkCount; ++c)
            if (const uint64_t slot = workSlot(c); slot < work.size())
                work[size_t(slot)] = chunkLeaves[size_t(c)];
    }
}

std::vector<std::array<uint32_t, 3>> decodeStrip(const std::vector<uint32_t>& indices) {
    std::vector<std::array<uint32_t, 3>> tris;
    tris.reserve(indices.size());
    size_t begin = 0;
    while (begin < indices.size()) {
        size_t end = begin;
        while (end < indices.size() && indices[end] != kRestartIndex) ++end;
        for (size_t k = begin; k + 2 < end; ++k) {
            uint32_t v0 = indices[k], v1 = indices[k + 1], v2 = indices[k + 2];
            if (v0 == v1 || v1 == v2 || v0 == v2) continue;
            if ((k - begin) & 1) std::swap(v0, v1);
            tris.push_back({v0, v1, v2});
        }
        begin = end + 1;
    }
    return tris;
}

int64_t countDistinctVertices(const std::vector<uint32_t>& indices, int side) {
    std::vector<uint8_t> seen(size_t(side) * side, 0);
    int64_t count = 0;
    for (uint32_t v : indices) {
        if (v == kRestartIndex) continue;
        SIERRA_CHECK(v < seen.size(), "countDistinctVertices: index ", v, " outside a ", side, "x",
                     side, " grid");
        count += !seen[v];
        seen[v] = 1;
    }
    return count;
}

double maxVerticalDistance(const terrain::Heightfield& field,
                           const std::vector<std::array<uint32_t, 3>>& triangles, int threads) {
    const int side = field.width();
    const int64_t chunks =
        std::max<int64_t>(1, std::min<int64_t>(int64_t(triangles.size()) / 4096 + 1, 256));
    std::vector<double> best(size_t(chunks), 0.0);
    parallelChunks(
        0, int64_t(triangles.size()), int(chunks),
        [&](int64_t lo, int64_t hi, int c) {
            double worst = 0.0;
            for (int64_t t = lo; t < hi; ++t) {
                int vi[3], vj[3];
                double vh[3];
                for (int k = 0; k < 3; ++k) {
                    vi[k] = int(triangles[t][k] % uint32_t(side));
                    vj[k] = int(triangles[t][k] / uint32_t(side));
                    vh[k] = field.worldHeight(vi[k], vj[k]);
                }
                const int64_t det = int64_t(vi[1] - vi[0]) * (vj[2] - vj[0]) -
                                    int64_t(vj[1] - vj[0]) * (vi[2] - vi[0]);
                if (det == 0) continue;
                const int i0 = std::min({vi[0], vi[1], vi[2]}),
                          i1 = std::max({vi[0], vi[1], vi[2]});
                const int j0 = std::min({vj[0], vj[1], vj[2]}),
                          j1 = std::max({vj[0], vj[1], vj[2]});
                for (int j = j0; j <= j1; ++j)
                    for (int i = i0; i <= i1; ++i) {
                        // barycentric coordinates (exact integers)
                        int64_t w1 = int64_t(i - vi[0]) * (vj[2] - vj[0]) -
                                     int64_t(j - vj[0]) * (vi[2] - vi[0]);
                        int64_t w2 = int64_t(vi[1] - vi[0]) * (j - vj[0]) -
                                     int64_t(vj[1] - vj[0]) * (i - vi[0]);
                        int64_t w0 = det - w1 - w2;
                        bool inside = det > 0 ? (w0 >= 0 && w1 >= 0 && w2 >= 0)
                                              : (w0 <= 0 && w1 <= 0 && w2 <= 0);
                        if (!inside) continue;
                        double hMesh =
                            (double(w0) * vh[0] + double(w1) * vh[1] + double(w2) * vh[2]) /
                            double(det);
                        worst = std::max(worst, std::fabs(double(field.worldHeight(i, j)) - hMesh));
                    }
            }
            best[size_t(c)] = worst;
        },
        threads);
    return *std::max_element(best.begin(), best.end());
}

}  // namespace sierra::sbt
