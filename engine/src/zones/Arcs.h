#pragma once
// The arcs of a borderline graph (private to the zones module): the chains
// of vertices between pinned ones (junctions and frame corners), found from
// the graph's adjacency and written back as its edges. Arcs.cpp defines these
// and the arc passes of Borderlines.h (duplicate and collinear vertices,
// Douglas-Peucker simplification without crossings); Borderlines.cpp
// doubles the arcs into bands.

#include <sierra/zones/Borderlines.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace sierra::zones::detail {

// Zone pair of edge e as seen leaving vertex v: (left, right) along v -> other end.
inline std::pair<int32_t, int32_t> pairLeaving(const Edge& e, uint32_t v) {
    return e.from == v ? std::pair{e.left, e.right} : std::pair{e.right, e.left};
}

struct Adjacency {
    std::vector<uint32_t> start;  // CSR: edges of vertex v are list[start[v] .. start[v + 1])
    std::vector<uint32_t> list;
};

// The edges at each vertex.
Adjacency adjacency(const Borderlines& lines);

// Per vertex: pinned (an arc ends there): not between exactly two edges that
// continue one borderline, or a corner of the frame.
std::vector<bool> junctionsOf(const Borderlines& lines, const Adjacency& adj);

// A chain of vertices between two pinned ones (closed: first == last), with the
// zones on its left and right along the chain.
struct Arc {
    std::vector<uint32_t> chain;
    int32_t left = kOutside;
    int32_t right = kOutside;
    bool closed = false;
};

// Every edge once, in arcs from pinned vertex to pinned vertex (closed loops
// without a pinned vertex start anywhere).
std::vector<Arc> extractArcs(const Borderlines& lines, const Adjacency& adj,
                             const std::vector<bool>& pinned);

// Replaces the edges by the arcs' chains (only vertices with keep[] set inside a
// chain survive) and drops unused vertices.
void rebuild(Borderlines& lines, const std::vector<Arc>& arcs);

// The chain of an arc after rule 3 at `epsilon` (the whole chain when 0).
std::vector<uint32_t> simplifiedChain(const Borderlines& lines, const Arc& arc, double epsilon);

// Per arc: whether its simplified chain (chains[k]) breaks the subdivision.
std::vector<bool> findConflicts(const Borderlines& lines, const std::vector<Arc>& arcs,
                                const std::vector<std::vector<uint32_t>>& chains);

}  // namespace sierra::zones::detail
