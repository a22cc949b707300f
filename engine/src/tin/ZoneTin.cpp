#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Timer.h>
#include <sierra/tin/ZoneTin.h>
#include <sierra/zones/Tiles.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <utility>
#include <vector>

namespace sierra::tin {

Constraints::Vertex mapToGrid(double mapX, double mapY, int mapWidth, int mapHeight, int gridWidth,
                              int gridHeight) {
    return {(mapX - 0.5) * double(gridWidth - 1) / double(mapWidth - 1),
            (mapY - 0.5) * double(gridHeight - 1) / double(mapHeight - 1)};
}

namespace {

// A zone map and a grid the TIN can relate: each at least 2x2.
void checkSizes(int mapWidth, int mapHeight, int gridWidth, int gridHeight) {
    SIERRA_CHECK(mapWidth >= 2 && mapHeight >= 2,
                 "a zone map for a TIN needs at least 2x2 pixels, got ", mapWidth, "x", mapHeight);
    SIERRA_CHECK(gridWidth >= 2 && gridHeight >= 2,
                 "a TIN needs a grid of at least 2x2 samples, got ", gridWidth, "x", gridHeight);
}

// Is (x, y) inside the closed polygon made of `edges` (even-odd rule)?
bool insideEdges(const zones::Borderlines& lines, const std::vector<uint32_t>& edges, double x,
                 double y) {
    bool inside = false;
    for (uint32_t k : edges) {
        const zones::Vertex& a = lines.vertices[lines.edges[k].from];
        const zones::Vertex& b = lines.vertices[lines.edges[k].to];
        if ((a.y > y) != (b.y > y) && x < a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y))
            inside = !inside;
    }
    return inside;
}

// The convex hull of the vertices `vs` (monotone chain; collinear points dropped).
std::vector<zones::Vertex> convexHull(const zones::Borderlines& lines,
                                      const std::vector<uint32_t>& vs) {
    std::vector<zones::Vertex> points;
    points.reserve(vs.size());
    for (uint32_t v : vs) points.push_back(lines.vertices[v]);
    std::sort(points.begin(), points.end(), [](const zones::Vertex& a, const zones::Vertex& b) {
        return a.x < b.x || (a.x == b.x && a.y < b.y);
    });
    if (points.size() < 3) return points;
    auto cross = [](const zones::Vertex& o, const zones::Vertex& a, const zones::Vertex& b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    std::vector<zones::Vertex> hull(2 * points.size());
    size_t k = 0;
    for (size_t i = 0; i < points.size(); ++i) {  // lower chain
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
        while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    hull.resize(k - 1);
    return hull;
}

// An island: a closed loop of edges without a junction, its component's root.
struct Island {
    uint32_t root;
    double x0, y0, x1, y1;  // bounding box
};

// Whether the loop (an island's edges, at least 3) is thin: every vertex
// within epsilon of a longest chord. *box: the island and its bounding box.
bool thinIsland(const zones::Borderlines& lines, const std::vector<uint32_t>& loop, uint32_t root,
                double epsilon, Island* box) {
    std::vector<uint32_t> vs;
    for (uint32_t k : loop) vs.push_back(lines.edges[k].from);
    // A strip within epsilon of a chord no longer than the box's diagonal
    // has an area of at most 2 epsilon x diagonal: a cheap test first.
    *box = Island{root, 1e300, 1e300, -1e300, -1e300};
    double twiceArea = 0.0;
    const int32_t inside = lines.edges[loop[0]].left;
    for (uint32_t k : loop) {
        const zones::Edge& e = lines.edges[k];
        const zones::Vertex& a = lines.vertices[e.left == inside ? e.from : e.to];
        const zones::Vertex& b = lines.vertices[e.left == inside ? e.to : e.from];
        twiceArea += a.x * b.y - b.x * a.y;
        box->x0 = std::min(box->x0, a.x), box->y0 = std::min(box->y0, a.y);
        box->x1 = std::max(box->x1, a.x), box->y1 = std::max(box->y1, a.y);
    }
    const double diagonal = std::hypot(box->x1 - box->x0, box->y1 - box->y0);
    if (0.5 * std::fabs(twiceArea) > 2.0 * epsilon * diagonal) return false;
    // The longest chord joins two corners of the convex hull: the pairs are
    // tried over the hull only (a long thin island has thousands of
    // vertices, its hull a few dozen). The island is thin when every vertex
    // lies within epsilon of a longest chord (of any, where several tie).
    const std::vector<zones::Vertex> hull = convexHull(lines, vs);
    double longest = 0.0;
    std::vector<std::pair<size_t, size_t>> chords;
    for (size_t i = 0; i < hull.size(); ++i)
        for (size_t j = i + 1; j < hull.size(); ++j) {
            const double d = (hull[i].x - hull[j].x) * (hull[i].x - hull[j].x) +
                             (hull[i].y - hull[j].y) * (hull[i].y - hull[j].y);
            if (d > longest) longest = d, chords.clear();
            if (d == longest && d > 0.0) chords.emplace_back(i, j);
        }
    const double length = std::sqrt(longest);
    bool within = false;
    for (size_t c = 0; c < chords.size() && !within; ++c) {
        const zones::Vertex& p = hull[chords[c].first];
        const zones::Vertex& q = hull[chords[c].second];
        within = true;
        for (size_t i = 0; i < vs.size() && within; ++i) {
            const zones::Vertex& s = lines.vertices[vs[i]];
            within = std::fabs((q.x - p.x) * (s.y - p.y) - (q.y - p.y) * (s.x - p.x)) <=
                     epsilon * length;
        }
    }
    return within;
}

}  // namespace

size_t removeThinIslands(zones::Borderlines& lines, double epsilon) {
    if (!(epsilon > 0.0)) return 0;
    const size_t nv = lines.vertices.size();
    const std::vector<bool> pinned = zones::junctions(lines);
    // The edges' connected components (union-find); an island is a component
    // without a junction: one closed loop with one zone pair all along.
    std::vector<uint32_t> parent(nv);
    for (uint32_t v = 0; v < nv; ++v) parent[v] = v;
    auto root = [&](uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const zones::Edge& e : lines.edges) parent[root(e.from)] = root(e.to);
    std::vector<uint8_t> hasJunction(nv, 0);
    for (uint32_t v = 0; v < nv; ++v)
        if (pinned[v]) hasJunction[root(v)] = 1;
    std::vector<std::vector<uint32_t>> loopEdges(nv);
    for (uint32_t k = 0; k < lines.edges.size(); ++k)
        if (!hasJunction[root(lines.edges[k].from)])
            loopEdges[root(lines.edges[k].from)].push_back(k);

    std::vector<Island> thin;
    for (uint32_t r = 0; r < nv; ++r) {
        const std::vector<uint32_t>& loop = loopEdges[r];
        if (loop.size() < 3) continue;
        Island box;
        if (thinIsland(lines, loop, r, epsilon, &box)) thin.push_back(box);
    }
    // An island with a kept borderline inside stays: removing it would leave
    // that borderline's outer zone (the island's) inside another zone. Keeping
    // one may keep an island around it in turn, so this repeats until stable.
    // Borderlines never cross, so a component lies inside an island when one
    // of its vertices does: one vertex per component, sorted by x, is tested.
    std::vector<uint8_t> removed(nv, 0);
    for (const Island& i : thin) removed[i.root] = 1;
    std::vector<uint32_t> witnesses;  // one vertex of each component, by x
    {
        std::vector<uint8_t> seen(nv, 0);
        for (const zones::Edge& e : lines.edges)
            if (!seen[root(e.from)]) seen[root(e.from)] = 1, witnesses.push_back(e.from);
    }
    std::sort(witnesses.begin(), witnesses.end(),
              [&](uint32_t a, uint32_t b) { return lines.vertices[a].x < lines.vertices[b].x; });
    auto byX = [&](uint32_t v, double x) { return lines.vertices[v].x <= x; };
    for (bool changed = true; changed;) {
        changed = false;
        for (const Island& i : thin) {
            if (!removed[i.root]) continue;
            for (auto w = std::partition_point(witnesses.begin(), witnesses.end(),
                                               [&](uint32_t v) { return byX(v, i.x0); });
                 w != witnesses.end() && lines.vertices[*w].x < i.x1; ++w) {
                const zones::Vertex& s = lines.vertices[*w];
                if (removed[root(*w)] || s.y <= i.y0 || s.y >= i.y1) continue;
                if (insideEdges(lines, loopEdges[i.root], s.x, s.y)) {
                    removed[i.root] = 0;
                    changed = true;
                    break;
                }
            }
        }
    }
    size_t count = 0;
    for (const Island& i : thin) count += removed[i.root];
    if (count == 0) return 0;
    std::vector<zones::Edge> edges;
    std::vector<int64_t> remap(nv, -1);
    for (const zones::Edge& e : lines.edges)
        if (!removed[root(e.from)]) {
            edges.push_back(e);
            remap[e.from] = remap[e.to] = 0;
        }
    std::vector<zones::Vertex> vertices;
    for (uint32_t v = 0; v < nv; ++v)
        if (remap[v] >= 0) {
            remap[v] = int64_t(vertices.size());
            vertices.push_back(lines.vertices[v]);
        }
    for (zones::Edge& e : edges) {
        e.from = uint32_t(remap[e.from]);
        e.to = uint32_t(remap[e.to]);
    }
    lines.vertices.swap(vertices);
    lines.edges.swap(edges);
    return count;
}

zones::Borderlines gridBorderlines(const zones::ZoneMap& map, const zones::Palette& palette,
                                   const zones::BorderlineDesc& desc, int gridWidth, int gridHeight,
                                   size_t* removedIslands) {
    checkSizes(map.width, map.height, gridWidth, gridHeight);
    SIERRA_CHECK(std::isfinite(desc.epsilon) && desc.epsilon >= 0.0,
                 "borderlines: epsilon must be >= 0 pixels, got ", desc.epsilon);
    // zones::buildBorderlines without the band, with thin islands removed before rule 3.
    zones::Borderlines lines = zones::vectorise(map, palette);
    zones::removeCollinearVertices(lines);
    const size_t islands = removeThinIslands(lines, desc.epsilon);
    if (removedIslands) *removedIslands = islands;
    zones::simplifyArcs(lines, desc.epsilon);
    const double sx = double(map.width - 1) / double(gridWidth - 1);
    const double sy = double(map.height - 1) / double(gridHeight - 1);
    auto snap = [&](const zones::Vertex& v) {
        const Constraints::Vertex g =
            mapToGrid(v.x, v.y, map.width, map.height, gridWidth, gridHeight);
        const double x = std::clamp(std::floor(g.x + 0.5), 0.0, double(gridWidth - 1));
        const double y = std::clamp(std::floor(g.y + 0.5), 0.0, double(gridHeight - 1));
        return zones::Vertex{x * sx + 0.5, y * sy + 0.5};
    };
    for (zones::Vertex& v : lines.vertices) v = snap(v);
    zones::removeDuplicateVertices(lines);
    zones::doubleBorderlines(lines, desc.bandWidth, snap);
    return lines;
}

Constraints constraintsFromBorderlines(const zones::Borderlines& lines, int gridWidth,
                                       int gridHeight) {
    checkSizes(lines.mapWidth, lines.mapHeight, gridWidth, gridHeight);
    Constraints c;
    c.vertices.reserve(lines.vertices.size());
    for (const zones::Vertex& v : lines.vertices)
        c.vertices.push_back(
            mapToGrid(v.x, v.y, lines.mapWidth, lines.mapHeight, gridWidth, gridHeight));
    c.segments.reserve(lines.edges.size());
    bool haveDefault = false;
    for (const zones::Edge& e : lines.edges) {
        if (e.left < 0 && e.right < 0)
            continue;  // no zone on either side: nothing to seed or separate
        // The zones' "left as drawn" (y down) is where cross(b - a, p - a) < 0, the
        // TIN's right. A frame edge: its outside has no triangle, so the inside
        // zone goes on both sides.
        const int32_t left = e.right >= 0 ? e.right : e.left;
        const int32_t right = e.left >= 0 ? e.left : e.right;
        if (!haveDefault && (e.left < 0 || e.right < 0)) c.defaultZone = left, haveDefault = true;
        c.segments.push_back(
            {.a = int32_t(e.from), .b = int32_t(e.to), .leftZone = left, .rightZone = right});
    }
    for (const zones::Zone& z : lines.zones)
        if (z.bandOf[0] >= 0)
            c.bands.push_back({.zone = z.id, .first = z.bandOf[0], .second = z.bandOf[1]});
    return c;
}

ZoneAgreement zoneAgreement(const TinMesh& mesh, const zones::ZoneMap& map) {
    SIERRA_CHECK(map.width >= 2 && map.height >= 2 && mesh.gridWidth >= 2 && mesh.gridHeight >= 2,
                 "zone agreement needs a map and a grid of at least 2x2, got ", map.width, "x",
                 map.height, " and ", mesh.gridWidth, "x", mesh.gridHeight);
    // Grid units per pixel; pixel (i, j)'s centre lies at (i sx, j sy), moved
    // by the tie-breaking offset (see the header) and back inside at the far edges.
    constexpr double kNudgeX = 1.3e-4, kNudgeY = 0.7e-4;
    const double sx = double(mesh.gridWidth - 1) / double(map.width - 1);
    const double sy = double(mesh.gridHeight - 1) / double(map.height - 1);
    auto centreX = [&](int i) {
        return i == map.width - 1 ? double(mesh.gridWidth - 1) - kNudgeX : i * sx + kNudgeX;
    };
    auto centreY = [&](int j) {
        return j == map.height - 1 ? double(mesh.gridHeight - 1) - kNudgeY : j * sy + kNudgeY;
    };
    std::vector<uint8_t> counted(size_t(map.width) * size_t(map.height), 0);
    ZoneAgreement result;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        double px[3], py[3];
        for (int k = 0; k < 3; ++k) {
            const GridPoint& g = mesh.vertices[size_t(mesh.triangles[t][size_t(k)])];
            px[k] = double(g.x);
            py[k] = double(g.y);
        }
        const double area = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
        if (area == 0.0) continue;
        // The pixels whose centres the bounding box can hold (one pixel of margin for the offset).
        const int i0 = std::max(0, int(std::floor(std::min({px[0], px[1], px[2]}) / sx)) - 1);
        const int i1 =
            std::min(map.width - 1, int(std::ceil(std::max({px[0], px[1], px[2]}) / sx)) + 1);
        const int j0 = std::max(0, int(std::floor(std::min({py[0], py[1], py[2]}) / sy)) - 1);
        const int j1 =
            std::min(map.height - 1, int(std::ceil(std::max({py[0], py[1], py[2]}) / sy)) + 1);
        const int32_t s0 = mesh.surfaces[t][0], s1 = mesh.surfaces[t][1];
        for (int j = j0; j <= j1; ++j) {
            const double y = centreY(j);
            for (int i = i0; i <= i1; ++i) {
                const double x = centreX(i);
                bool inside = true;
                for (int k = 0; k < 3 && inside; ++k) {
                    const int n = (k + 1) % 3;
                    const double e = (px[n] - px[k]) * (y - py[k]) - (py[n] - py[k]) * (x - px[k]);
                    inside = (area > 0 ? e : -e) > 0.0;
                }
                if (!inside) continue;
                const size_t p = size_t(j) * size_t(map.width) + size_t(i);
                if (counted[p]) continue;
                counted[p] = 1;
                const int zone = map.ids[p];
                if (zone == zones::kBorderlinePixel) continue;
                ++result.pixels;
                result.agree += (zone == s0 || zone == s1) ? 1 : 0;
            }
        }
    }
    return result;
}

ObjOptions zoneMaterials(const std::string& objPath, const TinMesh& mesh,
                         const zones::Palette& palette, int mapWidth, int mapHeight) {
    SIERRA_CHECK(mapWidth >= 2 && mapHeight >= 2 && mesh.gridWidth >= 2 && mesh.gridHeight >= 2,
                 "zone materials need a map and a grid of at least 2x2, got ", mapWidth, "x",
                 mapHeight, " and ", mesh.gridWidth, "x", mesh.gridHeight);
    namespace fs = std::filesystem;
    const fs::path obj(objPath);
    const fs::path folder = obj.parent_path().empty() ? fs::path(".") : obj.parent_path();
    ObjOptions options;
    auto reference = [&](const std::string& file) {
        std::error_code ec;
        fs::path rel = fs::proximate(fs::path(file), folder, ec);
        return ec || rel.empty() ? fs::absolute(file).string() : rel.generic_string();
    };
    // Grid samples per zone-map pixel on each axis.
    const double gx = double(mesh.gridWidth - 1) / double(mapWidth - 1);
    const double gy = double(mesh.gridHeight - 1) / double(mapHeight - 1);
    options.uvOffset = {0.5 * gx, 0.5 * gy};
    for (size_t s = 0; s < palette.surfaces.size(); ++s) {
        options.surfaceColours[int32_t(s)] = palette.surfaces[s].colour;
        const double size = double(palette.surfaces[s].tileSize);
        options.surfacePeriods[int32_t(s)] = {size * gx, size * gy};
        if (!palette.surfaces[s].tile.empty())
            options.tileImages[int32_t(s)] = reference(palette.surfaces[s].tile);
    }
    std::set<std::pair<int32_t, int32_t>> bands;
    for (const auto& s : mesh.surfaces)
        if (s[0] != s[1]) bands.insert({s[0], s[1]});
    for (const auto& [a, b] : bands) {
        SIERRA_CHECK(a >= 0 && b >= 0 && size_t(a) < palette.surfaces.size() &&
                         size_t(b) < palette.surfaces.size(),
                     "band of surfaces ", a, " and ", b, ": the palette has ",
                     palette.surfaces.size(), " surfaces");
        const zones::SurfaceType& first = palette.surfaces[size_t(a)];
        const zones::SurfaceType& second = palette.surfaces[size_t(b)];
        if (first.tile.empty() || second.tile.empty()) continue;
        zones::TileImage blend =
            zones::blendTiles(zones::loadTile(first.tile), zones::loadTile(second.tile),
                              0.5f * (first.heightBlend + second.heightBlend));
        const std::string name = msg(obj.stem().string(), "_band_", a, "_", b, ".png");
        writeFileAtomic((folder / name).string(), zones::encodeTilePng(blend));
        options.bandImages[{a, b}] = name;
    }
    return options;
}

double budgetEpsilon(int64_t triangles, int gridWidth, int gridHeight, const zones::ZoneMap& map,
                     double least) {
    const double area = double(gridWidth - 1) * double(gridHeight - 1);
    const double samples = 0.45 * std::sqrt(area / double(std::max<int64_t>(triangles, 1)));
    const double pixelsPerSample = 0.5 * (double(map.width - 1) / double(gridWidth - 1) +
                                          double(map.height - 1) / double(gridHeight - 1));
    return std::max(least, samples * pixelsPerSample);
}

int64_t budgetTriangles(const TinDesc& desc) {
    if (desc.maxTriangles > 0 && desc.maxPoints > 0)
        return std::min(desc.maxTriangles, 2 * desc.maxPoints);
    return desc.maxTriangles > 0 ? desc.maxTriangles : std::max<int64_t>(0, 2 * desc.maxPoints);
}

ZonedTin buildZonedTin(const terrain::Heightfield& field, const zones::ZoneMap& map,
                       const zones::Palette& palette, const TinDesc& desc,
                       const ZonedTinDesc& zoned) {
    SIERRA_CHECK(zoned.epsilon >= 0.0, "the borderline epsilon is ", zoned.epsilon,
                 " px; it must be >= 0");
    const bool errorTarget = desc.maxError > 0.0 || desc.maxErrorRel > 0.0;
    const int64_t triangles = budgetTriangles(desc);
    ZonedTin z;
    z.autoEpsilon = zoned.autoEpsilon && triangles > 0 && !errorTarget;
    z.epsilon = z.autoEpsilon
                    ? budgetEpsilon(triangles, field.width(), field.height(), map, zoned.epsilon)
                    : zoned.epsilon;
    while (true) {
        Stopwatch clock;
        z.islandsRemoved = 0;
        z.lines =
            gridBorderlines(map, palette, {.epsilon = z.epsilon, .bandWidth = zoned.bandWidth},
                            field.width(), field.height(), &z.islandsRemoved);
        z.constraints = constraintsFromBorderlines(z.lines, field.width(), field.height());
        z.borderlinesMs += clock.ms();
        z.result = buildTin(field, z.constraints, desc);
        ++z.builds;
        z.agreement = zoneAgreement(z.result.mesh, map);
        if (!z.autoEpsilon || z.agreement.fraction() >= zoned.leastAgreement ||
            z.epsilon <= zoned.epsilon)
            return z;
        const double next = std::max(zoned.epsilon, z.epsilon / 2);
        if (zoned.retry) zoned.retry(z.agreement.fraction(), z.epsilon, next);
        z.epsilon = next;
    }
}

}  // namespace sierra::tin
