#pragma once
// Exact geometric predicates on grid samples. Coordinates are grid indices
// (|x|, |y| < 2^20 is far beyond any grid Sierra loads), so orientation fits in
// int64 and the in-circle determinant in __int128: no rounding, no epsilon.

#include <sierra/tin/Tin.h>

#include <cstdint>
#include <utility>

namespace sierra::tin::detail {

__extension__ typedef __int128 Int128;

// > 0 when c is left of a->b (a, b, c counter-clockwise), 0 when collinear.
inline int64_t orient(GridPoint a, GridPoint b, GridPoint c) {
    return int64_t(b.x - a.x) * (c.y - a.y) - int64_t(b.y - a.y) * (c.x - a.x);
}

// Largest coordinate difference for which inCircle64 is exact: each lifted
// term is at most 4 D^4 and their sum 12 D^4 < 2^63 for D <= 2^14 (grids up to
// 16385 samples a side).
constexpr int kInCircle64MaxExtent = 1 << 14;

// inCircleSign in int64 only: exact when every coordinate difference is at
// most kInCircle64MaxExtent.
inline int inCircleSign64(GridPoint a, GridPoint b, GridPoint c, GridPoint d) {
    const int64_t adx = a.x - d.x, ady = a.y - d.y;
    const int64_t bdx = b.x - d.x, bdy = b.y - d.y;
    const int64_t cdx = c.x - d.x, cdy = c.y - d.y;
    const int64_t det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
                        (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
                        (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
    return (det > 0) - (det < 0);
}
inline bool inCircle64(GridPoint a, GridPoint b, GridPoint c, GridPoint d) {
    return inCircleSign64(a, b, c, d) > 0;
}

// Where d lies against the circumcircle of the counter-clockwise triangle
// a, b, c: 1 strictly inside, 0 on it, -1 outside.
inline int inCircleSign(GridPoint a, GridPoint b, GridPoint c, GridPoint d) {
    const int64_t adx = a.x - d.x, ady = a.y - d.y;
    const int64_t bdx = b.x - d.x, bdy = b.y - d.y;
    const int64_t cdx = c.x - d.x, cdy = c.y - d.y;
    const Int128 alift = adx * adx + ady * ady;
    const Int128 blift = bdx * bdx + bdy * bdy;
    const Int128 clift = cdx * cdx + cdy * cdy;
    const Int128 det = alift * (bdx * cdy - cdx * bdy) + blift * (cdx * ady - adx * cdy) +
                       clift * (adx * bdy - bdx * ady);
    return (det > 0) - (det < 0);
}

// True when d lies strictly inside the circumcircle of the counter-clockwise
// triangle a, b, c.
inline bool inCircle(GridPoint a, GridPoint b, GridPoint c, GridPoint d) {
    return inCircleSign(a, b, c, d) > 0;
}

// Scan conversion of a triangle over the grid: calls row(y, x0, x1) for every
// row y with at least one sample inside or on the triangle, x0..x1 inclusive.
// Edges are stepped incrementally with exact integer quotient and remainder, so
// a sample on an edge belongs to both triangles sharing it and to no gap.
template <typename Row>
inline void scanTriangle(GridPoint a, GridPoint b, GridPoint c, Row&& row) {
    // Sort by y.
    if (b.y < a.y) std::swap(a, b);
    if (c.y < b.y) std::swap(b, c);
    if (b.y < a.y) std::swap(a, b);
    if (a.y == c.y) return;  // degenerate
    // Stepper for x along an edge p->q (p.y < q.y): x(y) = qx_ + rx_ / dy_.
    struct Edge {
        int64_t q, r, dy, qs, rs;
        void start(GridPoint p, GridPoint e, int y) {
            dy = e.y - p.y;
            const int64_t dx = e.x - p.x;
            qs = dx >= 0 ? dx / dy : -((-dx + dy - 1) / dy);
            rs = dx - qs * dy;
            const int64_t num = dx * (y - p.y);
            q = num >= 0 ? num / dy : -((-num + dy - 1) / dy);
            r = num - q * dy;
            q += p.x;
        }
        void step() {
            q += qs;
            r += rs;
            if (r >= dy) {
                ++q;
                r -= dy;
            }
        }
        int64_t floorX() const { return q; }
        int64_t ceilX() const { return q + (r > 0); }
    };
    const bool shortLeft =
        orient(a, c, b) > 0;  // b left of the long edge a->c: short edges bound from the left
    Edge longEdge;
    longEdge.start(a, c, a.y);
    if (a.y < b.y) {
        Edge e;
        e.start(a, b, a.y);
        for (int y = a.y; y < b.y; ++y) {
            if (shortLeft)
                row(y, int(e.ceilX()), int(longEdge.floorX()));
            else
                row(y, int(longEdge.ceilX()), int(e.floorX()));
            e.step();
            longEdge.step();
        }
    }
    if (b.y < c.y) {
        Edge e;
        e.start(b, c, b.y);
        for (int y = b.y; y <= c.y; ++y) {
            if (shortLeft)
                row(y, int(e.ceilX()), int(longEdge.floorX()));
            else
                row(y, int(longEdge.ceilX()), int(e.floorX()));
            e.step();
            longEdge.step();
        }
    } else {
        // b and c on one row: that last row runs between them.
        if (shortLeft)
            row(b.y, b.x, int(longEdge.floorX()));
        else
            row(b.y, int(longEdge.ceilX()), b.x);
    }
}

}  // namespace sierra::tin::detail
