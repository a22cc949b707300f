#include <sierra/terrain/Maps.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Progress.h>

#include <stb/stb_image_write.h>

// The digits and letters of legends: a small vector font of quads, header-only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wcast-qual"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace sierra::terrain {
namespace {

constexpr double kDegrees = std::numbers::pi / 180.0;

// World-unit height gradient (east, north) at (i, j), Sobel-weighted over the
// 3x3 neighbourhood; row j - 1 is north. A neighbour outside the grid or with
// no data is extrapolated linearly from the centre and the opposite neighbour
// (the centre itself when that is missing too), so a plane is a plane up to
// the edges.
struct Gradient {
    double east, north;
};

Gradient gradientAt(const Heightfield& f, int i, int j) {
    const int w = f.width(), h = f.height();
    auto has = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && f.valid(x, y); };
    const double c = f.at(i, j);
    // Missing diagonal neighbours whose opposite is missing too (corners) are
    // extrapolated from the two axis neighbours: h(di, dj) = h(di, 0) + h(0, dj) - c.
    auto axis = [&](int di, int dj) {
        if (has(i + di, j + dj)) return double(f.at(i + di, j + dj));
        if (has(i - di, j - dj)) return 2.0 * c - double(f.at(i - di, j - dj));
        return c;
    };
    auto height = [&](int di, int dj) {
        if (di == 0 || dj == 0 || has(i + di, j + dj) || has(i - di, j - dj)) return axis(di, dj);
        return axis(di, 0) + axis(0, dj) - c;
    };
    double z[3][3];
    for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) z[dj + 1][di + 1] = height(di, dj);
    const double vs = f.verticalScale();
    const double east = ((z[0][2] + 2 * z[1][2] + z[2][2]) - (z[0][0] + 2 * z[1][0] + z[2][0])) /
                        (8.0 * f.spacingX());
    const double north = ((z[0][0] + 2 * z[0][1] + z[0][2]) - (z[2][0] + 2 * z[2][1] + z[2][2])) /
                         (8.0 * f.spacingZ());
    return {east * vs, north * vs};
}

void appendBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    auto* p = static_cast<const uint8_t*>(data);
    out->insert(out->end(), p, p + size);
}

uint8_t grey8(double v) {
    return uint8_t(std::lround(std::clamp(v, 0.0, 255.0)));
}

std::string tickLabel(double value, double step) {
    const int decimals = step >= 1.0 ? 0 : int(std::ceil(-std::log10(step) - 1e-9));
    if (std::abs(value) < step * 1e-6) value = 0.0;  // no "-0"
    return fixed(value, decimals);
}

}  // namespace

std::vector<float> hillshade(const Heightfield& field, const Sun& sun) {
    SIERRA_CHECK(std::isfinite(sun.azimuth) && std::isfinite(sun.altitude) &&
                     sun.altitude >= 0.0f && sun.altitude <= 90.0f,
                 "sun azimuth ", sun.azimuth, " and altitude ", sun.altitude,
                 " degrees: need a finite azimuth and an altitude in 0..90");
    const double az = sun.azimuth * kDegrees, alt = sun.altitude * kDegrees;
    const double lx = std::sin(az) * std::cos(alt), ly = std::cos(az) * std::cos(alt),
                 lz = std::sin(alt);
    std::vector<float> out(size_t(field.sampleCount()), 0.0f);
    for (int j = 0; j < field.height(); ++j)
        for (int i = 0; i < field.width(); ++i) {
            if (!field.valid(i, j)) continue;
            const Gradient g = gradientAt(field, i, j);
            // Normal of z = f(east, north): (-dz/de, -dz/dn, 1), normalised.
            const double len = std::sqrt(g.east * g.east + g.north * g.north + 1.0);
            const double lit = (-g.east * lx - g.north * ly + lz) / len;
            out[size_t(j) * field.width() + i] = float(255.0 * std::max(0.0, lit));
        }
    return out;
}

std::vector<float> slopeDegrees(const Heightfield& field) {
    std::vector<float> out(size_t(field.sampleCount()), std::numeric_limits<float>::quiet_NaN());
    for (int j = 0; j < field.height(); ++j)
        for (int i = 0; i < field.width(); ++i) {
            if (!field.valid(i, j)) continue;
            const Gradient g = gradientAt(field, i, j);
            out[size_t(j) * field.width() + i] =
                float(std::atan(std::hypot(g.east, g.north)) / kDegrees);
        }
    return out;
}

MapScheme parseMapScheme(const std::string& name) {
    if (name == "plasma") return MapScheme::Plasma;
    if (name == "atlas") return MapScheme::Atlas;
    if (name == "hypsometric") return MapScheme::Hypsometric;
    if (name == "hillshade") return MapScheme::Hillshade;
    if (name == "slope") return MapScheme::Slope;
    throw Error(msg("unknown map scheme '", name,
                    "'; expected plasma, atlas, hypsometric, hillshade or slope"));
}

RgbImage renderMap(const Heightfield& field, MapScheme scheme, const ColourRamp& ramp,
                   const Sun& sun) {
    SIERRA_CHECK(!field.empty(), "cannot draw a map of an empty heightfield");
    RgbImage image{field.width(), field.height(),
                   std::vector<uint8_t>(size_t(field.sampleCount()) * 3)};
    std::vector<float> grey;
    if (scheme == MapScheme::Hillshade) grey = hillshade(field, sun);
    if (scheme == MapScheme::Slope) {
        grey = slopeDegrees(field);
        for (float& s : grey) s = 255.0f * (1.0f - s / 90.0f);  // flat white, vertical black
    }
    for (int j = 0; j < field.height(); ++j)
        for (int i = 0; i < field.width(); ++i) {
            Rgb c = ramp.noDataColour();
            if (field.valid(i, j)) {
                if (grey.empty()) {
                    c = ramp.colourAt(field.at(i, j));
                } else {
                    const uint8_t g = grey8(grey[size_t(j) * field.width() + i]);
                    c = {g, g, g};
                }
            }
            image.set(i, j, c);
        }
    return image;
}

int drawText(RgbImage& image, int x, int y, const std::string& text, Rgb colour, int scale) {
    // A glyph is up to ~12 quads of 4 vertices of 16 bytes: 1 KiB per
    // character is ample (the font silently drops quads that do not fit).
    std::vector<char> vertices(text.size() * 1024 + 1024);
    std::string copy = text;
    const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, vertices.data(),
                                          int(vertices.size()));
    struct Vertex {
        float x, y, z;
        unsigned char rgba[4];
    };
    const auto* v = reinterpret_cast<const Vertex*>(vertices.data());
    for (int q = 0; q < quads; ++q) {
        float x0 = v[4 * q].x, y0 = v[4 * q].y, x1 = x0, y1 = y0;
        for (int k = 1; k < 4; ++k) {
            x0 = std::min(x0, v[4 * q + k].x), x1 = std::max(x1, v[4 * q + k].x);
            y0 = std::min(y0, v[4 * q + k].y), y1 = std::max(y1, v[4 * q + k].y);
        }
        for (int py = y + int(y0) * scale; py < y + int(y1) * scale; ++py)
            for (int px = x + int(x0) * scale; px < x + int(x1) * scale; ++px)
                if (px >= 0 && py >= 0 && px < image.width && py < image.height)
                    image.set(px, py, colour);
    }
    return stb_easy_font_width(copy.data()) * scale;
}

std::vector<LegendTick> addColourBar(RgbImage& image, const ColourRamp& ramp, float unitScale,
                                     const std::string& units, int* barXOut) {
    SIERRA_CHECK(image.width > 0 && image.height > 0, "cannot add a colour bar to an empty image");
    SIERRA_CHECK(std::isfinite(unitScale) && unitScale > 0.0f,
                 "legend unit scale must be > 0, got ", unitScale);
    const int h = image.height;
    const int scale = std::max(1, h / 200);  // font pixels: ~7 per line at scale 1
    const double lo = ramp.desc().minHeight, hi = ramp.desc().maxHeight;
    const double loU = lo * unitScale, hiU = hi * unitScale;

    // "Nice" step: 1, 2 or 5 times a power of ten, about 5 ticks over the range.
    const double raw = (hiU - loU) / 5.0;
    const double p10 = std::pow(10.0, std::floor(std::log10(raw)));
    const double m = raw / p10;
    const double step = (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * p10;
    std::vector<LegendTick> ticks;
    for (double v = std::ceil(loU / step - 1e-9) * step; v <= hiU + step * 1e-9; v += step) {
        const int row = int(std::lround((hiU - v) / (hiU - loU) * (h - 1)));
        ticks.push_back({v, std::clamp(row, 0, h - 1), tickLabel(v, step)});
    }
    if (!units.empty() && !ticks.empty()) ticks.back().label += " " + units;

    const int gap = std::max(2, image.width / 50);
    const int bar = std::max(8, image.width / 16);
    const int tick =
        3 * scale;  // drawn from inside the bar out, then a gap: not read as a minus sign
    int labelWidth = 0;
    for (auto& t : ticks) {
        std::string s = t.label;
        labelWidth = std::max(labelWidth, stb_easy_font_width(s.data()) * scale);
    }
    const int barX = image.width + gap;
    // The font's width leaves out the last glyph's right edge: a margin of 6.
    const int width = barX + bar + tick + 3 * scale + labelWidth + 6 * scale;
    RgbImage out{width, h, std::vector<uint8_t>(size_t(width) * h * 3, 255)};
    for (int y = 0; y < h; ++y) {
        std::copy_n(image.rgb.data() + size_t(y) * image.width * 3, size_t(image.width) * 3,
                    out.rgb.data() + size_t(y) * width * 3);
        const double t = h > 1 ? double(y) / double(h - 1) : 0.0;
        const Rgb c = ramp.colourAt(float(hi - (hi - lo) * t));  // top row = maxHeight
        for (int x = barX; x < barX + bar; ++x) out.set(x, y, c);
    }
    constexpr Rgb kInk{0, 0, 0};
    const int textHeight = 7 * scale;
    for (const auto& t : ticks) {
        for (int x = barX + bar - bar / 3; x < barX + bar + tick; ++x)
            for (int y = t.row; y < std::min(h, t.row + std::max(1, scale / 2)); ++y)
                out.set(x, y, kInk);
        const int ty = std::clamp(t.row - textHeight / 2, 0, std::max(0, h - textHeight));
        drawText(out, barX + bar + tick + 3 * scale, ty, t.label, kInk, scale);
    }
    image = std::move(out);
    if (barXOut) *barXOut = barX;
    return ticks;
}

void writeRgbPng(const std::string& path, const RgbImage& image) {
    SIERRA_CHECK(image.width > 0 && image.height > 0, "cannot write ", path,
                 ": the image is empty");
    std::vector<uint8_t> png;
    if (!stbi_write_png_to_func(appendBytes, &png, image.width, image.height, 3, image.rgb.data(),
                                image.width * 3))
        throw Error(msg("cannot write ", path, ": PNG encoding failed for a ", image.width, "x",
                        image.height, " image"));
    writeFileAtomic(path, png);
}

void writeGreyPng(const std::string& path, int width, int height, std::span<const uint8_t> grey) {
    SIERRA_CHECK(width > 0 && height > 0 && grey.size() == size_t(width) * size_t(height),
                 "cannot write ", path, ": a ", width, "x", height, " grey image needs ",
                 int64_t(width) * height, " bytes, got ", grey.size());
    std::vector<uint8_t> png;
    if (!stbi_write_png_to_func(appendBytes, &png, width, height, 1, grey.data(), width))
        throw Error(msg("cannot write ", path, ": PNG encoding failed for a ", width, "x", height,
                        " image"));
    writeFileAtomic(path, png);
}

}  // namespace sierra::terrain
