#include "Predicates.h"

#include <sierra/core/Error.h>
#include <sierra/core/Timer.h>
#include <sierra/tin/Tin.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <unordered_map>

namespace sierra::tin {

using detail::inCircle;
using detail::orient;
using detail::scanTriangle;

const char* toString(StopReason reason) {
    switch (reason) {
        case StopReason::Error:
            return "error";
        case StopReason::Triangles:
            return "triangles";
        case StopReason::Points:
            return "points";
        case StopReason::Exhausted:
            return "exhausted";
    }
    return "?";
}

const char* toString(BudgetStop rule) {
    return rule == BudgetStop::BestMax ? "best-max" : "last";
}

namespace {

inline int nextHe(int e) {
    return e % 3 == 2 ? e - 2 : e + 1;
}
inline int prevHe(int e) {
    return e % 3 == 0 ? e + 2 : e - 1;
}

// The triangulation in flat arrays: triangle t owns half-edges 3t, 3t+1, 3t+2,
// counter-clockwise; half-edge e runs from vertex origin_[e] to origin_[nextHe(e)]
// with its triangle on its left. twin_[e] is the opposite half-edge (-1 on the
// grid's border). A constrained half-edge carries the zone of its own side.
class Mesher {
  public:
    Mesher(const terrain::Heightfield& field, const TinDesc& desc)
        : field_(field),
          desc_(desc),
          width_(field.width()),
          height_(field.height()),
          heights_(field.samples().data()) {}

    TinResult run(const Constraints& constraints);

  private:
    // --- topology -------------------------------------------------------------
    int addVertex(GridPoint p) {
        points_.push_back(p);
        vertexHe_.push_back(-1);
        return int(points_.size()) - 1;
    }
    void reserve(size_t points) {
        const size_t triangles = 2 * points, halfEdges = 3 * triangles;
        points_.reserve(points);
        vertexHe_.reserve(points);
        for (auto* v : {&origin_, &twin_}) v->reserve(halfEdges);
        constrained_.reserve(halfEdges);
        zone_.reserve(halfEdges);
        segment_.reserve(halfEdges);
        heapPos_.reserve(triangles);
        candidate_.reserve(triangles);
        candidateError_.reserve(triangles);
        mark_.reserve(triangles);
        heap_.reserve(triangles);
    }
    int addTriangle() {
        const int t = int(origin_.size() / 3);
        origin_.resize(origin_.size() + 3, -1);
        twin_.resize(twin_.size() + 3, -1);
        constrained_.resize(constrained_.size() + 3, 0);
        zone_.resize(zone_.size() + 3, -1);
        segment_.resize(segment_.size() + 3, -1);
        heapPos_.push_back(-1);
        candidate_.push_back(-1);
        candidateError_.push_back(-1.0);
        mark_.push_back(0);
        return t;
    }
    // Every write to a half-edge goes through these (and keep()), so the
    // budget's journal sees it.
    void setOrigin(int e, int v) {
        keep(e);
        origin_[e] = v;
        vertexHe_[v] = e;
    }
    void setTwin(int e, int o) {
        keep(e);
        twin_[e] = o;
    }
    void link(int e, int o) {
        setTwin(e, o);
        if (o >= 0) setTwin(o, e);
    }
    // Saved data of a half-edge about to move to another index.
    struct EdgeData {
        int twin;
        uint8_t constrained;
        int32_t zone;
        int32_t segment;
    };
    EdgeData save(int e) const { return {twin_[e], constrained_[e], zone_[e], segment_[e]}; }
    void restore(int e, const EdgeData& d) {
        link(e, d.twin);
        keep(e);
        constrained_[e] = d.constrained;
        zone_[e] = d.zone;
        segment_[e] = d.segment;
    }
    // Copies the constrained state of d (not its twin) to e.
    void constrainLike(int e, const EdgeData& d) {
        keep(e);
        constrained_[e] = d.constrained;
        zone_[e] = d.zone;
        segment_[e] = d.segment;
    }
    void unconstrain(int e) {
        keep(e);
        constrained_[e] = 0;
        zone_[e] = -1;
        segment_[e] = -1;
    }
    void constrain(int e, int32_t zone, int32_t segment) {
        keep(e);
        constrained_[e] = 1;
        zone_[e] = zone;
        segment_[e] = segment;
    }
    void setTriangle(int t, int a, int b, int c) {
        setOrigin(3 * t, a);
        setOrigin(3 * t + 1, b);
        setOrigin(3 * t + 2, c);
    }
    GridPoint pt(int v) const { return points_[size_t(v)]; }
    GridPoint at(int e) const { return points_[size_t(origin_[e])]; }
    void touch(int t) {
        if (mark_[t] != stamp_) {
            mark_[t] = stamp_;
            dirty_.push_back(t);
        }
    }

    // --- budget journal (BudgetStop::BestMax) ---------------------------------
    // The mesh of smallest max error so far is the checkpoint: the half-edges
    // and vertices that existed then, with the values they had. Each existing
    // half-edge rewritten since is saved once (its value at the checkpoint);
    // newer half-edges and vertices are simply cut off. rollback() returns the
    // topology (origin_, twin_, constrained_, zone_, segment_, points_) to the
    // checkpoint; the heap, the candidates and vertexHe_ are not restored, so
    // no insertion may follow it (the run only writes the mesh out).
    struct SavedEdge {
        int32_t e;
        int32_t origin;
        int32_t twin;
        int32_t zone;
        int32_t segment;
        uint8_t constrained;
    };
    // Called before every write to half-edge e: one test when not journaling.
    void keep(int e) {
        if (journaling_ && size_t(e) < checkpointHalfEdges_ && savedEpoch_[size_t(e)] != epoch_)
            saveEdge(e);
    }
    void saveEdge(int e);
    void checkpoint();
    void rollback();

    void insertInTriangle(int t, int v);
    void splitEdge(int e, int v);
    void snapInsert(int t, int k, int v);
    void rotateTriangle(int t, int k);
    void flip(int e);
    bool shouldFlip(int e);
    void legalizeFrom(int e);
    int locate(GridPoint p, int start) const;
    int insertVertex(GridPoint p);
    int findEdge(int u, int w) const;
    template <typename Fn>
    void forEachOutgoing(int v, Fn&& fn) const;
    void recoverSegment(int a, int b, int32_t leftZone, int32_t rightZone, int32_t segment);
    void legalizeEdges(std::vector<std::pair<int, int>>& edges);

    // --- error scan -----------------------------------------------------------
    float height(int x, int y) const { return heights_[size_t(y) * size_t(width_) + size_t(x)]; }
    void scan(int t);
    // The plane through a, b, c against the samples of that triangle: the sum
    // of squared vertical errors (kLargest false) or the largest one (true;
    // the scan stops at the first row that starts with `limit` reached).
    template <bool kLargest>
    double planeError(GridPoint a, GridPoint b, GridPoint c,
                      double limit = std::numeric_limits<double>::infinity()) const;
    double quadError(GridPoint a, GridPoint b, GridPoint c) const {
        return planeError<false>(a, b, c);
    }
    void heapUpdate(int t);
    bool heapLess(int i, int j) const { return heap_[size_t(i)].error < heap_[size_t(j)].error; }
    void heapSwap(int i, int j) {
        std::swap(heap_[size_t(i)], heap_[size_t(j)]);
        heapPos_[heap_[size_t(i)].triangle] = i;
        heapPos_[heap_[size_t(j)].triangle] = j;
    }
    void heapUp(int i);
    void heapDown(int i);
    void floodZones(const Constraints& constraints, TinResult& result);

    const terrain::Heightfield& field_;
    const TinDesc& desc_;
    int width_, height_;
    const float* heights_;

    std::vector<GridPoint> points_;
    std::vector<int> vertexHe_;
    std::vector<int> origin_, twin_;
    std::vector<uint8_t> constrained_;
    std::vector<int32_t> zone_;
    // Per half-edge: the input segment a constrained edge comes from (-1 none),
    // and that segment's snapped end points: the snap rule measures distances
    // from the input segment, so a borderline never drifts further than that.
    std::vector<int32_t> segment_;
    std::vector<std::pair<GridPoint, GridPoint>> segments_;
    // Per triangle: its place in the heap (-1 none), its worst sample (index
    // into the grid, -1 none) and that sample's error (stored units).
    std::vector<int32_t> heapPos_;
    std::vector<int64_t> candidate_;
    std::vector<double> candidateError_;
    std::vector<uint32_t> mark_;
    uint32_t stamp_ = 1;
    std::vector<int> dirty_;
    std::vector<int> stack_;
    bool dataDependent_ = false;
    bool smallGrid_ = false;  // every coordinate difference fits detail::inCircle64
    int64_t flips_ = 0;
    int lastTriangle_ = 0;

    bool journaling_ = false;
    uint32_t epoch_ = 0;
    std::vector<uint32_t> savedEpoch_;  // per half-edge: the epoch it was saved in
    std::vector<SavedEdge> journal_;
    size_t checkpointHalfEdges_ = 0;
    size_t checkpointPoints_ = 0;

    // A binary max-heap of triangles by candidate error (kept in the entry, so
    // sifting reads one array), indexed so that a rescanned triangle moves in
    // place (no stale entries).
    struct HeapItem {
        double error;
        int32_t triangle;
    };
    std::vector<HeapItem> heap_;
    double targetStored_ = 0.0;
};

template <typename Fn>
void Mesher::forEachOutgoing(int v, Fn&& fn) const {
    const int start = vertexHe_[v];
    int e = start;
    // Clockwise around v: the previous half-edge of e's triangle ends at v; its twin leaves v.
    do {
        if (fn(e)) return;
        const int in = prevHe(e);
        e = twin_[in];
    } while (e >= 0 && e != start);
    if (e == start) return;
    // Hit the border: go the other way from the start.
    e = start;
    while (true) {
        const int o = twin_[e];
        if (o < 0) return;
        e = nextHe(o);
        if (fn(e)) return;
    }
}

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

void Mesher::floodZones(const Constraints& constraints, TinResult& result) {
    TinMesh& mesh = result.mesh;
    const int triangles = int(origin_.size() / 3);
    std::vector<int32_t>& zone = mesh.zone;
    zone.assign(size_t(triangles), -1);
    std::vector<int> queue;
    // Seeds from the borderlines inside the grid first, then from the edges on its
    // border (the frame's, and borderlines snapped onto it). A frame edge carries the
    // zone of the map's outermost pixels, which a borderline one pixel from the
    // frame leaves on the wrong side of it once snapped; so a border edge only seeds
    // triangles no inner borderline reaches, and takes the zone of its triangle
    // otherwise. Conflicts are counted between inner borderlines only.
    for (const bool border : {false, true}) {
        for (int e = 0; e < int(origin_.size()); ++e) {
            if (!constrained_[e] || zone_[e] < 0 || (twin_[e] < 0) != border) continue;
            const int t = e / 3;
            if (zone[t] >= 0) {
                if (zone[t] == zone_[e]) continue;
                if (border) {
                    zone_[e] = zone[t];
                    mesh.edgeZones[size_t(t)][size_t(e % 3)] = zone[t];
                } else {
                    ++result.stats.zoneConflicts;
                }
                continue;
            }
            zone[t] = zone_[e];
            queue.assign(1, t);
            while (!queue.empty()) {
                const int u = queue.back();
                queue.pop_back();
                for (int k = 0; k < 3; ++k) {
                    const int h = 3 * u + k;
                    if (constrained_[h] || twin_[h] < 0) continue;
                    const int n = twin_[h] / 3;
                    if (zone[n] < 0) {
                        zone[n] = zone[u];
                        queue.push_back(n);
                    }
                }
            }
        }
    }
    std::unordered_map<int32_t, std::array<int32_t, 2>> bands;
    for (const auto& band : constraints.bands) bands[band.zone] = {band.first, band.second};
    mesh.surfaces.resize(size_t(triangles));
    for (int t = 0; t < triangles; ++t) {
        if (zone[t] < 0) zone[t] = constraints.defaultZone;
        auto it = bands.find(zone[t]);
        mesh.surfaces[size_t(t)] =
            it != bands.end() ? it->second : std::array<int32_t, 2>{zone[t], zone[t]};
    }
}

TinResult Mesher::run(const Constraints& constraints) {
    SIERRA_CHECK(width_ >= 2 && height_ >= 2,
                 "sierra::tin: the heightfield must be at least 2 x 2 samples, got ", width_, " x ",
                 height_);
    SIERRA_CHECK(desc_.maxError >= 0.0 && desc_.maxErrorRel >= 0.0 && desc_.maxTriangles >= 0 &&
                     desc_.maxPoints >= 0 && desc_.snapDistance >= 0.0,
                 "sierra::tin: stop limits and snap distance must not be negative");
    for (const auto& s : constraints.segments) {
        SIERRA_CHECK(s.a >= 0 && s.b >= 0 && size_t(s.a) < constraints.vertices.size() &&
                         size_t(s.b) < constraints.vertices.size(),
                     "sierra::tin: segment (", s.a, ", ", s.b, ") names a vertex outside 0..",
                     int64_t(constraints.vertices.size()) - 1);
        SIERRA_CHECK(s.leftZone >= 0 && s.rightZone >= 0, "sierra::tin: zones must be >= 0, got ",
                     s.leftZone, " and ", s.rightZone);
    }
    for (const auto& v : constraints.vertices)
        SIERRA_CHECK(std::isfinite(v.x) && std::isfinite(v.y),
                     "sierra::tin: a borderline vertex is not finite");

    TinResult result;
    Stopwatch clock;
    smallGrid_ = std::max(width_, height_) - 1 <= detail::kInCircle64MaxExtent;
    // Error target in stored height units.
    const double scale = std::fabs(double(field_.verticalScale()));
    const auto [lo, hi] = field_.range();
    double target = desc_.maxErrorRel * (double(hi) - double(lo));
    if (desc_.maxError > 0.0)
        target = std::max(target, scale > 0.0 ? desc_.maxError / scale : 1e30);
    targetStored_ = target;
    result.stats.targetError = target * scale;

    // Arrays grow by doubling (amortised: no allocation in most insertions);
    // with a point or triangle budget they are sized once up front.
    int64_t expectedPoints = 1024;
    if (desc_.maxPoints > 0) expectedPoints = desc_.maxPoints;
    if (desc_.maxTriangles > 0)
        expectedPoints = std::max(expectedPoints, desc_.maxTriangles / 2 + 2);
    expectedPoints =
        std::min<int64_t>({expectedPoints, int64_t(width_) * height_, int64_t(1) << 26});
    reserve(size_t(expectedPoints));
    // The grid's corners: two triangles, split along the (0,0)-(w-1,h-1) diagonal.
    const int c00 = addVertex({0, 0}), c10 = addVertex({width_ - 1, 0});
    const int c11 = addVertex({width_ - 1, height_ - 1}), c01 = addVertex({0, height_ - 1});
    const int t0 = addTriangle(), t1 = addTriangle();
    setTriangle(t0, c00, c10, c11);
    setTriangle(t1, c00, c11, c01);
    link(3 * t0 + 2, 3 * t1 + 0);

    // Borderline vertices, snapped to the nearest sample and merged.
    std::unordered_map<int64_t, int> bySample;
    for (int v = 0; v < 4; ++v) bySample[int64_t(pt(v).y) * width_ + pt(v).x] = v;
    std::vector<int> vertexOf(constraints.vertices.size(), -1);
    for (size_t i = 0; i < constraints.vertices.size(); ++i) {
        const auto& cv = constraints.vertices[i];
        const GridPoint p{int32_t(std::clamp(std::floor(cv.x + 0.5), 0.0, double(width_ - 1))),
                          int32_t(std::clamp(std::floor(cv.y + 0.5), 0.0, double(height_ - 1)))};
        const int64_t key = int64_t(p.y) * width_ + p.x;
        auto it = bySample.find(key);
        if (it == bySample.end()) it = bySample.emplace(key, insertVertex(p)).first;
        vertexOf[i] = it->second;
    }
    for (const auto& s : constraints.segments) {
        const int a = vertexOf[size_t(s.a)], b = vertexOf[size_t(s.b)];
        if (a == b) continue;
        segments_.emplace_back(pt(a), pt(b));
        recoverSegment(a, b, s.leftZone, s.rightZone, int32_t(segments_.size()) - 1);
    }
    dataDependent_ = desc_.triangulation == Triangulation::DataDependent;

    // First scan of every triangle.
    const int initial = int(origin_.size() / 3);
    for (int t = 0; t < initial; ++t) {
        scan(t);
        heapUpdate(t);
    }
    result.stats.setupMs = clock.ms();
    clock.restart();

    int64_t sinceProgress = 0;
    auto report = [&](double worst) {
        if (!desc_.progress) return;
        desc_.progress({.points = int64_t(points_.size()),
                        .triangles = int64_t(origin_.size() / 3),
                        .worstError = worst * scale,
                        .targetError = result.stats.targetError});
    };
    const double snap2 = desc_.snapDistance * desc_.snapDistance;
    result.stats.stop = StopReason::Exhausted;
    // With a budget and BudgetStop::BestMax, the mesh of smallest max error so
    // far (the heap's top before each insertion is the current mesh's max error)
    // is the checkpoint that a budget stop goes back to.
    journaling_ =
        (desc_.maxTriangles > 0 || desc_.maxPoints > 0) && desc_.budgetStop == BudgetStop::BestMax;
    struct Kept {
        double error = std::numeric_limits<double>::infinity();  // stored units
        int64_t inserted = 0, edgeSplits = 0, snapSplits = 0, flips = 0;
    } kept;
    while (!heap_.empty()) {
        const int t = heap_.front().triangle;
        const double topError = heap_.front().error;
        result.stats.worstError = topError * scale;
        if (journaling_ && topError <= kept.error) {
            checkpoint();
            kept = {topError, result.stats.inserted, result.stats.edgeSplits,
                    result.stats.snapSplits, flips_};
        }
        if (!(topError > targetStored_)) {
            result.stats.stop = StopReason::Error;
            break;
        }
        const int64_t index = candidate_[t];
        const GridPoint p{int32_t(index % width_), int32_t(index / width_)};
        // Where p lies in t: on an edge (exactly), next to a constrained edge, or inside.
        int onEdge = -1, snapEdge = -1;
        double snapBest = snap2;
        for (int k = 0; k < 3; ++k) {
            const int e = 3 * t + k;
            const GridPoint a = at(e), b = at(nextHe(e));
            const int64_t o = orient(a, b, p);
            if (o == 0) {
                onEdge = e;
                break;
            }
            if (!constrained_[e] || twin_[e] < 0 || snap2 <= 0.0) continue;
            // Distance from the input segment this edge comes from.
            const auto [sa, sb] = segments_[size_t(segment_[e])];
            const int64_t os = orient(sa, sb, p);
            const double len2 =
                double(sb.x - sa.x) * (sb.x - sa.x) + double(sb.y - sa.y) * (sb.y - sa.y);
            const double dist2 = double(os) * double(os) / len2;
            const int64_t dotA =
                int64_t(p.x - a.x) * (b.x - a.x) + int64_t(p.y - a.y) * (b.y - a.y);
            const int64_t dotB =
                int64_t(p.x - b.x) * (a.x - b.x) + int64_t(p.y - b.y) * (a.y - b.y);
            if (dist2 < snapBest && dotA > 0 && dotB > 0) {
                snapBest = dist2;
                snapEdge = k;
            }
        }
        const int64_t newTriangles = (onEdge >= 0 && twin_[onEdge] < 0) ? 1 : 2;
        if (desc_.maxPoints > 0 && int64_t(points_.size()) + 1 > desc_.maxPoints)
            result.stats.stop = StopReason::Points;
        else if (desc_.maxTriangles > 0 &&
                 int64_t(origin_.size() / 3) + newTriangles > desc_.maxTriangles)
            result.stats.stop = StopReason::Triangles;
        if (result.stats.stop != StopReason::Exhausted) {
            result.stats.budgetInserted = result.stats.inserted;
            result.stats.budgetWorstError = result.stats.worstError;
            if (journaling_) {
                rollback();
                result.stats.worstError = kept.error * scale;
                result.stats.inserted = kept.inserted;
                result.stats.edgeSplits = kept.edgeSplits;
                result.stats.snapSplits = kept.snapSplits;
                flips_ = kept.flips;
            }
            break;
        }
        const int v = addVertex(p);
        ++stamp_;
        dirty_.clear();
        if (onEdge >= 0) {
            splitEdge(onEdge, v);
            ++result.stats.edgeSplits;
        } else if (snapEdge >= 0) {
            snapInsert(t, snapEdge, v);
            ++result.stats.snapSplits;
        } else {
            insertInTriangle(t, v);
        }
        for (int d : dirty_) {
            scan(d);
            heapUpdate(d);
        }
        ++result.stats.inserted;
        if (++sinceProgress >= desc_.progressEvery) {
            sinceProgress = 0;
            report(topError);
        }
    }
    if (heap_.empty()) result.stats.worstError = 0.0;
    journaling_ = false;
    if (result.stats.stop != StopReason::Triangles && result.stats.stop != StopReason::Points) {
        result.stats.budgetInserted = result.stats.inserted;
        result.stats.budgetWorstError = result.stats.worstError;
    }
    result.stats.insertMs = clock.ms();
    report(result.stats.worstError / (scale > 0.0 ? scale : 1.0));
    clock.restart();

    // The mesh.
    TinMesh& mesh = result.mesh;
    mesh.gridWidth = width_;
    mesh.gridHeight = height_;
    mesh.spacingX = field_.spacingX();
    mesh.spacingZ = field_.spacingZ();
    mesh.vertices = points_;
    mesh.heights.resize(points_.size());
    for (size_t v = 0; v < points_.size(); ++v)
        mesh.heights[v] = float(height(points_[v].x, points_[v].y)) * field_.verticalScale();
    const int triangles = int(origin_.size() / 3);
    mesh.triangles.resize(size_t(triangles));
    mesh.constrainedEdges.resize(size_t(triangles));
    mesh.edgeZones.resize(size_t(triangles));
    for (int t = 0; t < triangles; ++t) {
        uint8_t bits = 0;
        for (int k = 0; k < 3; ++k) {
            mesh.triangles[size_t(t)][size_t(k)] = origin_[3 * t + k];
            if (constrained_[3 * t + k]) bits |= uint8_t(1u << k);
            mesh.edgeZones[size_t(t)][size_t(k)] = constrained_[3 * t + k] ? zone_[3 * t + k] : -1;
        }
        mesh.constrainedEdges[size_t(t)] = bits;
    }
    result.stats.flips = flips_;
    floodZones(constraints, result);
    result.stats.zonesMs = clock.ms();
    return result;
}

}  // namespace

TinResult buildTin(const terrain::Heightfield& field, const Constraints& constraints,
                   const TinDesc& desc) {
    SIERRA_CHECK(!field.empty(), "sierra::tin: the heightfield is empty");
    Mesher mesher(field, desc);
    return mesher.run(constraints);
}

ErrorStats measureError(const TinMesh& mesh, const terrain::Heightfield& field) {
    SIERRA_CHECK(mesh.gridWidth == field.width() && mesh.gridHeight == field.height(),
                 "sierra::tin::measureError: the mesh is for a ", mesh.gridWidth, " x ",
                 mesh.gridHeight, " grid, the heightfield is ", field.width(), " x ",
                 field.height());
    const int w = field.width();
    std::vector<uint8_t> seen(size_t(field.sampleCount()), 0);
    ErrorStats stats;
    double sum = 0.0;
    const double scale = field.verticalScale();
    for (const auto& tri : mesh.triangles) {
        const GridPoint a = mesh.vertices[size_t(tri[0])], b = mesh.vertices[size_t(tri[1])],
                        c = mesh.vertices[size_t(tri[2])];
        const double za = mesh.heights[size_t(tri[0])], zb = mesh.heights[size_t(tri[1])],
                     zc = mesh.heights[size_t(tri[2])];
        const double ux = b.x - a.x, uy = b.y - a.y, uz = zb - za;
        const double vx = c.x - a.x, vy = c.y - a.y, vz = zc - za;
        const double nz = ux * vy - uy * vx;
        if (nz == 0.0) continue;
        const double gx = -(uy * vz - uz * vy) / nz, gy = -(uz * vx - ux * vz) / nz;
        scanTriangle(a, b, c, [&](int y, int x0, int x1) {
            for (int x = x0; x <= x1; ++x) {
                const size_t i = size_t(y) * size_t(w) + size_t(x);
                if (seen[i]) continue;
                seen[i] = 1;
                const double err = std::fabs(double(field.at(x, y)) * scale -
                                             (za + gx * (x - a.x) + gy * (y - a.y)));
                stats.maxError = std::max(stats.maxError, err);
                sum += err * err;
                ++stats.samples;
            }
        });
    }
    stats.rmsError = stats.samples > 0 ? std::sqrt(sum / double(stats.samples)) : 0.0;
    return stats;
}

}  // namespace sierra::tin
