#pragma once
// Fixed mode on the split keys (private to the sbt module; see Walker.h for
// its siblings): Walker::refineKeyed, refineFixed's walk once the split keys
// exist (Refiner::splitKeys_, encoding in Keys.h): a triangle splits when its
// key is above epsilon's, the exact float read only when the keys tie; the
// keys lie in tree order, so each level is read front to back.

#include "sbt/Walker.h"

namespace sierra::sbt {
namespace {

// Fixed mode on the split keys: does triangle `node` (tree index, see
// Refiner::splitKeys_) with hypotenuse (a, b) split? The exact float is read
// only when the keys tie. kAll: epsilon < 0, every triangle splits.
template <bool kView, bool kFast>
template <bool kAll>
inline bool Walker<kView, kFast>::splits(uint64_t node, uint32_t a, uint32_t b) const {
    if constexpr (kAll) return true;
    const int32_t k = keys[node];
    return k > epsKey || (k == epsKey && err[(a + b) >> 1] > eps);
}

template <bool kView, bool kFast>
inline void Walker<kView, kFast>::leaf(uint32_t q, int l) {
    append(q, l & 1);
    ++leaves;
}

// Triangle `node` with entry a, apex q, exit b at level l.
template <bool kView, bool kFast>
inline void Walker<kView, kFast>::refineKeyed(uint32_t a, uint32_t q, uint32_t b, int l,
                                              uint64_t node) {
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
template <bool kView, bool kFast>
template <bool kAll>
inline void Walker<kView, kFast>::descend(uint32_t a, uint32_t q, uint32_t b, int l,
                                          uint64_t node) {
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

}  // namespace
}  // namespace sierra::sbt
