#pragma once
// The reference walk (private to the sbt module; see Walker.h for its
// siblings): Walker::refine, the SBT recursion with every decision as the
// definition states it, in double on the three separate arrays (height,
// error, radius). refineViewReference and fixed mode without split keys take
// it; the other walks must make the same decisions. TopWalker is the serial
// top of every refinement: the same decisions above the chunk level,
// recorded as ops (Refiner::Op) for the chunks to run.

#include "sbt/Walker.h"

#include <vector>

namespace sierra::sbt {
namespace {

// Sphere of vertex m against the planes still in `mask`: kCulled when fully
// outside one, else the planes it still straddles.
template <bool kView, bool kFast>
inline unsigned Walker<kView, kFast>::cull(double x, double y, double z, float r,
                                           unsigned mask) const {
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
template <bool kView, bool kFast>
inline void Walker<kView, kFast>::refine(V a, V q, V b, int l, unsigned mask) {
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

}  // namespace
}  // namespace sierra::sbt
