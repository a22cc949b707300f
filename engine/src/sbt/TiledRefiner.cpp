#include <sierra/sbt/TiledRefiner.h>

#include <sierra/core/Error.h>
#include <sierra/sbt/TileFile.h>

#include <algorithm>
#include <cmath>

namespace sierra::sbt {

TiledVertices::TiledVertices(const TiledGridDesc& desc) : desc_(desc) {
    SIERRA_CHECK(desc.n >= 1 && desc.n <= 30 && desc.k >= 1 && desc.k <= desc.n,
                 "a tiled grid needs 1 <= k <= n <= 30, got n ", desc.n, ", k ", desc.k);
}

// One refinement's walk: ExactWalk.h's view recursion (Refiner::refineViewReference)
// with the usable rule on top. Above the tiles (levels < tileLevel) every
// vertex is a tile corner and every test is the reference's, in double. A
// triangle of level tileLevel is half a tile: below it the walk keeps the
// tile's records, its usable levels (its own, and along each edge the least
// of it and the neighbour across) and what it reached, and takes the tests
// as FastWalk.h does: in float, the double reference inside the guard band.
struct TiledRefiner::Walk {
    const TiledVertices& tiles;
    const std::vector<int>& usable;  // per tile, levels
    std::vector<uint8_t>& reached;   // per tile: the tile levels the walk reached
    TiledMesh& out;
    const size_t* levelStart;   // per tile level, its first record
    const VertexRecord* zeros;  // the records of a tile that holds none
    int n, k, tileLevel, finest, tilesPerSide;
    uint32_t side, T;
    double ex, ey, ez, sx, sz, vs, kE;
    float fex, fey, fez, fsx, fsz, fvs, fkE;
    float distanceSlack;  // absolute slack on squared distances (world units^2)
    float planeSlack[6];  // absolute slack on plane distances (world units)
    Plane planes[6];
    bool needStart = true;
    int parity = -1;
    int64_t leaves = 0, culled = 0;
    size_t stripBegin = 0;

    // The tile being walked: origin, records, usable and reached levels of its
    // interior and of its edges x = 0, x = T, y = 0, y = T.
    uint32_t i0 = 0, j0 = 0;
    const VertexRecord* rec = nullptr;
    int uInner = 0, uEdge[4] = {};
    uint8_t rInner = 0, rEdge[4] = {};
    int tile = 0, edgeTile[4] = {};  // -1: the grid's border

    static constexpr unsigned kAllPlanes = 0x3f;
    static constexpr unsigned kCulled = 0x80;

    // The reference's tests, in double.
    unsigned cull(double x, double y, double z, float r, unsigned mask) const {
        for (int p = 0; p < 6; ++p) {
            if (!(mask & (1u << p))) continue;
            const Plane& pl = planes[p];
            const double s = pl.a * x + pl.b * y + pl.c * z + pl.d;
            if (s < -double(r)) return kCulled;
            if (s >= double(r)) mask &= ~(1u << p);
        }
        return mask;
    }
    bool active(double x, double y, double z, const VertexRecord& v) const {
        const double dx = x - ex, dy = y - ey, dz = z - ez;
        const double reach = kE * double(v.error) + double(v.radius);
        return reach * reach > dx * dx + dy * dy + dz * dz;
    }

    // The same in float where the float result is certain (FastWalk.h's
    // cullFast and activeFast, the slacks of Refiner::setUpWalker).
    unsigned cullFast(uint32_t i, uint32_t j, float x, float y, float z, const VertexRecord& v,
                      unsigned mask) const {
        const float r = v.radius;
        for (int p = 0; p < 6; ++p) {
            if (!(mask & (1u << p))) continue;
            const Plane& pl = planes[p];
            const float s = pl.a * x + pl.b * y + pl.c * z + pl.d;
            const float slack = planeSlack[p];
            if (s < -r - slack) return kCulled;
            if (s >= r + slack) {
                mask &= ~(1u << p);
                continue;
            }
            if (s >= -r + slack && s < r - slack) continue;  // straddles for sure
            const double sd =
                pl.a * (i * sx) + pl.b * (double(v.height) * vs) + pl.c * (j * sz) + pl.d;
            if (sd < -double(r)) return kCulled;
            if (sd >= double(r)) mask &= ~(1u << p);
        }
        return mask;
    }
    bool activeFast(uint32_t i, uint32_t j, float x, float y, float z,
                    const VertexRecord& v) const {
        const float dx = x - fex, dy = y - fey, dz = z - fez;
        const float d2 = dx * dx + dy * dy + dz * dz;
        const float reach = fkE * v.error + v.radius;
        const float r2 = reach * reach;
        const float slack = 0x1.0p-17f * (r2 + d2) + distanceSlack;
        if (r2 > d2 + slack) return true;
        if (r2 < d2 - slack) return false;
        return active(i * sx, double(v.height) * vs, j * sz, v);
    }

    // Closes the strip begun at stripBegin: dropped when it draws nothing;
    // else its first vertex (the entry, written twice) dropped when that
    // makes it decode clockwise in (i, j), as Refiner's strips do
    // (StripWriter.h's StripJoin).
    void finishStrip() {
        std::vector<uint64_t>& s = out.strip;
        const size_t count = s.size() - stripBegin;
        for (size_t k = 0; k + 2 < count; ++k) {
            const uint64_t v0 = s[stripBegin + k], v1 = s[stripBegin + k + 1],
                           v2 = s[stripBegin + k + 2];
            if (v0 == v1 || v1 == v2 || v0 == v2) continue;
            auto i = [](uint64_t v) { return int64_t(uint32_t(v)); };
            auto j = [](uint64_t v) { return int64_t(v >> 32); };
            const int64_t g = (i(v1) - i(v0)) * (j(v2) - j(v0)) - (j(v1) - j(v0)) * (i(v2) - i(v0));
            // Decoded clockwise iff (g > 0) == (its position is odd).
            if ((int64_t(k) & 1) != (g > 0 ? 1 : 0)) s.erase(s.begin() + ptrdiff_t(stripBegin));
            return;
        }
        s.resize(stripBegin > 0 ? stripBegin - 1 : 0);  // nothing drawn: gone, with its restart
    }

    void start(uint64_t a) {
        if (!out.strip.empty()) {
            finishStrip();
            if (!out.strip.empty()) out.strip.push_back(kTiledRestart);
        }
        stripBegin = out.strip.size();
        out.strip.push_back(a);
        out.strip.push_back(a);
        parity = -1;
        needStart = false;
    }

    // Lindstrom and Pascucci's tstrip-append, as StripWriter.h's appendToStrip.
    void append(uint64_t v, int p) {
        if (needStart) return;
        std::vector<uint64_t>& s = out.strip;
        const size_t size = s.size();
        if (v == s[size - 1] || v == s[size - 2]) return;
        if (p == parity)
            s.push_back(s[size - 2]);
        else
            parity = p;
        s.push_back(v);
    }

    void leaf(uint64_t a, uint64_t q, int l) {
        if (needStart) start(a);
        append(q, l & 1);
        ++leaves;
    }

    // Above the tiles: every split vertex is a tile corner.
    void top(uint64_t a, uint64_t q, uint64_t b, int l, unsigned mask) {
        if (l == tileLevel) {
            enterTile(a, q, b, l, mask);
            return;
        }
        const uint64_t m = (a + b) >> 1;  // lane-wise: both coordinate sums are even
        const uint32_t i = uint32_t(m), j = uint32_t(m >> 32);
        const VertexRecord v = tiles.corner(i, j);
        const double x = i * sx, y = double(v.height) * vs, z = j * sz;
        if (mask) {
            mask = cull(x, y, z, v.radius, mask);
            if (mask == kCulled) {
                ++culled;
                needStart = true;
                return;
            }
        }
        if (needStart) start(a);
        if (!active(x, y, z, v)) {
            append(q, l & 1);
            ++leaves;
            return;
        }
        top(a, m, q, l + 1, mask);
        append(q, l & 1);
        top(q, m, b, l + 1, mask);
    }

    // Half a tile: its split vertex m is the tile's centre.
    void enterTile(uint64_t a, uint64_t q, uint64_t b, int l, unsigned mask) {
        const uint64_t m = (a + b) >> 1;
        const int tx = int(uint32_t(m) >> k), ty = int(uint32_t(m >> 32) >> k);
        tile = ty * tilesPerSide + tx;
        i0 = uint32_t(tx) << k, j0 = uint32_t(ty) << k;
        rec = tiles.tileRecords(tx, ty);
        if (!rec) rec = zeros;
        uInner = usable[size_t(tile)];
        const int nb[4] = {tx > 0 ? tile - 1 : -1, tx + 1 < tilesPerSide ? tile + 1 : -1,
                           ty > 0 ? tile - tilesPerSide : -1,
                           ty + 1 < tilesPerSide ? tile + tilesPerSide : -1};
        for (int e = 0; e < 4; ++e) {
            edgeTile[e] = nb[e];
            uEdge[e] = nb[e] < 0 ? uInner : std::min(uInner, usable[size_t(nb[e])]);
            rEdge[e] = 0;
        }
        rInner = 0;
        if (l < finest)
            node(a, q, b, l, mask, recordIndex(uint64_t(m) - (uint64_t(j0) << 32 | i0), 0));
        else
            leaf(a, q, l);
        uint8_t& own = reached[size_t(tile)];
        own = std::max({own, rInner, rEdge[0], rEdge[1], rEdge[2], rEdge[3]});
        for (int e = 0; e < 4; ++e)
            if (edgeTile[e] >= 0)
                reached[size_t(edgeTile[e])] = std::max(reached[size_t(edgeTile[e])], rEdge[e]);
    }

    // The record index of tile-local vertex (x, y) of tile level t.
    size_t recordIndex(uint64_t local, int t) const {
        return levelStart[t] +
               TileAddressing::indexInLevel(uint32_t(local), uint32_t(local >> 32), t, k);
    }

    // Triangle (a, q, b) at level l (tileLevel <= l < finest) inside the
    // tile, `at` the record of its split vertex.
    [[gnu::always_inline]] inline void node(uint64_t a, uint64_t q, uint64_t b, int l,
                                            unsigned mask, size_t at) {
        const uint64_t m = (a + b) >> 1;
        const uint32_t i = uint32_t(m), j = uint32_t(m >> 32);
        const uint32_t x = i - i0, y = j - j0;
        const int t = l - tileLevel;
        int u;
        uint8_t* r;
        if (x - 1 < T - 1 && y - 1 < T - 1) {  // 0 < x, y < T: inside, most vertices
            u = uInner;
            r = &rInner;
        } else {
            const int e = x == 0 ? 0 : x == T ? 1 : y == 0 ? 2 : 3;
            u = uEdge[e];
            r = &rEdge[e];
        }
        *r = std::max(*r, uint8_t(t + 1));
        if (t >= u) {  // not usable: not known to be outside, drawn whole, coarse
            leaf(a, q, l);
            return;
        }
        const VertexRecord& v = rec[at];
        const float fx = float(i) * fsx, fy = v.height * fvs, fz = float(j) * fsz;
        if (mask) {
            mask = cullFast(i, j, fx, fy, fz, v, mask);
            if (mask == kCulled) {
                ++culled;
                needStart = true;
                return;
            }
        }
        if (needStart) start(a);
        if (!activeFast(i, j, fx, fy, fz, v)) {
            append(q, l & 1);
            ++leaves;
            return;
        }
        split(a, q, b, l, mask, m);
    }

    // Splits (a, q, b) at m. The children's records are fetched first: the
    // level-ordered records of a tile lie far apart (a miss per vertex).
    void split(uint64_t a, uint64_t q, uint64_t b, int l, unsigned mask, uint64_t m) {
        if (l + 1 < finest) {
            const uint64_t origin = uint64_t(j0) << 32 | i0;
            const int t = l + 1 - tileLevel;
            const size_t first = recordIndex(((a + q) >> 1) - origin, t),
                         second = recordIndex(((q + b) >> 1) - origin, t);
            __builtin_prefetch(rec + first);
            __builtin_prefetch(rec + second);
            if (l + 2 < finest) {  // and the grandchildren's, a level ahead
                __builtin_prefetch(rec + recordIndex(((a + m) >> 1) - origin, t + 1));
                __builtin_prefetch(rec + recordIndex(((m + q) >> 1) - origin, t + 1));
                __builtin_prefetch(rec + recordIndex(((m + b) >> 1) - origin, t + 1));
            }
            node(a, m, q, l + 1, mask, first);
            append(q, l & 1);
            node(q, m, b, l + 1, mask, second);
        } else {
            leaf(a, m, l + 1);
            append(q, l & 1);
            leaf(q, m, l + 1);
        }
    }
};

TiledRefiner::TiledRefiner(const TiledVertices& tiles) : tiles_(tiles) {
    const TiledGridDesc& g = tiles.desc();
    const TileAddressing address(g.k);
    for (int t = 0; t <= 2 * g.k; ++t) levelStart_.push_back(address.countBelow(t));
    zeros_.assign(levelStart_.back(), VertexRecord{});
    // Every vertex is a corner or descends from the grid's centre, a corner,
    // and lies within a corner's saturated radius of it (the radius holds its
    // descendants' distances): |y| + r over the corners bounds every height
    // and radius, as Refiner::measureMagnitude's maximum does.
    const uint32_t T = uint32_t(1) << g.k;
    const double vs = std::fabs(double(g.verticalScale));
    double largest = 0.0;
    for (int cy = 0; cy <= tiles.tilesPerSide(); ++cy)
        for (int cx = 0; cx <= tiles.tilesPerSide(); ++cx) {
            const VertexRecord c = tiles.corner(uint32_t(cx) * T, uint32_t(cy) * T);
            largest = std::max(largest, std::fabs(double(c.height)) * vs + double(c.radius));
        }
    const double extent = double(uint64_t(1) << g.n);
    magnitude_ = std::max({largest, extent * double(g.spacingX), extent * double(g.spacingZ), 1.0});
}

void TiledRefiner::refineView(const ViewParams& view, TiledMesh& out) {
    SIERRA_CHECK(view.tau > 0.0f && view.lambda > 0.0f,
                 "tiled refinement: tau and lambda must be > 0, got ", view.tau, ", ", view.lambda);
    const TiledGridDesc& g = tiles_.desc();
    const int t = tiles_.tilesPerSide();
    // Resident depths, balanced: D(T) = min over U of d(U) + |T - U|_1, by the
    // two passes of a city-block distance transform.
    usable_.assign(size_t(t) * size_t(t), 0);
    for (int ty = 0; ty < t; ++ty)
        for (int tx = 0; tx < t; ++tx)
            usable_[size_t(ty) * size_t(t) + size_t(tx)] =
                std::clamp(tiles_.residentLevels(tx, ty), 0, 2 * g.k);
    auto at = [&](int tx, int ty) -> int& { return usable_[size_t(ty) * size_t(t) + size_t(tx)]; };
    for (int ty = 0; ty < t; ++ty)
        for (int tx = 0; tx < t; ++tx) {
            if (tx > 0) at(tx, ty) = std::min(at(tx, ty), at(tx - 1, ty) + 1);
            if (ty > 0) at(tx, ty) = std::min(at(tx, ty), at(tx, ty - 1) + 1);
        }
    for (int ty = t - 1; ty >= 0; --ty)
        for (int tx = t - 1; tx >= 0; --tx) {
            if (tx + 1 < t) at(tx, ty) = std::min(at(tx, ty), at(tx + 1, ty) + 1);
            if (ty + 1 < t) at(tx, ty) = std::min(at(tx, ty), at(tx, ty + 1) + 1);
        }
    reached_.assign(usable_.size(), 0);

    out.strip.clear();
    Walk w{.tiles = tiles_,
           .usable = usable_,
           .reached = reached_,
           .out = out,
           .levelStart = levelStart_.data(),
           .zeros = zeros_.data(),
           .n = g.n,
           .k = g.k,
           .tileLevel = 2 * (g.n - g.k),
           .finest = 2 * g.n,
           .tilesPerSide = t,
           .side = (uint32_t(1) << g.n) + 1,
           .T = uint32_t(1) << g.k,
           .ex = view.eye[0],
           .ey = view.eye[1],
           .ez = view.eye[2],
           .sx = g.spacingX,
           .sz = g.spacingZ,
           .vs = g.verticalScale,
           .kE = double(view.lambda) / double(view.tau)};
    // The fast walk's float view and slacks (Refiner::setUpWalker): every
    // coordinate, eye and radius at most M in magnitude.
    const double M = std::max({magnitude_, std::fabs(w.ex), std::fabs(w.ey), std::fabs(w.ez)});
    w.fex = view.eye[0], w.fey = view.eye[1], w.fez = view.eye[2];
    w.fsx = g.spacingX, w.fsz = g.spacingZ, w.fvs = g.verticalScale;
    w.fkE = float(w.kE);
    w.distanceSlack = float(0x1.0p-22 * M * M);
    for (int p = 0; p < 6; ++p) {
        w.planes[p] = view.planes[size_t(p)];
        w.planeSlack[p] = float(0x1.0p-19 * (3.0 * M + std::fabs(double(view.planes[p].d))));
    }
    const unsigned mask = view.cull ? Walk::kAllPlanes : 0u;
    // The two level-0 triangles, as Refiner's top: entry (0,0), apex (0,S),
    // exit (S,S); entry (S,S), apex (S,0), exit (0,0).
    const uint64_t S = w.side - 1;
    const uint64_t v00 = 0, v0S = S << 32, vSS = S | (S << 32), vS0 = S;
    w.top(v00, v0S, vSS, 0, mask);
    w.append(vSS, 0);
    w.top(vSS, vS0, v00, 0, mask);
    w.append(v00, 0);
    if (!out.strip.empty()) w.finishStrip();
    out.triangleCount = w.leaves;
    out.culledSubtrees = w.culled;
    out.coarseTiles = 0;
    for (size_t t = 0; t < reached_.size(); ++t) out.coarseTiles += reached_[t] > usable_[t];
}

std::vector<std::array<uint32_t, 3>> decodeTiledStrip(const std::vector<uint64_t>& strip,
                                                      int side) {
    std::vector<uint32_t> linear;
    linear.reserve(strip.size());
    for (uint64_t v : strip)
        linear.push_back(v == kTiledRestart
                             ? kRestartIndex
                             : uint32_t(v >> 32) * uint32_t(side) + uint32_t(v & 0xffffffffu));
    return decodeStrip(linear);
}

InMemoryTiles::InMemoryTiles(const terrain::Heightfield& field, const VertexErrors& errors, int k)
    : TiledVertices({.n = errors.n,
                     .k = k,
                     .spacingX = field.spacingX(),
                     .spacingZ = field.spacingZ(),
                     .verticalScale = field.verticalScale()}),
      field_(field),
      errors_(errors) {
    SIERRA_CHECK(field.width() == errors.side && field.height() == errors.side,
                 "in-memory tiles: the errors are not of this field");
    const TileAddressing address(k);
    const int T = 1 << k, P = tilesPerSide();
    packed_.resize(size_t(P) * size_t(P));
    for (int ty = 0; ty < P; ++ty)
        for (int tx = 0; tx < P; ++tx) {
            std::vector<VertexRecord>& records = packed_[size_t(ty) * size_t(P) + size_t(tx)];
            records.resize(address.countBelow(2 * k));
            for (int y = 0; y <= T; ++y)
                for (int x = 0; x <= T; ++x) {
                    if ((x == 0 || x == T) && (y == 0 || y == T)) continue;  // a corner
                    records[address.index(x, y)] =
                        vertex(uint32_t(tx * T + x), uint32_t(ty * T + y));
                }
        }
    setAllResident(2 * k);
}

int InMemoryTiles::residentLevels(int tx, int ty) const {
    return resident_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)];
}

const VertexRecord* InMemoryTiles::tileRecords(int tx, int ty) const {
    return packed_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)].data();
}

VertexRecord InMemoryTiles::corner(uint32_t i, uint32_t j) const {
    return vertex(i, j);
}

VertexRecord InMemoryTiles::vertex(uint32_t i, uint32_t j) const {
    const size_t index = size_t(j) * size_t(errors_.side) + size_t(i);
    return {field_.samples()[index], errors_.error[index], errors_.radius[index]};
}

void InMemoryTiles::setAllResident(int levels) {
    resident_.assign(size_t(tilesPerSide()) * size_t(tilesPerSide()), levels);
}

void InMemoryTiles::setResident(int tx, int ty, int levels) {
    SIERRA_CHECK(tx >= 0 && ty >= 0 && tx < tilesPerSide() && ty < tilesPerSide(),
                 "in-memory tiles: no tile ", tx, ", ", ty);
    resident_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)] = levels;
}

}  // namespace sierra::sbt
