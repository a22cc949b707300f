// The border field of a zone map (BorderField.h): per texel its zone
// (fillZones), the nearest borderline segment (nearestSegments) and the
// signed distance to it with the two zones it separates.
#include <sierra/zones/BorderField.h>

#include <sierra/core/Error.h>

#include <algorithm>
#include <cmath>

namespace sierra::zones {
namespace {

// A borderline segment in texel units, ready for point distances.
struct Segment {
    float ax, ay, dx, dy, invLen2;
    uint8_t lo, hi;
};

inline float distance2(const Segment& s, float px, float py) {
    float qx = px - s.ax, qy = py - s.ay;
    float t = std::clamp((qx * s.dx + qy * s.dy) * s.invLen2, 0.0f, 1.0f);
    float ex = qx - t * s.dx, ey = qy - t * s.dy;
    return ex * ex + ey * ey;
}

struct Crossing {
    double x;
    int32_t before, after;  // zone on the -x and +x side of the crossing
};

// f.zone, s texels per map pixel, by an exact scanline fill of the edge
// polygons. Rows are sampled a hair below their centres (and inside the
// frame), so no vertex lies on a scanline and the half-pixel margin of
// Figure 1 maps takes the zone just inside the frame.
void fillZones(const Borderlines& lines, int s, BorderField& f) {
    const int w = f.width, h = f.height;
    const double tiny = 1e-6;
    std::vector<uint32_t> start(size_t(h) + 1, 0);
    auto rowRange = [&](const Edge& e, int& j0, int& j1) {
        double y0 = lines.vertices[e.from].y, y1 = lines.vertices[e.to].y;
        if (y0 == y1) return false;
        double lo = std::min(y0, y1), hi = std::max(y0, y1);
        // rows whose sample y = clamp((j + 0.5) / s + tiny) lies in [lo, hi)
        j0 = std::max(0, int(std::ceil((lo - tiny) * s - 0.5)));
        j1 = std::min(h - 1, int(std::ceil((hi - tiny) * s - 0.5)) - 1);
        // the first and last rows are clamped into the frame: include them when the edge covers
        // the frame's ends
        if (lo <= lines.frameY0) j0 = 0;
        if (hi >= lines.frameY1) j1 = h - 1;
        return j0 <= j1;
    };
    auto sampleY = [&](int j) {
        return std::clamp((j + 0.5) / s + tiny, lines.frameY0 + tiny, lines.frameY1 - tiny);
    };
    for (const Edge& e : lines.edges) {
        int j0, j1;
        if (rowRange(e, j0, j1))
            for (int j = j0; j <= j1; ++j) {
                double y = sampleY(j);
                double y0 = lines.vertices[e.from].y, y1 = lines.vertices[e.to].y;
                if (y >= std::min(y0, y1) && y < std::max(y0, y1)) ++start[size_t(j) + 1];
            }
    }
    for (int j = 0; j < h; ++j) start[size_t(j) + 1] += start[size_t(j)];
    std::vector<Crossing> crossings(start.back());
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (const Edge& e : lines.edges) {
        int j0, j1;
        if (!rowRange(e, j0, j1)) continue;
        const Vertex& a = lines.vertices[e.from];
        const Vertex& b = lines.vertices[e.to];
        // Going down (dy > 0) the left of the edge is its +x side (left = (dy, -dx) as drawn).
        int32_t after = b.y > a.y ? e.left : e.right, before = b.y > a.y ? e.right : e.left;
        for (int j = j0; j <= j1; ++j) {
            double y = sampleY(j);
            if (!(y >= std::min(a.y, b.y) && y < std::max(a.y, b.y))) continue;
            double x = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
            crossings[fill[size_t(j)]++] = {x, before, after};
        }
    }
    for (int j = 0; j < h; ++j) {
        auto first = crossings.begin() + start[size_t(j)],
             last = crossings.begin() + start[size_t(j) + 1];
        std::sort(first, last, [](const Crossing& p, const Crossing& q) { return p.x < q.x; });
        size_t count = size_t(last - first), k = 0;
        int32_t current = kOutside;
        for (int i = 0; i < w; ++i) {
            double x = (i + 0.5) / s;
            while (k < count && first[long(k)].x <= x) current = first[long(k++)].after;
            int32_t zone = current;
            if (zone < 0 && count > 0) zone = k == 0 ? first[0].after : first[long(k) - 1].before;
            f.zone[size_t(j) * size_t(w) + size_t(i)] = uint8_t(std::max(zone, 0));
        }
    }
}

// Per texel of a w x h field: the nearest segment (nearest, all -1 on entry)
// and its squared distance (best, all 3e38 on entry). The texels around every
// segment are seeded with exact distances, then nearest-segment indices are
// propagated in two raster passes (each row both ways), re-measured exactly at
// every texel.
void nearestSegments(const std::vector<Segment>& segments, int w, int h,
                     std::vector<int32_t>& nearest, std::vector<float>& best) {
    auto consider = [&](int i, int j, int32_t seg) {
        size_t p = size_t(j) * size_t(w) + size_t(i);
        if (nearest[p] == seg) return;
        float d = distance2(segments[size_t(seg)], i + 0.5f, j + 0.5f);
        if (d < best[p]) {
            best[p] = d;
            nearest[p] = seg;
        }
    };
    for (size_t k = 0; k < segments.size(); ++k) {
        const Segment& g = segments[k];
        int steps = int(std::ceil(std::sqrt(g.dx * g.dx + g.dy * g.dy) * 2.0f)) + 1;
        for (int t = 0; t <= steps; ++t) {
            float px = g.ax + g.dx * float(t) / float(steps),
                  py = g.ay + g.dy * float(t) / float(steps);
            int ci = int(std::floor(px)), cj = int(std::floor(py));
            for (int j = std::max(cj - 1, 0); j <= std::min(cj + 1, h - 1); ++j)
                for (int i = std::max(ci - 1, 0); i <= std::min(ci + 1, w - 1); ++i)
                    consider(i, j, int32_t(k));
        }
    }
    auto pull = [&](int i, int j, int ni, int nj) {
        if (ni < 0 || nj < 0 || ni >= w || nj >= h) return;
        int32_t seg = nearest[size_t(nj) * size_t(w) + size_t(ni)];
        if (seg >= 0) consider(i, j, seg);
    };
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            pull(i, j, i - 1, j);
            pull(i, j, i - 1, j - 1);
            pull(i, j, i, j - 1);
            pull(i, j, i + 1, j - 1);
        }
        for (int i = w - 1; i >= 0; --i) pull(i, j, i + 1, j);
    }
    for (int j = h - 1; j >= 0; --j) {
        for (int i = w - 1; i >= 0; --i) {
            pull(i, j, i + 1, j);
            pull(i, j, i + 1, j + 1);
            pull(i, j, i, j + 1);
            pull(i, j, i - 1, j + 1);
        }
        for (int i = 0; i < w; ++i) pull(i, j, i - 1, j);
    }
}

}  // namespace

BorderField buildBorderField(const Borderlines& lines, const BorderFieldDesc& desc) {
    const int s = desc.texelsPerPixel;
    SIERRA_CHECK(s >= 1 && s <= 8, "border field: texelsPerPixel must be 1..8, got ", s);
    SIERRA_CHECK(lines.mapWidth > 0 && lines.mapHeight > 0,
                 "border field: the borderlines have no map size");
    SIERRA_CHECK(lines.zones.size() <= 255, "border field: at most 255 zones, got ",
                 lines.zones.size());
    for (const Zone& z : lines.zones)
        SIERRA_CHECK(z.bandOf[0] < 0,
                     "border field: build it from the borderlines before doubling (band zone ",
                     z.name, "); the band is where |signedDistance| < W/2");
    BorderField f;
    f.width = lines.mapWidth * s;
    f.height = lines.mapHeight * s;
    f.texelsPerPixel = s;
    const int w = f.width, h = f.height;
    const size_t n = size_t(w) * size_t(h);
    f.zone.assign(n, 0);
    f.lowZone.assign(n, 0);
    f.highZone.assign(n, 0);
    f.signedDistance.assign(n, 1e9f);

    fillZones(lines, s, f);

    // Nearest borderline segment (nearestSegments).
    std::vector<Segment> segments;
    for (const Edge& e : lines.edges) {
        if (e.left < 0 || e.right < 0) continue;
        const Vertex& a = lines.vertices[e.from];
        const Vertex& b = lines.vertices[e.to];
        float dx = float((b.x - a.x) * s), dy = float((b.y - a.y) * s);
        float len2 = dx * dx + dy * dy;
        segments.push_back({float(a.x * s), float(a.y * s), dx, dy, len2 > 0 ? 1.0f / len2 : 0.0f,
                            uint8_t(std::min(e.left, e.right)),
                            uint8_t(std::max(e.left, e.right))});
    }
    if (segments.empty()) {
        f.lowZone = f.zone;
        f.highZone = f.zone;
        return f;
    }
    std::vector<int32_t> nearest(n, -1);
    std::vector<float> best(n, 3e38f);
    nearestSegments(segments, w, h, nearest, best);

    // Signed distance: negative on the lower zone's side.
    for (size_t p = 0; p < n; ++p) {
        const Segment& g = segments[size_t(nearest[p])];
        float d = std::sqrt(best[p]);
        uint8_t z = f.zone[p];
        if (z == g.lo || z == g.hi) {
            f.lowZone[p] = g.lo;
            f.highZone[p] = g.hi;
            f.signedDistance[p] = z == g.hi ? d : -d;
        } else {
            // Only where the nearest segment is another zones' (a junction's
            // neighbourhood, by propagation error): blend nothing.
            f.lowZone[p] = f.highZone[p] = z;
            f.signedDistance[p] = d;
        }
    }
    return f;
}

}  // namespace sierra::zones
