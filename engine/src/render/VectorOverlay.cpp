#include <sierra/render/VectorOverlay.h>

#include <sierra/core/Error.h>
#include <sierra/core/Parallel.h>

#include <algorithm>
#include <cmath>

namespace sierra::render {

using terrain::VectorFeature;

namespace {

struct Point {
    double x, y;  // texels of one level
};

// The polyline in a level's texels, reduced to points at least half a texel
// apart (the last one kept), so a coarse level draws the path, not every
// vertex of it.
std::vector<Point> levelPath(std::span<const analysis::LineVertex> line, double perSampleX,
                             double perSampleY) {
    std::vector<Point> out;
    for (size_t k = 0; k < line.size(); ++k) {
        // Sample i's centre is texel (i + 0.5) * perSample: the drape's mapping.
        const Point p{(line[k].x + 0.5) * perSampleX, (line[k].z + 0.5) * perSampleY};
        if (!out.empty() && k + 1 < line.size() &&
            std::hypot(p.x - out.back().x, p.y - out.back().y) < 0.5)
            continue;
        out.push_back(p);
    }
    return out;
}

// One level: each polyline's coverage (antialiased, 1 inside width / 2,
// falling to 0 over one texel; the largest over the polyline's segments, so
// joints do not darken), dashed by arc length, composed over `rgba`.
void rasteriseLevel(const LineLayer& layer, int w, int h, double perSampleX, double perSampleY,
                    std::vector<float>& coverage, std::vector<uint8_t>& rgba) {
    const LineStyle& st = layer.style;
    const double half = 0.5 * st.width, reach = half + 0.5;
    const double period = st.dashOn > 0.0f ? double(st.dashOn) + st.dashOff : 0.0;
    std::fill(coverage.begin(), coverage.end(), 0.0f);
    for (size_t k = 0; k < layer.lines->polylineCount(); ++k) {
        const std::vector<Point> path = levelPath(layer.lines->polyline(k), perSampleX, perSampleY);
        double along = 0.0;
        for (size_t s = 1; s < path.size(); ++s) {
            const Point a = path[s - 1], b = path[s];
            const double dx = b.x - a.x, dy = b.y - a.y, length2 = dx * dx + dy * dy;
            const double length = std::sqrt(length2);
            const int x0 = std::max(0, int(std::floor(std::min(a.x, b.x) - reach)));
            const int x1 = std::min(w - 1, int(std::ceil(std::max(a.x, b.x) + reach)));
            const int y0 = std::max(0, int(std::floor(std::min(a.y, b.y) - reach)));
            const int y1 = std::min(h - 1, int(std::ceil(std::max(a.y, b.y) + reach)));
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x) {
                    const double px = x + 0.5 - a.x, py = y + 0.5 - a.y;
                    const double t =
                        length2 > 0.0 ? std::clamp((px * dx + py * dy) / length2, 0.0, 1.0) : 0.0;
                    if (period > 0.0 && std::fmod(along + t * length, period) >= st.dashOn)
                        continue;
                    const double d = std::hypot(px - t * dx, py - t * dy);
                    const float c = float(std::clamp(reach - d, 0.0, 1.0));
                    float& cell = coverage[size_t(y) * size_t(w) + size_t(x)];
                    cell = std::max(cell, c);
                }
            along += length;
        }
    }
    for (size_t t = 0; t < coverage.size(); ++t) {
        const float a = coverage[t] * st.colour.a;
        if (a <= 0.0f) continue;
        uint8_t* p = &rgba[4 * t];
        for (int c = 0; c < 3; ++c)
            p[c] = uint8_t(std::lround(st.colour[c] * a * 255.0f + float(p[c]) * (1.0f - a)));
        p[3] = uint8_t(std::lround(a * 255.0f + float(p[3]) * (1.0f - a)));
    }
}

}  // namespace

LinePyramid rasteriseLines(std::span<const LineLayer> layers, int gridWidth, int gridHeight,
                           int maxSide) {
    SIERRA_CHECK(gridWidth > 0 && gridHeight > 0 && maxSide >= 1, "line texture: bad grid ",
                 gridWidth, "x", gridHeight);
    for (const LineLayer& l : layers)
        SIERRA_CHECK(
            l.lines && l.style.width > 0.0f && l.style.dashOn >= 0.0f && l.style.dashOff >= 0.0f,
            "line texture: a layer needs lines, a width > 0 and dashes >= 0");
    LinePyramid p;
    p.texelsPerSample = float(std::min(2.0, double(maxSide) / std::max(gridWidth, gridHeight)));
    p.width = std::max(1, int(std::lround(gridWidth * double(p.texelsPerSample))));
    p.height = std::max(1, int(std::lround(gridHeight * double(p.texelsPerSample))));
    int count = 1;
    while (p.levelWidth(count - 1) > 1 || p.levelHeight(count - 1) > 1) ++count;
    p.levels.resize(size_t(count));
    parallelFor(0, count, [&](int64_t level) {
        const int w = p.levelWidth(int(level)), h = p.levelHeight(int(level));
        std::vector<uint8_t>& rgba = p.levels[size_t(level)];
        rgba.assign(size_t(w) * size_t(h) * 4, 0);
        std::vector<float> coverage(size_t(w) * size_t(h));
        for (const LineLayer& layer : layers)
            rasteriseLevel(layer, w, h, double(w) / gridWidth, double(h) / gridHeight, coverage,
                           rgba);
    });
    return p;
}

analysis::LineSet vectorLines(const terrain::VectorLayer& layer, bool outlines, float step) {
    SIERRA_CHECK(step > 0.0f && std::isfinite(step), "vector lines: step must be > 0, got ", step);
    analysis::LineSet lines;
    auto add = [&](const std::vector<terrain::GridPoint>& part) {
        if (part.size() < 2) return;
        lines.vertices.push_back({float(part[0].i), float(part[0].j), 1.0f});
        for (size_t k = 1; k < part.size(); ++k) {
            const double di = part[k].i - part[k - 1].i, dj = part[k].j - part[k - 1].j;
            const int pieces = std::max(1, int(std::ceil(std::hypot(di, dj) / step)));
            for (int p = 1; p <= pieces; ++p) {
                const double t = double(p) / pieces;
                lines.vertices.push_back(
                    {float(part[k - 1].i + t * di), float(part[k - 1].j + t * dj), 1.0f});
            }
        }
        lines.offsets.push_back(uint32_t(lines.vertices.size()));
    };
    for (const VectorFeature& f : layer.features) {
        if (f.kind == VectorFeature::Kind::Line) add(f.parts[0]);
        if (f.kind == VectorFeature::Kind::Polygon && outlines)
            for (const auto& ring : f.parts) add(ring);
    }
    return lines;
}

terrain::DrapeImage polygonDrape(const terrain::VectorLayer& layer, int gridWidth, int gridHeight,
                                 glm::vec4 colour, float opacity, int texelsPerSample) {
    SIERRA_CHECK(gridWidth > 0 && gridHeight > 0 && texelsPerSample >= 1, "polygon fill: bad grid ",
                 gridWidth, "x", gridHeight);
    SIERRA_CHECK(opacity >= 0.0f && opacity <= 1.0f, "polygon fill: opacity is 0..1, got ",
                 opacity);
    terrain::DrapeImage d;
    d.width = gridWidth * texelsPerSample;
    d.height = gridHeight * texelsPerSample;
    d.rgba.assign(size_t(d.width) * size_t(d.height) * 4, 0);
    const uint8_t rgb[3] = {uint8_t(std::lround(std::clamp(colour.r, 0.0f, 1.0f) * 255.0f)),
                            uint8_t(std::lround(std::clamp(colour.g, 0.0f, 1.0f) * 255.0f)),
                            uint8_t(std::lround(std::clamp(colour.b, 0.0f, 1.0f) * 255.0f))};
    const uint8_t alpha = uint8_t(std::lround(opacity * 255.0f));
    const double k = texelsPerSample;
    std::vector<double> crossings;
    size_t filled = 0;
    for (const VectorFeature& f : layer.features) {
        if (f.kind != VectorFeature::Kind::Polygon) continue;
        double j0 = INFINITY, j1 = -INFINITY;
        for (const auto& p : f.parts[0]) j0 = std::min(j0, p.j), j1 = std::max(j1, p.j);
        // Texel rows whose centres (v + 0.5) / k - 0.5 lie within the outer ring.
        const int v0 = std::max(0, int(std::floor((j0 + 0.5) * k - 0.5)));
        const int v1 = std::min(d.height - 1, int(std::ceil((j1 + 0.5) * k - 0.5)));
        for (int v = v0; v <= v1; ++v) {
            const double j = (v + 0.5) / k - 0.5;
            crossings.clear();
            for (const auto& ring : f.parts)
                for (size_t e = 0; e + 1 < ring.size(); ++e) {
                    const auto& a = ring[e];
                    const auto& b = ring[e + 1];
                    if ((a.j <= j) == (b.j <= j)) continue;  // half-open: each vertex counted once
                    crossings.push_back(a.i + (j - a.j) / (b.j - a.j) * (b.i - a.i));
                }
            std::sort(crossings.begin(), crossings.end());
            for (size_t c = 0; c + 1 < crossings.size(); c += 2) {
                // Texel columns whose centres (u + 0.5) / k - 0.5 lie in [x0, x1).
                const int u0 = std::max(0, int(std::ceil((crossings[c] + 0.5) * k - 0.5)));
                const int u1 =
                    std::min(d.width - 1, int(std::ceil((crossings[c + 1] + 0.5) * k - 0.5)) - 1);
                for (int u = u0; u <= u1; ++u) {
                    uint8_t* t = &d.rgba[(size_t(v) * size_t(d.width) + size_t(u)) * 4];
                    if (t[3] == 0) ++filled;
                    t[0] = rgb[0], t[1] = rgb[1], t[2] = rgb[2], t[3] = alpha;
                }
            }
        }
    }
    d.coverage = double(filled) / (double(d.width) * d.height);
    return d;
}

glm::vec3 surfacePoint(const terrain::Heightfield& field, double i, double j) {
    const int i0 = std::clamp(int(std::floor(i)), 0, field.width() - 1);
    const int j0 = std::clamp(int(std::floor(j)), 0, field.height() - 1);
    const int i1 = std::min(i0 + 1, field.width() - 1), j1 = std::min(j0 + 1, field.height() - 1);
    const float fi = float(std::clamp(i - i0, 0.0, 1.0)), fj = float(std::clamp(j - j0, 0.0, 1.0));
    const float h = (1 - fi) * (1 - fj) * field.worldHeight(i0, j0) +
                    fi * (1 - fj) * field.worldHeight(i1, j0) +
                    (1 - fi) * fj * field.worldHeight(i0, j1) + fi * fj * field.worldHeight(i1, j1);
    return {float(i) * field.spacingX(), h, float(j) * field.spacingZ()};
}

std::vector<Label> vectorLabels(const terrain::VectorLayer& layer,
                                const terrain::Heightfield& field) {
    std::vector<Label> labels;
    for (const VectorFeature& f : layer.features) {
        if (f.kind != VectorFeature::Kind::Point && f.label.empty()) continue;
        const terrain::GridPoint p = f.parts[0][0];
        if (p.i < 0.0 || p.j < 0.0 || p.i > field.width() - 1.0 || p.j > field.height() - 1.0)
            continue;
        // Points first, then labelled lines and areas.
        labels.push_back({f.label, surfacePoint(field, p.i, p.j),
                          f.kind == VectorFeature::Kind::Point ? 1.0f : 0.0f});
    }
    return labels;
}

}  // namespace sierra::render
