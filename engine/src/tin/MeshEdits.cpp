// The TIN mesher's edits of its triangulation (Mesher.h): vertex insertion
// inside a triangle, on an edge and next to a borderline (snap), Lawson flips
// with the Delaunay or data-dependent rule (planeError), the budget's
// journal, point location, and the recovery of borderline segments as
// constrained edges. The insertion loop that calls them is in Tin.cpp.
#include "Mesher.h"

#include <sierra/core/Error.h>

#include <algorithm>
#include <cmath>
#include <deque>

namespace sierra::tin::detail {

void Mesher::rotateTriangle(int t, int k) {
    if (k == 0) return;
    EdgeData d[3];
    int v[3];
    for (int i = 0; i < 3; ++i) {
        d[i] = save(3 * t + (i + k) % 3);
        v[i] = origin_[3 * t + (i + k) % 3];
    }
    for (int i = 0; i < 3; ++i) {
        setTwin(3 * t + i, -1);
    }
    for (int i = 0; i < 3; ++i) {
        setOrigin(3 * t + i, v[i]);
        restore(3 * t + i, d[i]);
    }
}

// p strictly inside t = (a, b, c): t becomes (a, b, p), new (b, c, p) and (c, a, p).
// Edge 0 of each is the old outer edge, vertex 2 the new point.
void Mesher::insertInTriangle(int t, int v) {
    const int a = origin_[3 * t], b = origin_[3 * t + 1], c = origin_[3 * t + 2];
    const EdgeData bc = save(3 * t + 1), ca = save(3 * t + 2);
    const int t1 = addTriangle(), t2 = addTriangle();
    setTriangle(t, a, b, v);
    setTriangle(t1, b, c, v);
    setTriangle(t2, c, a, v);
    restore(3 * t1, bc);
    restore(3 * t2, ca);
    unconstrain(3 * t + 1);
    unconstrain(3 * t + 2);
    link(3 * t + 1, 3 * t1 + 2);
    link(3 * t1 + 1, 3 * t2 + 2);
    link(3 * t2 + 1, 3 * t + 2);
    touch(t);
    touch(t1);
    touch(t2);
    legalizeFrom(3 * t);
    legalizeFrom(3 * t1);
    legalizeFrom(3 * t2);
}

// p exactly on half-edge e = a->b of triangle (a, b, c), twin in (b, a, d) if any.
// The two halves keep the constrained flag and the zones of each side.
void Mesher::splitEdge(int e, int v) {
    const int t = e / 3;
    rotateTriangle(t, e % 3);
    e = 3 * t;
    // Rotate the twin's triangle too before anything is rewritten, so that
    // saved twins all point at half-edges that stay where they are.
    int u = -1, un = -1;
    if (twin_[e] >= 0) {
        u = twin_[e] / 3;
        rotateTriangle(u, twin_[e] % 3);
    }
    const int o = twin_[e];
    // Triangle (x0, x1, x2) with the split edge x0 -> x1 becomes (x2, x0, p) and a new
    // (x1, x2, p): the outer edges keep their twins and flags, the halves x0-p and p-x1
    // keep the split edge's constraint and zone, the new inner edge is plain. Serves t
    // = (a, b, c) and its twin's u = (b, a, d) alike. Returns the new triangle.
    const auto splitHalf = [&](int tri) {
        const int x0 = origin_[3 * tri], x1 = origin_[3 * tri + 1], x2 = origin_[3 * tri + 2];
        const EdgeData e01 = save(3 * tri), e12 = save(3 * tri + 1), e20 = save(3 * tri + 2);
        const int nt = addTriangle();
        setTriangle(tri, x2, x0, v);
        setTriangle(nt, x1, x2, v);
        for (int k = 0; k < 3; ++k) setTwin(3 * tri + k, -1);
        restore(3 * tri, e20);
        restore(3 * nt, e12);
        link(3 * tri + 2, 3 * nt + 1);
        constrainLike(3 * tri + 1, e01);
        constrainLike(3 * nt + 2, e01);
        unconstrain(3 * tri + 2);
        unconstrain(3 * nt + 1);
        touch(tri);
        touch(nt);
        return nt;
    };
    const int tn = splitHalf(t);  // t = (c, a, p), tn = (b, c, p)
    if (o >= 0) {
        un = splitHalf(u);  // u = (d, b, p), un = (a, d, p)
        link(3 * t + 1, 3 * un + 2);
        link(3 * tn + 2, 3 * u + 1);
    } else {
        setTwin(3 * t + 1, -1);
        setTwin(3 * tn + 2, -1);
    }
    legalizeFrom(3 * t);
    legalizeFrom(3 * tn);
    if (u >= 0) {
        legalizeFrom(3 * u);
        legalizeFrom(3 * un);
    }
}

// The snap() rule: p strictly inside t, next to t's constrained edge k = a->b
// (which has a twin). p is inserted as usual, then the borderline a->b is
// replaced by a->p->b: the sliver (a, b, p) changes sides and a-b may flip.
void Mesher::snapInsert(int t, int k, int v) {
    rotateTriangle(t, k);
    const int e = 3 * t;
    const int o = twin_[e];
    const int32_t zoneHere = zone_[e], zoneThere = zone_[o], segment = segment_[e];
    const int a = origin_[e], b = origin_[nextHe(e)];
    // An ordinary insertion first: a->b is still constrained, so its flips
    // leave the sliver (a, b, p) alone. They may move the edges around p, so
    // the new borderline halves are found by their end points, not their slots.
    insertInTriangle(t, v);
    const int ap = findEdge(a, v), pb = findEdge(v, b);
    SIERRA_CHECK(ap >= 0 && pb >= 0, "sierra::tin: snap: the split edge lost its new vertex");
    const int ab = findEdge(a, b);
    SIERRA_CHECK(ab >= 0 && twin_[ab] >= 0, "sierra::tin: snap: the constrained edge moved");
    const int ba = twin_[ab];
    // c (the old triangle's far corner) stays left of a->p and p->b, so they
    // take the zone of c's side; their twins take the other side's. The sliver
    // (a, b, p) is now on the other side, and a-b an ordinary edge.
    unconstrain(ab);
    unconstrain(ba);
    for (int h : {ap, pb}) {
        constrain(h, zoneHere, segment);
        constrain(twin_[h], zoneThere, segment);
    }
    touch(ab / 3);
    touch(ba / 3);
    legalizeFrom(ab);
}

// Flips half-edge e = a->b of (a, b, p) with its twin in (b, a, d): the two
// triangles become (p, a, d) and (d, b, p). Afterwards a->d is half-edge 1 of
// e's triangle and d->b half-edge 0 of the twin's, both opposite p.
void Mesher::flip(int e) {
    const int o = twin_[e];
    const int t1 = e / 3, t2 = o / 3;
    const int a = origin_[e], b = origin_[nextHe(e)], p = origin_[prevHe(e)],
              d = origin_[prevHe(o)];
    const EdgeData bp = save(nextHe(e)), pa = save(prevHe(e)), ad = save(nextHe(o)),
                   db = save(prevHe(o));
    for (int k = 0; k < 3; ++k) {
        setTwin(3 * t1 + k, -1);
        setTwin(3 * t2 + k, -1);
    }
    setTriangle(t1, p, a, d);
    setTriangle(t2, d, b, p);
    restore(3 * t1, pa);
    restore(3 * t1 + 1, ad);
    restore(3 * t2, db);
    restore(3 * t2 + 1, bp);
    link(3 * t1 + 2, 3 * t2 + 2);
    unconstrain(3 * t1 + 2);
    unconstrain(3 * t2 + 2);
    touch(t1);
    touch(t2);
    ++flips_;
}

// Whether edge e = a->b of (a, b, p), twin in (b, a, d), should flip.
bool Mesher::shouldFlip(int e) {
    const int o = twin_[e];
    if (o < 0 || constrained_[e]) return false;
    const GridPoint a = at(e), b = at(nextHe(e)), p = at(prevHe(e)), d = at(prevHe(o));
    if (!dataDependent_) {
        const int side =
            smallGrid_ ? detail::inCircleSign64(a, b, p, d) : detail::inCircleSign(a, b, p, d);
        if (side != 0) return side > 0;
        // d on the circle (four grid samples on one circle are common): both
        // diagonals are Delaunay. Keep the one whose two planes have the smaller
        // largest error over the quad's samples, the measure the insertion
        // minimises, by a relative margin of 1e-9 so the pair cannot flip back.
        // On the fractals of docs/tin.md it saves 0.3-1.7% of the triangles at
        // 0.1-0.5% relative error; keeping the first diagonal gave about the
        // public mesher's counts.
        const double bar =
            std::max(planeError<true>(a, b, p), planeError<true>(b, a, d)) * (1.0 - 1e-9);
        return planeError<true>(p, a, d, bar) < bar && planeError<true>(d, b, p, bar) < bar;
    }
    // Data-dependent: only a strictly convex quad, and only when the other
    // diagonal's two planes fit the quad's samples better (sum of squared errors,
    // by a relative margin of 1e-9 so round-off cannot make flips cycle).
    if (orient(p, a, d) <= 0 || orient(d, b, p) <= 0) return false;
    const double now = quadError(a, b, p) + quadError(b, a, d);
    const double other = quadError(p, a, d) + quadError(d, b, p);
    return other < now * (1.0 - 1e-9);
}

// Lawson's legalization after inserting p: e is opposite p in its triangle.
void Mesher::legalizeFrom(int e0) {
    stack_.push_back(e0);
    while (!stack_.empty()) {
        const int e = stack_.back();
        stack_.pop_back();
        if (!shouldFlip(e)) continue;
        const int o = twin_[e];
        flip(e);
        stack_.push_back(3 * (e / 3) + 1);
        stack_.push_back(3 * (o / 3));
    }
}

void Mesher::saveEdge(int e) {
    savedEpoch_[size_t(e)] = epoch_;
    journal_.push_back({e, origin_[e], twin_[e], zone_[e], segment_[e], constrained_[e]});
}

void Mesher::checkpoint() {
    ++epoch_;
    journal_.clear();
    checkpointHalfEdges_ = origin_.size();
    checkpointPoints_ = points_.size();
    savedEpoch_.resize(origin_.size(), 0);
}

void Mesher::rollback() {
    for (auto it = journal_.rbegin(); it != journal_.rend(); ++it) {
        const size_t e = size_t(it->e);
        origin_[e] = it->origin;
        twin_[e] = it->twin;
        zone_[e] = it->zone;
        segment_[e] = it->segment;
        constrained_[e] = it->constrained;
    }
    journal_.clear();
    for (auto* v : {&origin_, &twin_, &zone_, &segment_}) v->resize(checkpointHalfEdges_);
    constrained_.resize(checkpointHalfEdges_);
    const size_t triangles = checkpointHalfEdges_ / 3;
    heapPos_.resize(triangles);
    candidate_.resize(triangles);
    candidateError_.resize(triangles);
    mark_.resize(triangles);
    points_.resize(checkpointPoints_);
    vertexHe_.resize(checkpointPoints_);
    journaling_ = false;
}

// Walks from triangle `start` to a triangle containing p (inside or on its edges).
int Mesher::locate(GridPoint p, int start) const {
    int t = start;
    unsigned turn = 0;
    for (size_t steps = 0; steps < 4 * origin_.size() + 16; ++steps) {
        bool moved = false;
        for (int i = 0; i < 3; ++i) {
            // Vary the first edge tried so the walk cannot circle.
            const int e = 3 * t + int((i + turn) % 3);
            if (orient(at(e), at(nextHe(e)), p) < 0 && twin_[e] >= 0) {
                t = twin_[e] / 3;
                moved = true;
                break;
            }
        }
        ++turn;
        if (!moved) return t;
    }
    throw Error(msg("sierra::tin: point location did not converge at (", p.x, ", ", p.y, ")"));
}

int Mesher::findEdge(int u, int w) const {
    int found = -1;
    forEachOutgoing(u, [&](int e) {
        if (origin_[nextHe(e)] == w) {
            found = e;
            return true;
        }
        return false;
    });
    return found;
}

// Inserts a vertex at p during setup (Delaunay flips), returning its index.
int Mesher::insertVertex(GridPoint p) {
    const int t = locate(p, lastTriangle_);
    const int v = addVertex(p);
    int onEdge = -1;
    for (int k = 0; k < 3; ++k) {
        if (orient(at(3 * t + k), at(nextHe(3 * t + k)), p) == 0) onEdge = 3 * t + k;
    }
    ++stamp_;
    dirty_.clear();
    if (onEdge >= 0)
        splitEdge(onEdge, v);
    else
        insertInTriangle(t, v);
    lastTriangle_ = t;
    return v;
}

// Makes a->b a chain of mesh edges (split at vertices exactly on it), marks it
// constrained with its zones, and restores the constrained Delaunay property.
void Mesher::recoverSegment(int a, int b, int32_t leftZone, int32_t rightZone, int32_t segment) {
    std::deque<std::pair<int, int>> crossing;
    std::vector<std::pair<int, int>> created;
    while (a != b) {
        const GridPoint pa = pt(a), pb = pt(b);
        // An edge from a along the segment: to b, or to a vertex on it.
        int along = -1, alongIn = -1, wedge = -1;
        auto onSegment = [&](GridPoint w) {
            const int64_t dot =
                int64_t(w.x - pa.x) * (pb.x - pa.x) + int64_t(w.y - pa.y) * (pb.y - pa.y);
            return orient(pa, pb, w) == 0 && dot > 0;
        };
        forEachOutgoing(a, [&](int e) {
            const GridPoint w = at(nextHe(e));
            if (onSegment(w)) {
                along = e;
                return true;
            }
            // On the grid's border the edge along the segment may exist only
            // as the half-edge coming in to a (its outgoing twin lies outside).
            if (twin_[prevHe(e)] < 0 && onSegment(at(prevHe(e)))) {
                alongIn = prevHe(e);
                return true;
            }
            // b strictly inside the wedge of e's triangle at a.
            if (orient(pa, w, pb) > 0 && orient(pa, at(prevHe(e)), pb) < 0) wedge = e;
            return false;
        });
        if (along >= 0) {
            const int w = origin_[nextHe(along)];
            constrain(along, leftZone, segment);
            if (twin_[along] >= 0) constrain(twin_[along], rightZone, segment);
            a = w;
            continue;
        }
        if (alongIn >= 0) {
            constrain(alongIn, rightZone,
                      segment);  // runs against the segment: its left is the right side
            a = origin_[alongIn];
            continue;
        }
        SIERRA_CHECK(wedge >= 0, "sierra::tin: no triangle at (", pa.x, ", ", pa.y, ") towards (",
                     pb.x, ", ", pb.y, ")");
        // Walk along a->b collecting the crossed edges, up to b or a vertex on the segment.
        crossing.clear();
        int c = nextHe(wedge);
        int stop = -1;
        while (true) {
            if (constrained_[c])
                throw Error(msg("sierra::tin: borderline segments cross near (", at(c).x, ", ",
                                at(c).y, "): borderlines may meet only at shared vertices"));
            crossing.emplace_back(origin_[c], origin_[nextHe(c)]);
            const int tc = twin_[c];
            SIERRA_CHECK(tc >= 0, "sierra::tin: a borderline leaves the grid");
            const int x = origin_[prevHe(tc)];
            const int64_t o = orient(pa, pb, pt(x));
            if (x == b || o == 0) {
                stop = x;
                break;
            }
            c = o > 0 ? nextHe(tc) : prevHe(tc);
        }
        // Flip crossing edges until none is left (each flip of a convex quad
        // removes one crossing or moves it on; non-convex ones wait their turn).
        created.clear();
        const GridPoint ps = pt(stop);
        size_t guard = 0;
        while (!crossing.empty()) {
            SIERRA_CHECK(++guard < 1000000, "sierra::tin: segment recovery did not converge");
            const auto [u, w] = crossing.front();
            crossing.pop_front();
            const int e = findEdge(u, w);
            SIERRA_CHECK(e >= 0, "sierra::tin: a crossing edge vanished");
            const GridPoint pu = at(e), pw = at(nextHe(e)), pp = at(prevHe(e)),
                            pd = at(prevHe(twin_[e]));
            if (orient(pp, pu, pd) <= 0 || orient(pd, pw, pp) <= 0) {
                crossing.emplace_back(u, w);
                continue;
            }
            const int p = origin_[prevHe(e)], d = origin_[prevHe(twin_[e])];
            flip(e);
            const int64_t op = orient(pa, ps, pt(p)), od = orient(pa, ps, pt(d));
            if ((op > 0 && od < 0) || (op < 0 && od > 0))
                crossing.emplace_back(p, d);
            else
                created.emplace_back(p, d);
        }
        const int e = findEdge(a, stop);
        SIERRA_CHECK(e >= 0, "sierra::tin: segment recovery lost the segment");
        constrain(e, leftZone, segment);
        if (twin_[e] >= 0) constrain(twin_[e], rightZone, segment);
        legalizeEdges(created);
        a = stop;
    }
}

// Lawson flips over arbitrary edges (given by end points) until each is locally
// Delaunay; used after segment recovery.
void Mesher::legalizeEdges(std::vector<std::pair<int, int>>& edges) {
    size_t guard = 0;
    while (!edges.empty()) {
        SIERRA_CHECK(++guard < 10000000, "sierra::tin: legalization did not converge");
        const auto [u, w] = edges.back();
        edges.pop_back();
        const int e = findEdge(u, w);
        if (e < 0 || twin_[e] < 0 || constrained_[e]) continue;
        const GridPoint pa = at(e), pb = at(nextHe(e)), pp = at(prevHe(e)),
                        pd = at(prevHe(twin_[e]));
        if (!inCircle(pa, pb, pp, pd)) continue;
        const int a = origin_[e], b = origin_[nextHe(e)], p = origin_[prevHe(e)],
                  d = origin_[prevHe(twin_[e])];
        flip(e);
        edges.emplace_back(p, a);
        edges.emplace_back(a, d);
        edges.emplace_back(d, b);
        edges.emplace_back(b, p);
    }
}

template <bool kLargest>
double Mesher::planeError(GridPoint a, GridPoint b, GridPoint c, double limit) const {
    const double za = height(a.x, a.y), zb = height(b.x, b.y), zc = height(c.x, c.y);
    const double ux = b.x - a.x, uy = b.y - a.y, uz = zb - za;
    const double vx = c.x - a.x, vy = c.y - a.y, vz = zc - za;
    const double nz = ux * vy - uy * vx;
    const double gx = -(uy * vz - uz * vy) / nz, gy = -(uz * vx - ux * vz) / nz;
    double sum = 0.0;
    scanTriangle(a, b, c, [&](int y, int x0, int x1) {
        if (kLargest && sum >= limit) return;
        const float* row = heights_ + size_t(y) * size_t(width_);
        for (int x = x0; x <= x1; ++x) {
            const double err = row[x] - (za + gx * (x - a.x) + gy * (y - a.y));
            if constexpr (kLargest)
                sum = std::max(sum, std::fabs(err));
            else
                sum += err * err;
        }
    });
    return sum;
}

}  // namespace sierra::tin::detail
