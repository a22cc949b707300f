// The zone map's borderlines as a graph (Borderlines.h, vectorise): one
// vertex per lattice position, an edge wherever two zones meet, in either
// layout of the map (pixels touching, or Figure 1's pixel centres). The arc
// passes over the graph are in Arcs.cpp, the bands in Borderlines.cpp.
#include <sierra/zones/Borderlines.h>

#include <sierra/core/Error.h>

#include <cmath>
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

}  // namespace sierra::zones
