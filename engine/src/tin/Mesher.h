#pragma once
// The TIN mesher (private to the tin module): a constrained Delaunay (or
// data-dependent) triangulation of a heightfield's samples, refined by
// greedy insertion of the worst sample (Garland and Heckbert, "Fast
// Polygonal Approximation of Terrains and Height Fields", 1995), in flat
// half-edge arrays. Its members are defined by concern:
//
//   Tin.cpp        run(): the insertion loop from the corners and borderlines
//                  to the stop rule, the mesh written out, the zones flooded
//   MeshEdits.cpp  the triangulation's edits: insertions, edge splits, flips
//                  and their legalization, point location, segment recovery,
//                  the budget's journal
//   ErrorScan.cpp  each triangle's worst sample (scan) and the heap of
//                  triangles by that error

#include "Predicates.h"

#include <sierra/tin/Tin.h>

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace sierra::tin::detail {

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

    // --- the steps of run (Tin.cpp) -------------------------------------------
    void checkInput(const Constraints& constraints) const;
    void buildInitialMesh(const Constraints& constraints);
    void report(double worst, double scale, const TinResult& result) const;
    void placeInTriangle(int t, GridPoint p, double snap2, int* onEdge, int* snapEdge) const;
    void insertPoints(double scale, TinResult& result);
    void writeMesh(TinResult& result) const;
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

}  // namespace sierra::tin::detail
