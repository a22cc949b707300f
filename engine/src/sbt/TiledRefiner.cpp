#include <sierra/sbt/TiledRefiner.h>

#include <sierra/core/Error.h>

#include <algorithm>

namespace sierra::sbt {

TiledVertices::TiledVertices(const TiledGridDesc& desc) : desc_(desc) {
    SIERRA_CHECK(desc.n >= 1 && desc.n <= 30 && desc.k >= 1 && desc.k <= desc.n,
                 "a tiled grid needs 1 <= k <= n <= 30, got n ", desc.n, ", k ", desc.k);
}

// One refinement's walk: ExactWalk.h's view recursion (Refiner::refineViewReference)
// with the vertex data read through the tiles and the usable rule on top.
struct TiledRefiner::Walk {
    const TiledVertices& tiles;
    const std::vector<int>& usable;  // per tile, levels
    std::vector<uint8_t>& reached;   // per tile: the tile levels the walk reached
    TiledMesh& out;
    int n, k, tileLevel, finest, tilesPerSide;
    uint32_t side;
    double ex, ey, ez, sx, sz, vs, kE;
    Plane planes[6];
    bool needStart = true;
    int parity = -1;
    int64_t leaves = 0, culled = 0;

    static constexpr unsigned kAllPlanes = 0x3f;
    static constexpr unsigned kCulled = 0x80;

    // The tiles holding vertex coordinate c along one axis: one, or two on a border.
    int tilesAlong(uint32_t c, int t[2]) const {
        const uint32_t mask = (uint32_t(1) << k) - 1;
        int count = 0;
        if ((c & mask) == 0 && c > 0) t[count++] = int((c - 1) >> k);
        if (int(c >> k) < tilesPerSide) t[count++] = int(c >> k);
        return count;
    }

    // The usable levels at vertex (i, j) of tile level `local`: the least over
    // the tiles holding it; each of them records that the walk reached it.
    bool usableAt(uint32_t i, uint32_t j, int local) {
        const uint32_t mask = (uint32_t(1) << k) - 1;
        if ((i & mask) != 0 && (j & mask) != 0) {  // inside one tile: most vertices
            const size_t t = size_t(j >> k) * size_t(tilesPerSide) + size_t(i >> k);
            reached[t] = std::max(reached[t], uint8_t(local + 1));
            return local < usable[t];
        }
        int ti[2], tj[2];
        const int ni = tilesAlong(i, ti), nj = tilesAlong(j, tj);
        int least = 2 * k;
        for (int a = 0; a < ni; ++a)
            for (int b = 0; b < nj; ++b)
                least =
                    std::min(least, usable[size_t(tj[b]) * size_t(tilesPerSide) + size_t(ti[a])]);
        for (int a = 0; a < ni; ++a)
            for (int b = 0; b < nj; ++b) {
                uint8_t& w = reached[size_t(tj[b]) * size_t(tilesPerSide) + size_t(ti[a])];
                w = std::max(w, uint8_t(local + 1));
            }
        return local < least;
    }

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

    size_t stripBegin = 0;

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

    void refine(uint64_t a, uint64_t q, uint64_t b, int l, unsigned mask) {
        if (l < finest) {
            const uint64_t m = (a + b) >> 1;  // lane-wise: both coordinate sums are even
            const uint32_t i = uint32_t(m), j = uint32_t(m >> 32);
            const bool readable = l < tileLevel || usableAt(i, j, l - tileLevel);
            if (readable) {
                const VertexRecord v = tiles.vertex(i, j);
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
                const double dx = x - ex, dy = y - ey, dz = z - ez;
                const double reach = kE * double(v.error) + double(v.radius);
                if (reach * reach > dx * dx + dy * dy + dz * dz) {
                    refine(a, m, q, l + 1, mask);
                    append(q, l & 1);
                    refine(q, m, b, l + 1, mask);
                    return;
                }
            } else if (needStart) {
                start(a);  // not known to be outside: drawn whole, coarse
            }
        } else if (needStart) {
            start(a);
        }
        append(q, l & 1);
        ++leaves;
    }
};

TiledRefiner::TiledRefiner(const TiledVertices& tiles) : tiles_(tiles) {}

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
    Walk w{tiles_,
           usable_,
           reached_,
           out,
           g.n,
           g.k,
           2 * (g.n - g.k),
           2 * g.n,
           t,
           (uint32_t(1) << g.n) + 1,
           view.eye[0],
           view.eye[1],
           view.eye[2],
           g.spacingX,
           g.spacingZ,
           g.verticalScale,
           double(view.lambda) / double(view.tau)};
    for (int p = 0; p < 6; ++p) w.planes[p] = view.planes[size_t(p)];
    const unsigned mask = view.cull ? Walk::kAllPlanes : 0u;
    // The two level-0 triangles, as Refiner's top: entry (0,0), apex (0,S),
    // exit (S,S); entry (S,S), apex (S,0), exit (0,0).
    const uint64_t S = w.side - 1;
    const uint64_t v00 = 0, v0S = S << 32, vSS = S | (S << 32), vS0 = S;
    w.refine(v00, v0S, vSS, 0, mask);
    w.append(vSS, 0);
    w.refine(vSS, vS0, v00, 0, mask);
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
    setAllResident(2 * k);
}

int InMemoryTiles::residentLevels(int tx, int ty) const {
    return resident_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)];
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
