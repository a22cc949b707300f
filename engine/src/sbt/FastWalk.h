#pragma once
// The fast view walk (private to the sbt module; see Walker.h for its
// siblings): Walker::node and Walker::split, refineView's walk while a
// triangle's sphere still straddles a frustum plane, or while its subtree is
// deeper than the keyed walk goes. Below a sphere inside every plane it hands
// the subtree to the keyed walk (KeyedWalk.h).
//
// The same decisions as refine() (the double-precision baseline), taken in
// float where the float result is certain: a float value v of a quantity
// computed exactly as w in double satisfies |v - w| <= slack (bounds in
// Refiner::setUpWalker), so a comparison whose float margin exceeds the slack has
// the same outcome in double; the few inside the band are recomputed in
// double. The children's data are prefetched while the parent is decided.
// (An interleaved 12-byte record per vertex, one cache line instead of
// three, was measured no faster on the orbit case and cost 12 bytes per
// sample: not kept.)

#include "sbt/Walker.h"

namespace sierra::sbt {
namespace {

// Plane tests of vertex m's sphere, in float with a double fallback.
template <bool kView, bool kFast>
inline unsigned Walker<kView, kFast>::cullFast(uint32_t i, uint32_t j, float x, float y, float z,
                                               float r, unsigned mask) const {
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
template <bool kView, bool kFast>
inline bool Walker<kView, kFast>::activeFast(uint32_t i, uint32_t j, float x, float y, float z,
                                             float e, float r) const {
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

template <bool kView, bool kFast>
inline void Walker<kView, kFast>::prefetch(V v) const {
    const uint32_t i = uint32_t(v), j = uint32_t(v >> 32);
    const size_t mi = j * side + i;
    __builtin_prefetch(height + mi);
    __builtin_prefetch(err + mi);
    __builtin_prefetch(rad + mi);
}

// Leaf at level l with apex q (entry a): what refine() does for a leaf.
template <bool kView, bool kFast>
inline void Walker<kView, kFast>::leafFast(V a, V q, int l) {
    if (needStart) start(index(a));
    ensure(4);
    append(index(q), l & 1);
    ++leaves;
}

// Triangle (a, q, b) at level l < finest: culled, a leaf, or split. Its
// children are decided here too (node() is inlined into split()), so a
// call is made only for a child that splits: half of the visited
// triangles are leaves.
template <bool kView, bool kFast>
inline void Walker<kView, kFast>::node(V a, V q, V b, int l, unsigned mask, uint64_t k) {
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

template <bool kView, bool kFast>
inline void Walker<kView, kFast>::split(V a, V q, V b, int l, unsigned mask, V m, uint64_t k) {
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

}  // namespace
}  // namespace sierra::sbt
