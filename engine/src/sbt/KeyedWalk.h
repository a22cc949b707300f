#pragma once
// The keyed view walk (private to the sbt module; see Walker.h for its
// siblings): Walker::walkKeyed, refineView's walk below a triangle whose
// sphere lies inside every frustum plane, one function per level
// (keyedLevel), both children of a node decided at once from their view keys
// (activePair; Refiner::viewKeys_, encodings in Keys.h), the few the keys
// leave undecided by the fast walk's exact test (activeExact). Its appends go
// through the strip writer (StripWriter.h) with the parity packed into the
// state it hands back.

#include "sbt/Walker.h"

#include <algorithm>
#include <bit>
#include <cstring>

namespace sierra::sbt {
namespace {

// activePair's exact fallback, out of line: the keyed walk's common path
// makes no call but the next level's.
template <bool kView, bool kFast>
[[gnu::noinline]] bool Walker<kView, kFast>::activeExact(V m) const {
    const uint32_t i = uint32_t(m), j = uint32_t(m >> 32);
    const uint32_t mi = j * side + i;
    return activeFast(i, j, float(i) * fsx, height[mi] * fvs, float(j) * fsz, err[mi], rad[mi]);
}

// The keyed walk's functions by depth (kDepths: keyedLevel<depth> at index depth - 1).
template <bool kView, bool kFast>
template <bool kScaled, bool kOdd, size_t... depthLess1>
constexpr auto Walker<kView, kFast>::keyedLevels(std::index_sequence<depthLess1...>)
    -> std::array<KeyedLevel, sizeof...(depthLess1)> {
    return {&Walker::keyedLevel<kScaled, kOdd, int(depthLess1) + 1>...};
}

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
template <bool kView, bool kFast>
template <bool kScaled>
inline void Walker<kView, kFast>::walkKeyed(V a, V q, V b, int l, uint64_t node) {
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

// Both children of tree node k (key offset kb) at once: bit 0 left (split
// vertex vl), bit 1 right (vr). Each lane computes the same float
// operations in the same order as one child's scalar test; the vertices
// in neither sure band go to activeExact.
template <bool kView, bool kFast>
template <bool kScaled>
[[gnu::always_inline]] inline unsigned Walker<kView, kFast>::activePair(V vl, V vr,
                                                                        uint64_t kb) const {
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
template <bool kView, bool kFast>
template <bool kScaled, bool kOdd, int depth>
inline auto Walker<kView, kFast>::keyedLevel(V a, V q, V b, uint64_t kb, uint32_t* o, int64_t state)
    -> Walked {
    const V m = (a + b) >> 1;
    const uint32_t sd = kw_.side;
    auto idx = [sd](V v) { return uint32_t(v >> 32) * sd + uint32_t(v); };
    auto put = [&](uint32_t v, int p) { appendToStrip(o, v, p, PackedStripParity{state}); };
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

}  // namespace
}  // namespace sierra::sbt
