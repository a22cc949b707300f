// The TIN mesher's error measure (Mesher.h): the worst sample of each
// triangle against the triangle's plane (scan), and the heap of triangles by
// that error from which Tin.cpp's insertion loop takes the next point.
#include "Mesher.h"

#include <algorithm>
#include <cmath>

namespace sierra::tin::detail {

// Finds the worst sample of triangle t (excluding its vertices) by scan
// conversion with an incrementally evaluated plane.
void Mesher::scan(int t) {
    const GridPoint a = at(3 * t), b = at(3 * t + 1), c = at(3 * t + 2);
    const double za = height(a.x, a.y), zb = height(b.x, b.y), zc = height(c.x, c.y);
    const double ux = b.x - a.x, uy = b.y - a.y, uz = zb - za;
    const double vx = c.x - a.x, vy = c.y - a.y, vz = zc - za;
    const double nz = ux * vy - uy * vx;
    const double gx = -(uy * vz - uz * vy) / nz;  // dz/dx
    const double gy = -(uz * vx - ux * vz) / nz;  // dz/dy
    double best = -1.0;
    int64_t bestIndex = -1;
    scanTriangle(a, b, c, [&](int y, int x0, int x1) {
        if (x0 > x1) return;
        const float* row = heights_ + size_t(y) * size_t(width_);
        const double z0 = za + gx * (x0 - a.x) + gy * (y - a.y);
        for (int x = x0; x <= x1; ++x) {
            const double err = std::fabs(double(row[x]) - (z0 + gx * double(x - x0)));
            if (err > best) [[unlikely]] {
                const GridPoint s{x, y};
                if (s == a || s == b || s == c) continue;
                best = err;
                bestIndex = int64_t(y) * width_ + x;
            }
        }
    });
    candidate_[t] = bestIndex;
    candidateError_[t] = best;
}

// Every triangle with a sample that is not a vertex stays in the heap, so its
// top is the worst error left even after the target is met.
// A 4-ary heap: half the depth of a binary one, and the four children of a
// node share a cache line or two, which matters once the heap outgrows the cache.
void Mesher::heapUp(int i) {
    while (i > 0) {
        const int parent = (i - 1) / 4;
        if (!heapLess(parent, i)) break;
        heapSwap(parent, i);
        i = parent;
    }
}

void Mesher::heapDown(int i) {
    const int n = int(heap_.size());
    while (true) {
        const int first = 4 * i + 1;
        if (first >= n) break;
        int largest = first;
        const int last = std::min(first + 4, n);
        for (int c = first + 1; c < last; ++c)
            if (heapLess(largest, c)) largest = c;
        if (!heapLess(i, largest)) break;
        heapSwap(i, largest);
        i = largest;
    }
}

void Mesher::heapUpdate(int t) {
    int i = heapPos_[t];
    if (candidate_[t] < 0) {
        if (i < 0) return;
        const int last = int(heap_.size()) - 1;
        heapSwap(i, last);
        heap_.pop_back();
        heapPos_[t] = -1;
        if (i < last) {
            heapUp(i);
            heapDown(i);
        }
        return;
    }
    if (i < 0) {
        i = int(heap_.size());
        heap_.push_back({candidateError_[t], t});
        heapPos_[t] = i;
        heapUp(i);
        return;
    }
    const double old = heap_[size_t(i)].error;
    heap_[size_t(i)].error = candidateError_[t];
    if (candidateError_[t] > old)
        heapUp(i);
    else
        heapDown(i);
}

}  // namespace sierra::tin::detail
