// The borderlines of a zone map (Borderlines.h): the arcs doubled into bands
// of a given width (doubleBorderlines), the whole pipeline (buildBorderlines:
// vectorise in Vectorise.cpp, the arc passes in Arcs.cpp, then the bands),
// and the outputs: zone areas, SVG (the JSON form is scene/BorderlinesJson.h).
#include <sierra/zones/Borderlines.h>

#include "zones/Arcs.h"

#include <sierra/core/Error.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <unordered_map>

namespace sierra::zones {

using detail::adjacency;
using detail::Adjacency;
using detail::Arc;
using detail::extractArcs;
using detail::findConflicts;
using detail::junctionsOf;
using detail::rebuild;
using detail::simplifiedChain;

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