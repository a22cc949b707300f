#include "ReliefSweep.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace sierra::analysis::relief {

namespace {
// True when point b lies on or below the line from p to c, with t_p < t_b and
// t_p < t_c: then b cannot be the horizon of p or of any point before it.
inline bool notAbove(const Profile& P, int p, int b, int c) {
    const double hp = P.h[p], tp = P.t[p];
    return (double(P.h[b]) - hp) * (P.t[c] - tp) <= (double(P.h[c]) - hp) * (P.t[b] - tp);
}
// Projected slopes of p -> q and p -> c compared: true when q is strictly higher.
inline bool steeper(const Profile& P, int p, int q, int c) {
    return !notAbove(P, p, q, c);
}

}  // namespace

// The horizon slope of every receiving point from its tangent point: the
// height difference over the true horizontal distance sqrt(dt^2 + dw^2).
void finishSlopes(Profile& P) {
    for (int k = 0; k < P.n; ++k) {
        if (!(P.flags[k] & kReceive)) {
            P.slope[k] = kNaN;
            continue;
        }
        const int q = P.best[k];
        if (q < 0) {
            P.slope[k] = kNoOccluder;
            continue;
        }
        const double dt = P.t[q] - P.t[k], dw = P.w[q] - P.w[k];
        P.slope[k] = float((double(P.h[q]) - double(P.h[k])) / std::sqrt(dt * dt + dw * dw));
    }
}

// With a radius R the occluders of p are the points q with 0 < t_q - t_p <= R.
// A vertex popped from the hull may return once the vertex that hid it moves
// out of range, so the profile is cut into blocks of length R in t (block b:
// t_0 - t in [bR, (b+1)R)). p's occluders are then (a) every point ahead of it
// in its own block and (b) a part of the previous block nearest to p's block:
// its points with t_q <= t_p + R, a set that grows as p moves back towards the
// previous block. (a) is the sweep above with the stack emptied at each block
// start (amortised O(1) per point); (b) is an upper hull built by adding the
// previous block's points in increasing t as p walks its own block in
// increasing t (amortised O(1)), queried by binary search for the tangent
// (O(log hull size)). The whole sweep is O(n log n) at worst and near O(n) on
// terrain, whose profile hulls are short.
void sweepRadius(Profile& P, double radius) {
    const int n = P.n;
    if (n == 0) return;
    const double t0 = P.t[0];
    auto block = [&](int k) { return int64_t(std::floor((t0 - P.t[k]) / radius)); };
    int* stack = P.stack.data();
    int* hull = P.hull.data();
    int prevBegin = -1, prevEnd = -1;  // the previous block's points [begin, end)
    int64_t prevBlock = -2;
    for (int begin = 0; begin < n;) {
        const int64_t b = block(begin);
        int end = begin + 1;
        while (end < n && block(end) == b) ++end;
        // (a) the own block
        int top = 0;
        for (int k = begin; k < end; ++k) {
            const uint8_t f = P.flags[k];
            if (!f) continue;
            while (top >= 2 && notAbove(P, k, stack[top - 1], stack[top - 2])) --top;
            P.best[k] = top ? stack[top - 1] : -1;
            if (f & kCast) stack[top++] = k;
        }
        // (b) the previous block, if it is the adjacent one
        if (prevBlock == b - 1) {
            int size = 0;
            int q = prevEnd - 1;  // the previous block's nearest point
            for (int k = end - 1; k >= begin; --k) {
                if (!(P.flags[k] & kReceive)) continue;
                const double reach = P.t[k] + radius;
                for (; q >= prevBegin && P.t[q] <= reach; --q) {
                    if (!(P.flags[q] & kCast)) continue;
                    // hull[] runs in increasing t; pop vertices on or under the
                    // segment from their left neighbour to q.
                    while (size >= 2 && notAbove(P, hull[size - 2], hull[size - 1], q)) --size;
                    hull[size++] = q;
                }
                if (size == 0) continue;
                // The slope from k along the hull rises, then falls.
                int lo = 0, hi = size - 1;
                while (lo < hi) {
                    const int mid = (lo + hi) / 2;
                    // Rising or level: the farther of equal ones wins.
                    if (!steeper(P, k, hull[mid], hull[mid + 1]))
                        lo = mid + 1;
                    else
                        hi = mid;
                }
                if (P.best[k] < 0 || !steeper(P, k, P.best[k], hull[lo])) P.best[k] = hull[lo];
            }
        }
        prevBlock = b;
        prevBegin = begin;
        prevEnd = end;
        begin = end;
    }
}

// Gathers line o of `l` into P in sweep order. On a diagonal the profile also
// holds the centre of every cell it crosses: the surface drawn there (the
// 4-8 mesh at full resolution splits cell (ci, cj) by its main diagonal when
// ci + cj is even, else by the anti diagonal) is the midpoint of the cell's
// drawn diagonal, which casts when both its ends have data.
void gatherLine(const Surface& s, const Lines& l, int o, Profile& P) {
    auto [mBegin, mEnd] = lineSpan(l, o);
    P.n = 0;
    if (mBegin >= mEnd) return;
    // t = (x, z) . (ux, uz), w = (x, z) . (-uz, ux)
    const double ax = s.sx * l.ux, az = s.sz * l.uz;
    const double bx = -s.sx * l.uz, bz = s.sz * l.ux;
    int pi = 0, pj = 0;
    double pt = 0.0, pw = 0.0;
    const int count = mEnd - mBegin;
    for (int c = 0; c < count; ++c) {
        const int m = l.look > 0 ? mEnd - 1 - c : mBegin + c;
        const int nn = o + l.r[m];
        const int i = l.iMajor ? m : nn, j = l.iMajor ? nn : m;
        const double t = double(i) * ax + double(j) * az;
        const double w = double(i) * bx + double(j) * bz;
        if (l.diagonal && c > 0) {
            const int ci = std::min(i, pi), cj = std::min(j, pj);
            int ai = ci, aj = cj, bi = ci + 1, bj = cj + 1;
            if ((ci + cj) & 1) {
                ai = ci + 1;
                bi = ci;
            }
            const int k = P.n++;
            P.h[k] = 0.5f * (s.h(ai, aj) + s.h(bi, bj));
            P.t[k] = 0.5 * (t + pt);
            P.w[k] = 0.5 * (w + pw);
            P.flags[k] = s.ok(ai, aj) && s.ok(bi, bj) ? kCast : 0;
            P.sample[k] = -1;
        }
        const int k = P.n++;
        P.h[k] = s.h(i, j);
        P.t[k] = t;
        P.w[k] = w;
        P.flags[k] = s.ok(i, j) ? kCast | kReceive : 0;
        P.sample[k] = int64_t(s.index(i, j));
        pi = i;
        pj = j;
        pt = t;
        pw = w;
    }
}

}  // namespace sierra::analysis::relief
