#include <sierra/zones/Borderlines.h>

#include <sierra/core/Error.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <unordered_map>

namespace sierra::zones {
namespace {

// Builds vertices on demand, one per lattice position (rule 1 by construction).
class LatticeVertices {
  public:
    LatticeVertices(Borderlines& lines, int nx, int ny, double offset)
        : lines_(lines), nx_(nx), index_(size_t(nx) * size_t(ny), -1), offset_(offset) {}
    uint32_t at(int x, int y) {
        int32_t& k = index_[size_t(y) * size_t(nx_) + size_t(x)];
        if (k < 0) {
            k = int32_t(lines_.vertices.size());
            lines_.vertices.push_back({x + offset_, y + offset_});
        }
        return uint32_t(k);
    }

  private:
    Borderlines& lines_;
    int nx_;
    std::vector<int32_t> index_;
    double offset_;
};

void vectoriseTouching(const ZoneMap& map, Borderlines& lines) {
    const int w = map.width, h = map.height;
    LatticeVertices vertex(lines, w + 1, h + 1, 0.0);
    auto zone = [&](int x, int y) -> int32_t {
        return x < 0 || y < 0 || x >= w || y >= h ? kOutside : map.at(x, y);
    };
    for (int y = 0; y <= h; ++y)
        for (int x = 0; x <= w; ++x) {
            // Vertical unit edge on line x, from (x, y) down to (x, y + 1): pixel
            // (x, y) on its left (as drawn, y down), pixel (x - 1, y) on its right.
            if (y < h) {
                int32_t l = zone(x, y), r = zone(x - 1, y);
                if (l != r) lines.edges.push_back({vertex.at(x, y), vertex.at(x, y + 1), l, r});
            }
            // Horizontal unit edge on line y, from (x, y) right to (x + 1, y):
            // pixel (x, y - 1) on its left, pixel (x, y) on its right.
            if (x < w) {
                int32_t l = zone(x, y - 1), r = zone(x, y);
                if (l != r) lines.edges.push_back({vertex.at(x, y), vertex.at(x + 1, y), l, r});
            }
        }
}

void vectoriseFigure1(const ZoneMap& map, Borderlines& lines) {
    const int w = map.width, h = map.height;
    LatticeVertices vertex(lines, w, h, 0.5);
    auto inside = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h; };
    auto border = [&](int x, int y) { return inside(x, y) && map.at(x, y) == kBorderlinePixel; };
    auto ring = [&](int x, int y) { return x == 0 || y == 0 || x == w - 1 || y == h - 1; };

    // The zone nearest to pixel (x, y) (Chebyshev rings, scanned in a fixed
    // order): only asked for cells of four borderline pixels (2x2 blobs).
    auto nearestZone = [&](int x, int y) -> int32_t {
        for (int r = 1; r < std::max(w, h); ++r)
            for (int j = y - r; j <= y + r; ++j)
                for (int i = x - r; i <= x + r; i += (j == y - r || j == y + r) ? 1 : 2 * r)
                    if (inside(i, j) && map.at(i, j) >= 0) return map.at(i, j);
        return kOutside;
    };

    // Zone on the side n of the axis edge p -> q: the face there is the unit
    // cell {p, q, p+n, q+n}, or the half of it next to pq when a diagonal cuts
    // it (then p or q is a zone pixel and names it, so p and q come first). A
    // cell of four borderline pixels (a 2x2 blob) gets one zone, the nearest
    // to its top-left pixel, whichever edge asks, so its faces stay consistent.
    auto axisSide = [&](int px, int py, int qx, int qy, int nx, int ny) -> int32_t {
        if (!inside(px + nx, py + ny)) return kOutside;
        for (auto [x, y] : {std::pair{px, py}, {qx, qy}, {px + nx, py + ny}, {qx + nx, qy + ny}})
            if (map.at(x, y) >= 0) return map.at(x, y);
        int cx = std::min({px, qx, px + nx}), cy = std::min({py, qy, py + ny});
        return nearestZone(cx, cy);
    };
    auto addAxis = [&](int px, int py, int qx, int qy) {
        int dx = qx - px, dy = qy - py;
        int32_t l = axisSide(px, py, qx, qy, dy, -dx), r = axisSide(px, py, qx, qy, -dy, dx);
        if (l != r) lines.edges.push_back({vertex.at(px, py), vertex.at(qx, qy), l, r});
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool b = border(x, y);
            if (!b && !ring(x, y)) continue;
            // Right and down neighbours: both borderline pixels, or both on the same side of the
            // ring.
            if (x + 1 < w && ((b && border(x + 1, y)) || y == 0 || y == h - 1))
                addAxis(x, y, x + 1, y);
            if (y + 1 < h && ((b && border(x, y + 1)) || x == 0 || x == w - 1))
                addAxis(x, y, x, y + 1);
            if (!b) continue;
            // Diagonals, only where no borderline pixel is a common 4-neighbour
            // (else the 4-connected path already joins them). The pixel on each
            // side of a diagonal is a zone pixel.
            for (int dx : {1, -1}) {
                int qx = x + dx, qy = y + 1;
                if (!border(qx, qy) || border(qx, y) || border(x, qy)) continue;
                int32_t a = map.at(qx, y),
                        c = map.at(x, qy);  // (x+dx, y) is on the left when dx*dy > 0
                int32_t l = dx > 0 ? a : c, r = dx > 0 ? c : a;
                if (l != r) lines.edges.push_back({vertex.at(x, y), vertex.at(qx, qy), l, r});
            }
        }
}

// Zone pair of edge e as seen leaving vertex v: (left, right) along v -> other end.
std::pair<int32_t, int32_t> pairLeaving(const Edge& e, uint32_t v) {
    return e.from == v ? std::pair{e.left, e.right} : std::pair{e.right, e.left};
}

struct Adjacency {
    std::vector<uint32_t> start;  // CSR: edges of vertex v are list[start[v] .. start[v + 1])
    std::vector<uint32_t> list;
};

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

// A chain of vertices between two pinned ones (closed: first == last), with the
// zones on its left and right along the chain.
struct Arc {
    std::vector<uint32_t> chain;
    int32_t left = kOutside;
    int32_t right = kOutside;
    bool closed = false;
};

double cross(const Vertex& o, const Vertex& a, const Vertex& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
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

double segmentDistance(const Vertex& p, const Vertex& a, const Vertex& b) {
    double dx = b.x - a.x, dy = b.y - a.y;
    double len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
    double ex = a.x + t * dx - p.x, ey = a.y + t * dy - p.y;
    return std::sqrt(ex * ex + ey * ey);
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

int orientation(const Vertex& p, const Vertex& q, const Vertex& r) {
    double v = (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
    return v > 0 ? 1 : v < 0 ? -1 : 0;
}

bool onSegment(const Vertex& p, const Vertex& a, const Vertex& b) {
    return orientation(a, b, p) == 0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
           std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}

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

}  // namespace

Borderlines vectorise(const ZoneMap& map, const Palette& palette) {
    SIERRA_CHECK(
        map.width > 0 && map.height > 0 && map.ids.size() == size_t(map.width) * size_t(map.height),
        "vectorise: the zone map is empty or its ids do not match its size");
    SIERRA_CHECK(map.layout == ZoneLayout::Touching || (map.width >= 2 && map.height >= 2),
                 "vectorise: a Figure 1 zone map needs at least 2x2 pixels");
    Borderlines lines;
    lines.mapWidth = map.width;
    lines.mapHeight = map.height;
    lines.layout = map.layout;
    for (size_t k = 0; k < palette.surfaces.size(); ++k)
        lines.zones.push_back(
            {int32_t(k), palette.surfaces[k].name, palette.surfaces[k].colour, {-1, -1}});
    if (map.layout == ZoneLayout::Touching) {
        lines.frameX1 = map.width;
        lines.frameY1 = map.height;
        vectoriseTouching(map, lines);
    } else {
        lines.frameX0 = lines.frameY0 = 0.5;
        lines.frameX1 = map.width - 0.5;
        lines.frameY1 = map.height - 0.5;
        vectoriseFigure1(map, lines);
    }
    return lines;
}

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

namespace {

// The two copies of one arc at +-width/2 (mitred), as vertex ids; new vertices
// are appended to `vertices`. An open arc's copies start and end at its
// junctions and reach their full width at min(taper, length / 3) from them.
std::pair<std::vector<uint32_t>, std::vector<uint32_t>> offsetArc(std::vector<Vertex>& vertices,
                                                                  const Arc& arc, double width,
                                                                  double taperLength) {
    const double half = width / 2;
    auto add = [&](Vertex p) {
        vertices.push_back(p);
        return uint32_t(vertices.size() - 1);
    };
    std::vector<Vertex> pts;
    for (uint32_t v : arc.chain) pts.push_back(vertices[v]);
    if (!arc.closed) {
        double length = 0;
        for (size_t k = 0; k + 1 < pts.size(); ++k)
            length += std::hypot(pts[k + 1].x - pts[k].x, pts[k + 1].y - pts[k].y);
        double taper = std::min(taperLength, length / 3);
        auto insertAt = [&](std::vector<Vertex>& p) {
            double walked = 0;
            for (size_t k = 0; k + 1 < p.size(); ++k) {
                double seg = std::hypot(p[k + 1].x - p[k].x, p[k + 1].y - p[k].y);
                if (walked + seg > taper) {
                    double t = (taper - walked) / seg;
                    if (t > 1e-9)
                        p.insert(p.begin() + long(k) + 1, {p[k].x + t * (p[k + 1].x - p[k].x),
                                                           p[k].y + t * (p[k + 1].y - p[k].y)});
                    return;
                }
                walked += seg;
            }
        };
        insertAt(pts);
        std::reverse(pts.begin(), pts.end());
        insertAt(pts);
        std::reverse(pts.begin(), pts.end());
    }
    const size_t n = pts.size();
    auto normal = [&](size_t a, size_t b) {
        double dx = pts[b].x - pts[a].x, dy = pts[b].y - pts[a].y, len = std::hypot(dx, dy);
        return std::pair{dy / len, -dx / len};  // left of a -> b as drawn (y down)
    };
    std::vector<uint32_t> leftCopy(n), rightCopy(n);
    for (size_t k = 0; k < n; ++k) {
        if (!arc.closed && (k == 0 || k == n - 1)) {
            leftCopy[k] = rightCopy[k] = arc.chain[k == 0 ? 0 : arc.chain.size() - 1];
            continue;
        }
        if (arc.closed && k == n - 1) {
            leftCopy[k] = leftCopy[0];
            rightCopy[k] = rightCopy[0];
            continue;
        }
        size_t prev = k > 0 ? k - 1 : n - 2, next = k + 1;  // closed: pts[n-1] == pts[0]
        auto n1 = normal(prev, k), n2 = normal(k, next);
        double mx = n1.first + n2.first, my = n1.second + n2.second, len = std::hypot(mx, my);
        double scale = 1.0;
        if (len > 1e-12) {
            mx /= len;
            my /= len;
            double c = mx * n1.first + my * n1.second;
            scale = std::min(1.0 / std::max(c, 1e-6), 4.0);  // mitre, capped at 4x on sharp turns
        } else {
            mx = n1.first;
            my = n1.second;
        }
        leftCopy[k] = add({pts[k].x + mx * scale * half, pts[k].y + my * scale * half});
        rightCopy[k] = add({pts[k].x - mx * scale * half, pts[k].y - my * scale * half});
    }
    return {leftCopy, rightCopy};
}

}  // namespace

void doubleBorderlines(Borderlines& lines, double width,
                       const std::function<Vertex(const Vertex&)>& snap) {
    if (!(width > 0.0)) return;
    Adjacency adj = adjacency(lines);
    const std::vector<Arc> arcs = extractArcs(lines, adj, junctionsOf(lines, adj));
    std::map<std::pair<int32_t, int32_t>, int32_t> bandOf;
    std::vector<int32_t> band(arcs.size(), -1);
    for (size_t a = 0; a < arcs.size(); ++a) {
        const Arc& arc = arcs[a];
        if (arc.left == kOutside || arc.right == kOutside) continue;
        auto key = std::minmax(arc.left, arc.right);
        auto [it, fresh] = bandOf.try_emplace({key.first, key.second}, int32_t(lines.zones.size()));
        if (fresh) {
            const Zone& za = lines.zones[size_t(key.first)];
            const Zone& zb = lines.zones[size_t(key.second)];
            Colour mixed = 0;
            for (int shift : {16, 8, 0})
                mixed |= ((((za.colour >> shift) & 255) + ((zb.colour >> shift) & 255)) / 2)
                         << shift;
            lines.zones.push_back(
                {it->second, za.name + "|" + zb.name, mixed, {key.first, key.second}});
        }
        band[a] = it->second;
    }
    // A band wider than the room beside its arc (a thin strip, a tight bend)
    // would cross its neighbours: every arc in a conflict is narrowed (W/2,
    // W/4) and at last left single; single arcs never conflict, so this ends.
    constexpr int kSingle = 3;
    std::vector<int> level(arcs.size(), 0);
    const size_t baseVertices = lines.vertices.size();
    while (true) {
        std::vector<Vertex> vertices(lines.vertices.begin(),
                                     lines.vertices.begin() + long(baseVertices));
        std::vector<Arc> out;
        std::vector<size_t> source;
        for (size_t a = 0; a < arcs.size(); ++a) {
            if (band[a] < 0 || level[a] >= kSingle) {
                out.push_back(arcs[a]);
                source.push_back(a);
                continue;
            }
            // The taper keeps its length when the band narrows, so the copies of
            // two arcs leaving one junction at a small angle separate.
            // Offsetting the arc simplified at a quarter of the band width keeps
            // wiggles smaller than the band from folding its copies.
            const double w = width / double(1 << level[a]);
            Arc smooth = arcs[a];
            smooth.chain = simplifiedChain(lines, arcs[a], w / 4);
            auto [leftCopy, rightCopy] = offsetArc(vertices, smooth, w, 2 * width);
            out.push_back({leftCopy, arcs[a].left, band[a], arcs[a].closed});
            out.push_back({rightCopy, band[a], arcs[a].right, arcs[a].closed});
            source.push_back(a);
            source.push_back(a);
        }
        if (snap) {
            // Snapped copies are what gets checked, so the check sees the final
            // geometry; a copy's vertices that snap together become one.
            for (size_t v = baseVertices; v < vertices.size(); ++v) vertices[v] = snap(vertices[v]);
            auto same = [&](uint32_t a, uint32_t b) {
                return vertices[a].x == vertices[b].x && vertices[a].y == vertices[b].y;
            };
            for (Arc& arc : out) {
                std::vector<uint32_t> kept;
                for (uint32_t v : arc.chain)
                    if (kept.empty() || !same(kept.back(), v)) kept.push_back(v);
                // A closed copy keeps its first vertex as its last.
                if (kept.size() > 1 && arc.chain.front() == arc.chain.back() &&
                    kept.back() != kept.front() && same(kept.back(), kept.front()))
                    kept.back() = kept.front();
                arc.chain = std::move(kept);
            }
        }
        Borderlines candidate = lines;
        candidate.vertices = std::move(vertices);
        std::vector<std::vector<uint32_t>> chains;
        for (const Arc& arc : out) chains.push_back(arc.chain);
        std::vector<bool> conflict = findConflicts(candidate, out, chains);
        // A closed copy inside a loop smaller than the band (a small island, after
        // snapping too) turns inside out without crossing anything: its area
        // changes sign or vanishes. It counts as a conflict like a crossing.
        auto area = [](const std::vector<Vertex>& v, const std::vector<uint32_t>& chain) {
            double sum = 0.0;
            for (size_t k = 0; k + 1 < chain.size(); ++k)
                sum += v[chain[k]].x * v[chain[k + 1]].y - v[chain[k + 1]].x * v[chain[k]].y;
            return 0.5 * sum;
        };
        for (size_t k = 0; k < out.size(); ++k) {
            const Arc& original = arcs[source[k]];
            if (!original.closed || band[source[k]] < 0 || level[source[k]] >= kSingle) continue;
            const double before = area(lines.vertices, original.chain);
            const double after = area(candidate.vertices, out[k].chain);
            if (out[k].chain.size() < 4 || !(after * before > 0.0)) conflict[k] = true;
        }
        std::vector<bool> narrow(arcs.size(), false);
        for (size_t k = 0; k < out.size(); ++k)
            if (conflict[k] && band[source[k]] >= 0 && level[source[k]] < kSingle)
                narrow[source[k]] = true;
        bool any = false;
        for (size_t a = 0; a < arcs.size(); ++a)
            if (narrow[a]) {
                ++level[a];
                any = true;
            }
        if (!any) {
            lines.vertices = std::move(candidate.vertices);
            rebuild(lines, out);
            return;
        }
    }
}

Borderlines buildBorderlines(const ZoneMap& map, const Palette& palette,
                             const BorderlineDesc& desc) {
    SIERRA_CHECK(std::isfinite(desc.epsilon) && desc.epsilon >= 0.0,
                 "borderlines: epsilon must be >= 0 pixels, got ", desc.epsilon);
    SIERRA_CHECK(std::isfinite(desc.bandWidth) && desc.bandWidth >= 0.0,
                 "borderlines: band width must be >= 0 pixels, got ", desc.bandWidth);
    Borderlines lines = vectorise(map, palette);
    removeCollinearVertices(lines);
    simplifyArcs(lines, desc.epsilon);
    doubleBorderlines(lines, desc.bandWidth);
    return lines;
}

std::vector<double> zoneAreas(const Borderlines& lines) {
    std::vector<double> area(lines.zones.size(), 0.0);
    for (const Edge& e : lines.edges) {
        const Vertex& a = lines.vertices[e.from];
        const Vertex& b = lines.vertices[e.to];
        double c = a.x * b.y - b.x * a.y;
        if (e.left >= 0) area[size_t(e.left)] -= c / 2;
        if (e.right >= 0) area[size_t(e.right)] += c / 2;
    }
    return area;
}

std::string borderlinesToJson(const Borderlines& lines) {
    nlohmann::json doc;
    doc["width"] = lines.mapWidth;
    doc["height"] = lines.mapHeight;
    doc["layout"] = lines.layout == ZoneLayout::Touching ? "touching" : "borderlines";
    doc["frame"] = {lines.frameX0, lines.frameY0, lines.frameX1, lines.frameY1};
    auto& vertices = doc["vertices"] = nlohmann::json::array();
    for (const Vertex& v : lines.vertices) vertices.push_back({v.x, v.y});
    auto& edges = doc["edges"] = nlohmann::json::array();
    for (const Edge& e : lines.edges) edges.push_back({e.from, e.to, e.left, e.right});
    auto& zones = doc["zones"] = nlohmann::json::array();
    for (const Zone& z : lines.zones) {
        nlohmann::json entry{{"id", z.id}, {"name", z.name}, {"colour", colourHex(z.colour)}};
        if (z.bandOf[0] >= 0) entry["bandOf"] = {z.bandOf[0], z.bandOf[1]};
        zones.push_back(entry);
    }
    return doc.dump() + "\n";
}

std::string borderlinesToSvg(const Borderlines& lines, const std::string& imageHref) {
    std::string out;
    char buf[256];
    std::snprintf(
        buf, sizeof buf,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
        "viewBox=\"0 0 %d %d\" width=\"%d\" height=\"%d\">\n",
        lines.mapWidth, lines.mapHeight, std::max(lines.mapWidth, 512),
        int(std::lround(std::max(lines.mapWidth, 512) * double(lines.mapHeight) / lines.mapWidth)));
    out += buf;
    out +=
        "<!-- sierra zones: borderlines (red), band copies (yellow), frame (blue); zone-map pixel "
        "units -->\n";
    if (!imageHref.empty()) {
        std::snprintf(buf, sizeof buf,
                      "<image x=\"0\" y=\"0\" width=\"%d\" height=\"%d\" "
                      "style=\"image-rendering:pixelated\" ",
                      lines.mapWidth, lines.mapHeight);
        out += buf;
        out += "xlink:href=\"" + imageHref + "\" href=\"" + imageHref + "\"/>\n";
    }
    auto isBand = [&](int32_t z) { return z >= 0 && lines.zones[size_t(z)].bandOf[0] >= 0; };
    const char* classes[3] = {"#ff2020", "#ffd000", "#2050ff"};
    for (int c = 0; c < 3; ++c) {
        out += std::string("<path fill=\"none\" stroke=\"") + classes[c] +
               "\" stroke-width=\"1.5\" vector-effect=\"non-scaling-stroke\" "
               "stroke-linecap=\"round\" d=\"";
        for (const Edge& e : lines.edges) {
            int cls = e.left == kOutside || e.right == kOutside ? 2
                      : isBand(e.left) || isBand(e.right)       ? 1
                                                                : 0;
            if (cls != c) continue;
            const Vertex& a = lines.vertices[e.from];
            const Vertex& b = lines.vertices[e.to];
            std::snprintf(buf, sizeof buf, "M%.3f %.3fL%.3f %.3f", a.x, a.y, b.x, b.y);
            out += buf;
        }
        out += "\"/>\n";
    }
    double r = std::max(0.15, std::max(lines.mapWidth, lines.mapHeight) / 1500.0);
    out += "<g fill=\"#202020\">";
    for (const Vertex& v : lines.vertices) {
        std::snprintf(buf, sizeof buf, "<circle cx=\"%.3f\" cy=\"%.3f\" r=\"%.3f\"/>", v.x, v.y, r);
        out += buf;
    }
    out += "</g>\n</svg>\n";
    return out;
}

std::string pngDataUri(const std::vector<uint8_t>& png) {
    static const char* kAlphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out = "data:image/png;base64,";
    out.reserve(out.size() + (png.size() + 2) / 3 * 4);
    for (size_t k = 0; k < png.size(); k += 3) {
        uint32_t n = uint32_t(png[k]) << 16;
        if (k + 1 < png.size()) n |= uint32_t(png[k + 1]) << 8;
        if (k + 2 < png.size()) n |= png[k + 2];
        out += kAlphabet[(n >> 18) & 63];
        out += kAlphabet[(n >> 12) & 63];
        out += k + 1 < png.size() ? kAlphabet[(n >> 6) & 63] : '=';
        out += k + 2 < png.size() ? kAlphabet[n & 63] : '=';
    }
    return out;
}

}  // namespace sierra::zones
