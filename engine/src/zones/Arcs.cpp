// The arcs of a borderline graph (Arcs.h) and the passes over them that
// Borderlines.h declares: merging duplicate vertices, dropping collinear
// ones, and the Douglas-Peucker simplification (rule 3) that keeps the zones
// a subdivision (no arc crosses another, findConflicts). The graph is made in
// Vectorise.cpp and doubled into bands in Borderlines.cpp.
#include "zones/Arcs.h"

#include <sierra/core/Error.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <unordered_map>

namespace sierra::zones {

using detail::Adjacency;
using detail::Arc;

namespace {

double cross(const Vertex& o, const Vertex& a, const Vertex& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

double segmentDistance(const Vertex& p, const Vertex& a, const Vertex& b) {
    double dx = b.x - a.x, dy = b.y - a.y;
    double len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
    double ex = a.x + t * dx - p.x, ey = a.y + t * dy - p.y;
    return std::sqrt(ex * ex + ey * ey);
}

// Douglas-Peucker over chain[first..last]: marks the kept vertices.
void douglasPeucker(const Borderlines& lines, const std::vector<uint32_t>& chain, size_t first,
                    size_t last, double epsilon, std::vector<bool>& keep) {
    std::vector<std::pair<size_t, size_t>> stack{{first, last}};
    while (!stack.empty()) {
        auto [a, b] = stack.back();
        stack.pop_back();
        double worst = -1.0;
        size_t at = a;
        for (size_t k = a + 1; k < b; ++k) {
            double d = segmentDistance(lines.vertices[chain[k]], lines.vertices[chain[a]],
                                       lines.vertices[chain[b]]);
            if (d > worst) {
                worst = d;
                at = k;
            }
        }
        if (worst > epsilon) {
            keep[at] = true;
            stack.push_back({a, at});
            stack.push_back({at, b});
        }
    }
}

int orientation(const Vertex& p, const Vertex& q, const Vertex& r) {
    double v = (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
    return v > 0 ? 1 : v < 0 ? -1 : 0;
}

bool onSegment(const Vertex& p, const Vertex& a, const Vertex& b) {
    return orientation(a, b, p) == 0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
           std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}

}  // namespace

namespace detail {

// Arcs whose simplified chains break the subdivision: two segments that cross
// or touch away from a shared end, or a vertex around which the zones do not
// follow each other (the zone right of one edge must be left of the next).
std::vector<bool> findConflicts(const Borderlines& lines, const std::vector<Arc>& arcs,
                                const std::vector<std::vector<uint32_t>>& chains) {
    struct Seg {
        uint32_t a, b, arc;
    };
    std::vector<Seg> segs;
    for (size_t k = 0; k < arcs.size(); ++k)
        for (size_t i = 0; i + 1 < chains[k].size(); ++i)
            segs.push_back({chains[k][i], chains[k][i + 1], uint32_t(k)});
    std::vector<bool> conflict(arcs.size(), false);

    // Around each vertex.
    std::vector<std::vector<std::pair<double, uint32_t>>> around(lines.vertices.size());
    for (uint32_t s = 0; s < segs.size(); ++s) {
        const Vertex& a = lines.vertices[segs[s].a];
        const Vertex& b = lines.vertices[segs[s].b];
        around[segs[s].a].push_back({std::atan2(b.y - a.y, b.x - a.x), 2 * s});
        around[segs[s].b].push_back({std::atan2(a.y - b.y, a.x - b.x), 2 * s + 1});
    }
    for (auto& list : around) {
        if (list.size() < 2) continue;
        std::sort(list.begin(), list.end());
        for (size_t k = 0; k < list.size(); ++k) {
            const auto& cur = list[k];
            const auto& next = list[(k + 1) % list.size()];
            const Arc& ca = arcs[segs[cur.second / 2].arc];
            const Arc& na = arcs[segs[next.second / 2].arc];
            int32_t curRight =
                cur.second % 2 ? ca.left : ca.right;  // leaving through the end: sides swap
            int32_t nextLeft = next.second % 2 ? na.right : na.left;
            if (cur.first == next.first || curRight != nextLeft) {
                for (const auto& e : list) conflict[segs[e.second / 2].arc] = true;
                break;
            }
        }
    }

    // Crossings, through a uniform grid of buckets.
    const double cell = std::max(4.0, std::max(lines.mapWidth, lines.mapHeight) / 256.0);
    const int gw = int(lines.mapWidth / cell) + 2, gh = int(lines.mapHeight / cell) + 2;
    std::vector<std::vector<uint32_t>> grid(size_t(gw) * size_t(gh));
    auto cellOf = [&](double v, int limit) {
        return std::clamp(int(std::floor(v / cell)), 0, limit - 1);
    };
    for (uint32_t s = 0; s < segs.size(); ++s) {
        const Vertex& a = lines.vertices[segs[s].a];
        const Vertex& b = lines.vertices[segs[s].b];
        for (int gy = cellOf(std::min(a.y, b.y), gh); gy <= cellOf(std::max(a.y, b.y), gh); ++gy)
            for (int gx = cellOf(std::min(a.x, b.x), gw); gx <= cellOf(std::max(a.x, b.x), gw);
                 ++gx)
                grid[size_t(gy) * size_t(gw) + size_t(gx)].push_back(s);
    }
    for (const auto& bucket : grid)
        for (size_t i = 0; i < bucket.size(); ++i)
            for (size_t j = i + 1; j < bucket.size(); ++j) {
                const Seg& s = segs[bucket[i]];
                const Seg& t = segs[bucket[j]];
                if (conflict[s.arc] && conflict[t.arc]) continue;
                const Vertex &a = lines.vertices[s.a], &b = lines.vertices[s.b];
                const Vertex &c = lines.vertices[t.a], &d = lines.vertices[t.b];
                bool shared = s.a == t.a || s.a == t.b || s.b == t.a || s.b == t.b;
                bool bad;
                if (shared) {
                    // Sharing an end is fine unless the other end lies on the other segment
                    // (overlap).
                    uint32_t sOther = (s.a == t.a || s.a == t.b) ? s.b : s.a;
                    uint32_t tOther = (t.a == s.a || t.a == s.b) ? t.b : t.a;
                    bad =
                        (sOther != t.a && sOther != t.b &&
                         onSegment(lines.vertices[sOther], c, d)) ||
                        (tOther != s.a && tOther != s.b && onSegment(lines.vertices[tOther], a, b));
                } else {
                    int o1 = orientation(a, b, c), o2 = orientation(a, b, d);
                    int o3 = orientation(c, d, a), o4 = orientation(c, d, b);
                    bad = (o1 * o2 < 0 && o3 * o4 < 0) || onSegment(c, a, b) ||
                          onSegment(d, a, b) || onSegment(a, c, d) || onSegment(b, c, d);
                }
                if (bad) conflict[s.arc] = conflict[t.arc] = true;
            }
    return conflict;
}

Adjacency adjacency(const Borderlines& lines) {
    Adjacency a;
    a.start.assign(lines.vertices.size() + 1, 0);
    for (const Edge& e : lines.edges) {
        ++a.start[e.from + 1];
        ++a.start[e.to + 1];
    }
    for (size_t v = 0; v < lines.vertices.size(); ++v) a.start[v + 1] += a.start[v];
    a.list.resize(a.start.back());
    std::vector<uint32_t> fill(a.start.begin(), a.start.end() - 1);
    for (uint32_t k = 0; k < lines.edges.size(); ++k) {
        a.list[fill[lines.edges[k].from]++] = k;
        a.list[fill[lines.edges[k].to]++] = k;
    }
    return a;
}

std::vector<bool> junctionsOf(const Borderlines& lines, const Adjacency& adj) {
    std::vector<bool> pinned(lines.vertices.size(), true);
    for (uint32_t v = 0; v < lines.vertices.size(); ++v) {
        if (adj.start[v + 1] - adj.start[v] != 2) continue;
        auto a = pairLeaving(lines.edges[adj.list[adj.start[v]]], v);
        auto b = pairLeaving(lines.edges[adj.list[adj.start[v] + 1]], v);
        pinned[v] = !(a.first == b.second && a.second == b.first);
    }
    for (uint32_t v = 0; v < lines.vertices.size(); ++v) {
        const Vertex& p = lines.vertices[v];
        if ((p.x == lines.frameX0 || p.x == lines.frameX1) &&
            (p.y == lines.frameY0 || p.y == lines.frameY1))
            pinned[v] = true;
    }
    return pinned;
}

std::vector<Arc> extractArcs(const Borderlines& lines, const Adjacency& adj,
                             const std::vector<bool>& pinned) {
    std::vector<Arc> arcs;
    std::vector<bool> used(lines.edges.size(), false);
    auto walk = [&](uint32_t v, uint32_t e) {
        Arc arc;
        auto pr = pairLeaving(lines.edges[e], v);
        arc.left = pr.first;
        arc.right = pr.second;
        arc.chain.push_back(v);
        uint32_t start = v;
        while (true) {
            used[e] = true;
            const Edge& edge = lines.edges[e];
            v = edge.from == v ? edge.to : edge.from;
            arc.chain.push_back(v);
            if (pinned[v] || v == start) break;
            uint32_t next =
                adj.list[adj.start[v]] == e ? adj.list[adj.start[v] + 1] : adj.list[adj.start[v]];
            e = next;
        }
        arc.closed = arc.chain.front() == arc.chain.back();
        return arc;
    };
    for (uint32_t v = 0; v < lines.vertices.size(); ++v) {
        if (!pinned[v]) continue;
        for (uint32_t k = adj.start[v]; k < adj.start[v + 1]; ++k)
            if (!used[adj.list[k]]) arcs.push_back(walk(v, adj.list[k]));
    }
    // What is left are closed loops of unpinned vertices: start each at a
    // corner (a vertex where the loop turns) so rule 2 leaves only corners.
    for (uint32_t e = 0; e < lines.edges.size(); ++e) {
        if (used[e]) continue;
        uint32_t v = lines.edges[e].from, edge = e;
        for (size_t guard = 0; guard < lines.edges.size(); ++guard) {
            uint32_t e0 = adj.list[adj.start[v]], e1 = adj.list[adj.start[v] + 1];
            uint32_t a = lines.edges[e0].from == v ? lines.edges[e0].to : lines.edges[e0].from;
            uint32_t b = lines.edges[e1].from == v ? lines.edges[e1].to : lines.edges[e1].from;
            if (cross(lines.vertices[a], lines.vertices[v], lines.vertices[b]) != 0.0) break;
            uint32_t next = e0 == edge ? e1 : e0;
            v = lines.edges[next].from == v ? lines.edges[next].to : lines.edges[next].from;
            edge = next;
        }
        // Walk from v along one of its edges.
        arcs.push_back(walk(v, adj.list[adj.start[v]]));
    }
    return arcs;
}

// Replaces the edges by the arcs' chains (only vertices with keep[] set inside a
// chain survive) and drops unused vertices.
void rebuild(Borderlines& lines, const std::vector<Arc>& arcs) {
    std::vector<Edge> edges;
    std::vector<int32_t> remap(lines.vertices.size(), -1);
    std::vector<Vertex> vertices;
    auto id = [&](uint32_t v) {
        if (remap[v] < 0) {
            remap[v] = int32_t(vertices.size());
            vertices.push_back(lines.vertices[v]);
        }
        return uint32_t(remap[v]);
    };
    for (const Arc& arc : arcs)
        for (size_t k = 0; k + 1 < arc.chain.size(); ++k)
            edges.push_back({id(arc.chain[k]), id(arc.chain[k + 1]), arc.left, arc.right});
    lines.vertices.swap(vertices);
    lines.edges.swap(edges);
}

// The chain of an arc after rule 3 at `epsilon` (the whole chain when 0).
std::vector<uint32_t> simplifiedChain(const Borderlines& lines, const Arc& arc, double epsilon) {
    const size_t n = arc.chain.size();
    if (n <= 2 || !(epsilon > 0.0)) return arc.chain;
    std::vector<bool> keep(n, false);
    keep[0] = keep[n - 1] = true;
    if (arc.closed) {
        // Pin the first vertex and the one farthest from it.
        const Vertex& p0 = lines.vertices[arc.chain[0]];
        size_t far = 1;
        double best = -1;
        for (size_t k = 1; k + 1 < n; ++k) {
            const Vertex& p = lines.vertices[arc.chain[k]];
            double d = std::hypot(p.x - p0.x, p.y - p0.y);
            if (d > best) {
                best = d;
                far = k;
            }
        }
        keep[far] = true;
        douglasPeucker(lines, arc.chain, 0, far, epsilon, keep);
        douglasPeucker(lines, arc.chain, far, n - 1, epsilon, keep);
    } else {
        douglasPeucker(lines, arc.chain, 0, n - 1, epsilon, keep);
    }
    std::vector<uint32_t> out;
    for (size_t k = 0; k < n; ++k)
        if (keep[k]) out.push_back(arc.chain[k]);
    return out;
}

}  // namespace detail

using detail::adjacency;
using detail::extractArcs;
using detail::junctionsOf;
using detail::rebuild;
using detail::simplifiedChain;

void removeDuplicateVertices(Borderlines& lines) {
    std::map<std::pair<double, double>, uint32_t> first;
    std::vector<uint32_t> remap(lines.vertices.size());
    std::vector<Vertex> vertices;
    for (uint32_t v = 0; v < lines.vertices.size(); ++v) {
        auto [it, fresh] = first.try_emplace({lines.vertices[v].x, lines.vertices[v].y},
                                             uint32_t(vertices.size()));
        if (fresh) vertices.push_back(lines.vertices[v]);
        remap[v] = it->second;
    }
    std::map<std::pair<uint32_t, uint32_t>, bool> seen;
    std::vector<Edge> edges;
    for (Edge e : lines.edges) {
        e.from = remap[e.from];
        e.to = remap[e.to];
        if (e.from == e.to) continue;
        auto key = std::minmax(e.from, e.to);
        if (!seen.try_emplace({key.first, key.second}, true).second) continue;
        edges.push_back(e);
    }
    lines.vertices.swap(vertices);
    lines.edges.swap(edges);
}

std::vector<bool> junctions(const Borderlines& lines) {
    return junctionsOf(lines, adjacency(lines));
}

void removeCollinearVertices(Borderlines& lines) {
    Adjacency adj = adjacency(lines);
    auto arcs = extractArcs(lines, adj, junctionsOf(lines, adj));
    for (Arc& arc : arcs) {
        std::vector<uint32_t> out{arc.chain.front()};
        for (size_t k = 1; k + 1 < arc.chain.size(); ++k) {
            const Vertex& a = lines.vertices[out.back()];
            const Vertex& v = lines.vertices[arc.chain[k]];
            const Vertex& b = lines.vertices[arc.chain[k + 1]];
            bool straight = cross(a, v, b) == 0.0 &&
                            (v.x - a.x) * (b.x - v.x) + (v.y - a.y) * (b.y - v.y) > 0.0;
            if (!straight) out.push_back(arc.chain[k]);
        }
        out.push_back(arc.chain.back());
        arc.chain.swap(out);
    }
    rebuild(lines, arcs);
}

void simplifyArcs(Borderlines& lines, double epsilon) {
    if (!(epsilon > 0.0)) return;
    Adjacency adj = adjacency(lines);
    const std::vector<Arc> arcs = extractArcs(lines, adj, junctionsOf(lines, adj));
    // Each arc is simplified on its own at epsilon, so two arcs that run close
    // together (the two sides of a thin strip) could cross. Every such conflict
    // found in the result tightens the arcs involved (epsilon / 2, / 4, then
    // exact) and those are simplified again; the exact arcs never conflict,
    // so this ends.
    constexpr int kExact = 3;
    std::vector<int> level(arcs.size(), 0);
    std::vector<std::vector<uint32_t>> chains(arcs.size());
    std::vector<bool> dirty(arcs.size(), true);
    for (int round = 0;; ++round) {
        for (size_t a = 0; a < arcs.size(); ++a) {
            if (!dirty[a]) continue;
            dirty[a] = false;
            chains[a] = simplifiedChain(lines, arcs[a],
                                        level[a] >= kExact ? 0.0 : epsilon / double(1 << level[a]));
        }
        std::vector<bool> conflict = findConflicts(lines, arcs, chains);
        bool any = false;
        for (size_t a = 0; a < arcs.size(); ++a)
            if (conflict[a] && level[a] < kExact) {
                ++level[a];
                dirty[a] = any = true;
            }
        if (!any) break;
    }
    std::vector<Arc> out = arcs;
    for (size_t a = 0; a < arcs.size(); ++a) out[a].chain = chains[a];
    rebuild(lines, out);
}

}  // namespace sierra::zones
