// The refiner's keys (Refiner.h, private members): the split keys of fixed
// mode and the view keys of view mode, built once per refiner (the reach
// keys again when lambda / tau changes for good, see Refiner.cpp), in tree
// order by a top-down pass over the whole tree (forEachNode). The encodings
// are in Keys.h; the walks that read them in SplitKeyWalk.h and KeyedWalk.h.
#include <sierra/sbt/Refiner.h>

#include "sbt/Keys.h"

#include <sierra/core/Parallel.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <vector>

namespace sierra::sbt {

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

}  // namespace sierra::sbt
