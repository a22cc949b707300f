#include <sierra/zones/Tiles.h>

#include "Png.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace sierra::zones {
namespace {

constexpr double kPi = 3.14159265358979323846;

uint64_t mix(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// Periodic noise over the unit square [0, 1)^2 (so every tile is seamless):
// value noise on a lattice of `cells` per side, wrapped, quintic fade.
class Noise {
  public:
    explicit Noise(uint64_t seed) : seed_(seed) {}

    double lattice(int cells, int ix, int iy, uint64_t salt) const {
        ix = ((ix % cells) + cells) % cells;
        iy = ((iy % cells) + cells) % cells;
        uint64_t h = mix(seed_ ^ mix(salt * 0x100000001b3ull + uint64_t(cells)) ^
                         mix(uint64_t(ix) << 32 | uint64_t(iy)));
        return double(h >> 11) / double(1ull << 53);  // [0, 1)
    }
    // Value noise in [0, 1).
    double value(double u, double v, int cells, uint64_t salt) const {
        double x = u * cells, y = v * cells;
        int ix = int(std::floor(x)), iy = int(std::floor(y));
        double fx = x - ix, fy = y - iy;
        auto fade = [](double t) { return t * t * t * (t * (t * 6 - 15) + 10); };
        double sx = fade(fx), sy = fade(fy);
        double a = lattice(cells, ix, iy, salt), b = lattice(cells, ix + 1, iy, salt);
        double c = lattice(cells, ix, iy + 1, salt), d = lattice(cells, ix + 1, iy + 1, salt);
        return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
    }
    // Fractal sum of `octaves` octaves from `cells`, gain 0.5, in [0, 1).
    double fbm(double u, double v, int cells, int octaves, uint64_t salt) const {
        double sum = 0, amp = 1, total = 0;
        for (int o = 0; o < octaves; ++o) {
            sum += amp * value(u, v, cells << o, salt + uint64_t(o));
            total += amp;
            amp *= 0.5;
        }
        return sum / total;
    }
    // Worley-like cells: distance to the nearest of one jittered point per cell, ~[0, 1].
    double cellular(double u, double v, int cells, uint64_t salt) const {
        double x = u * cells, y = v * cells;
        int ix = int(std::floor(x)), iy = int(std::floor(y));
        double best = 9;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                double px = ix + dx + lattice(cells, ix + dx, iy + dy, salt);
                double py = iy + dy + lattice(cells, ix + dx, iy + dy, salt + 77);
                best = std::min(best, std::hypot(px - x, py - y));
            }
        return std::min(best, 1.0);
    }
    // Distance to the nearest boundary between two cells of `cellular` (F2 - F1): small on cracks.
    double cellEdge(double u, double v, int cells, uint64_t salt) const {
        double x = u * cells, y = v * cells;
        int ix = int(std::floor(x)), iy = int(std::floor(y));
        double f1 = 9, f2 = 9;
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) {
                double px = ix + dx + lattice(cells, ix + dx, iy + dy, salt);
                double py = iy + dy + lattice(cells, ix + dx, iy + dy, salt + 77);
                double d = std::hypot(px - x, py - y);
                if (d < f1) {
                    f2 = f1;
                    f1 = d;
                } else if (d < f2) {
                    f2 = d;
                }
            }
        return f2 - f1;
    }

  private:
    uint64_t seed_;
};

struct Texel {
    double r, g, b, height;  // colour 0..1, height 0..1
};

double lerp(double a, double b, double t) {
    return a + (b - a) * t;
}
Texel mixColour(Texel a, Texel b, double t) {
    return {lerp(a.r, b.r, t), lerp(a.g, b.g, t), lerp(a.b, b.b, t), lerp(a.height, b.height, t)};
}

Texel shade(const std::string& name, const Noise& n, double u, double v) {
    if (name == "grass") {
        double base = n.fbm(u, v, 4, 5, 1);
        double blades = n.fbm(u * 1.0, v, 64, 2, 2);
        double clumps = n.value(u, v, 8, 3);
        Texel dark{0.20, 0.36, 0.12, 0}, light{0.42, 0.60, 0.22, 0};
        Texel t = mixColour(dark, light,
                            std::clamp(0.3 * base + 0.5 * blades + 0.3 * clumps - 0.05, 0.0, 1.0));
        t.height = std::clamp(0.25 + 0.5 * blades * clumps + 0.2 * base, 0.0, 1.0);
        return t;
    }
    if (name == "sand") {
        double warp = n.fbm(u, v, 4, 3, 10);
        double ripple = 0.5 + 0.5 * std::sin(2 * kPi * (12 * v + 2 * u + 1.5 * warp));
        double grain = n.value(u, v, 128, 11);
        double stones = 1.0 - n.cellular(u, v, 10, 12);
        double pebble = std::clamp((stones - 0.72) * 6, 0.0, 1.0);
        Texel sand{0.80 + 0.06 * grain, 0.71 + 0.05 * grain, 0.50 + 0.04 * grain, 0};
        sand = mixColour(sand, {0.70, 0.60, 0.42, 0}, 0.35 * ripple);
        Texel t = mixColour(sand, {0.55, 0.52, 0.48, 0}, pebble);
        t.height = std::clamp(0.2 + 0.25 * ripple + 0.6 * pebble + 0.05 * grain, 0.0, 1.0);
        return t;
    }
    if (name == "rock") {
        double base = n.fbm(u, v, 4, 6, 20);
        double ridge = 1.0 - std::abs(2 * n.fbm(u, v, 8, 4, 21) - 1);
        // Cracks along cell boundaries, wobbled by noise so they are not straight.
        double crack =
            n.cellEdge(u + 0.03 * n.fbm(u, v, 8, 3, 24), v + 0.03 * n.fbm(u, v, 8, 3, 25), 5, 22);
        Texel grey{0.38 + 0.25 * base, 0.36 + 0.24 * base, 0.34 + 0.22 * base, 0};
        Texel t = mixColour(grey, {0.45, 0.38, 0.30, 0}, n.value(u, v, 4, 23) * 0.5);
        double dark = std::clamp((0.08 - crack) * 14, 0.0, 1.0);
        t = mixColour(t, {0.15, 0.14, 0.13, 0}, dark * 0.7);
        t.height = std::clamp(0.3 + 0.5 * ridge * base + 0.3 * base - 0.3 * dark, 0.0, 1.0);
        return t;
    }
    if (name == "snow") {
        double base = n.fbm(u, v, 4, 5, 30);
        double sparkle = n.value(u, v, 128, 31) > 0.97 ? 1.0 : 0.0;
        Texel t = mixColour({0.80, 0.84, 0.92, 0}, {0.97, 0.97, 0.99, 0}, base);
        t = mixColour(t, {1, 1, 1, 0}, sparkle * 0.8);
        t.height = std::clamp(0.4 + 0.5 * base, 0.0, 1.0);
        return t;
    }
    if (name == "shallow-water") {
        double a = n.fbm(u, v, 6, 3, 40), b = n.fbm(u, v, 6, 3, 41);
        double caustic = std::pow(1.0 - std::abs(a - b) * 4, 6);
        caustic = std::clamp(caustic, 0.0, 1.0);
        Texel t = mixColour({0.16, 0.48, 0.60, 0}, {0.55, 0.82, 0.85, 0},
                            0.7 * caustic + 0.2 * n.fbm(u, v, 4, 4, 42));
        t.height = 0.1 + 0.1 * caustic;
        return t;
    }
    if (name == "deep-water") {
        double base = n.fbm(u, v, 4, 5, 50);
        double swell = 0.5 + 0.5 * std::sin(2 * kPi * (6 * u + 3 * v + 2 * base));
        Texel t = mixColour({0.04, 0.12, 0.32, 0}, {0.10, 0.24, 0.48, 0}, 0.6 * base + 0.3 * swell);
        t.height = 0.05 + 0.05 * swell;
        return t;
    }
    if (name == "earth") {
        double base = n.fbm(u, v, 4, 6, 60);
        double clods = 1.0 - n.cellular(u, v, 16, 61);
        double pebble = std::clamp((clods - 0.8) * 6, 0.0, 1.0);
        Texel t = mixColour({0.30, 0.21, 0.13, 0}, {0.48, 0.36, 0.24, 0}, base);
        t = mixColour(t, {0.52, 0.48, 0.42, 0}, pebble * 0.8);
        t.height = std::clamp(0.3 + 0.4 * base + 0.4 * pebble, 0.0, 1.0);
        return t;
    }
    throw Error(msg("unknown tile \"", name, "\""));
}

}  // namespace

const std::vector<std::string>& tileNames() {
    static const std::vector<std::string> names{"grass",         "sand",       "rock", "snow",
                                                "shallow-water", "deep-water", "earth"};
    return names;
}

TileImage generateTile(const std::string& name, int size, uint64_t seed) {
    const auto& names = tileNames();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
        std::string known;
        for (const auto& k : names) known += (known.empty() ? "" : ", ") + k;
        throw Error(msg("unknown tile \"", name, "\" (known: ", known, ")"));
    }
    SIERRA_CHECK(size >= 16 && size <= 2048 && (size & (size - 1)) == 0,
                 "tile size must be a power of two in 16..2048, got ", size);
    Noise noise(mix(seed));
    TileImage tile;
    tile.size = size;
    tile.rgba.resize(size_t(size) * size_t(size) * 4);
    auto byte = [](double x) { return uint8_t(std::lround(std::clamp(x, 0.0, 1.0) * 255.0)); };
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            Texel t = shade(name, noise, (x + 0.5) / size, (y + 0.5) / size);
            uint8_t* p = &tile.rgba[(size_t(y) * size_t(size) + size_t(x)) * 4];
            p[0] = byte(t.r);
            p[1] = byte(t.g);
            p[2] = byte(t.b);
            p[3] = byte(t.height);
        }
    return tile;
}

TileImage loadTile(const std::string& path) {
    constexpr int kMaxTile = 4096;
    auto bytes = readFileBytes(path);
    if (bytes.size() > size_t(INT32_MAX)) throw Error(msg("tile ", path, ": file too large"));
    int w = 0, h = 0, channels = 0;
    if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels))
        throw Error(msg("tile ", path, " is not an image (", stbi_failure_reason(), ")"));
    SIERRA_CHECK(w == h && w > 0 && w <= kMaxTile, "tile ", path, " is ", w, "x", h,
                 "; tiles are square, 1..", kMaxTile, " per side");
    std::unique_ptr<uint8_t, void (*)(void*)> pixels(
        stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels, 4),
        stbi_image_free);
    if (!pixels) throw Error(msg("tile ", path, " cannot be decoded: ", stbi_failure_reason()));
    TileImage tile;
    tile.size = w;
    tile.rgba.assign(pixels.get(), pixels.get() + size_t(w) * size_t(h) * 4);
    return tile;
}

TileImage blendTiles(const TileImage& first, const TileImage& second, float heightBlend) {
    SIERRA_CHECK(first.size == second.size && first.size > 0, "blending tiles of ", first.size,
                 " and ", second.size, " texels: both must have one size");
    auto smoothstep = [](double e0, double e1, double x) {
        double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
        return t * t * (3.0 - 2.0 * t);
    };
    TileImage out;
    out.size = first.size;
    out.rgba.resize(first.rgba.size());
    for (size_t k = 0; k < out.rgba.size(); k += 4) {
        const uint8_t* a = &first.rgba[k];
        const uint8_t* b = &second.rgba[k];
        // The shader's shift at weight w is strength (hb - ha) 4 w (1 - w): at w = 0.5, strength
        // (hb - ha).
        double weight =
            std::clamp(0.5 + double(heightBlend) * (double(b[3]) - double(a[3])) / 255.0, 0.0, 1.0);
        if (heightBlend > 0.0f) weight = smoothstep(0.15, 0.85, weight);
        for (int c = 0; c < 3; ++c)
            out.rgba[k + size_t(c)] =
                uint8_t(std::lround(double(a[c]) * (1.0 - weight) + double(b[c]) * weight));
        out.rgba[k + 3] = uint8_t((int(a[3]) + int(b[3]) + 1) / 2);
    }
    return out;
}

std::vector<uint8_t> encodeTilePng(const TileImage& tile) {
    return detail::encodePng8(tile.size, tile.size, 4, tile.rgba.data());
}

std::vector<uint8_t> encodeTileSheetPng(const std::vector<TileImage>& tiles) {
    SIERRA_CHECK(!tiles.empty(), "a tile sheet needs at least one tile");
    const int n = tiles[0].size;
    for (const auto& t : tiles)
        SIERRA_CHECK(t.size == n, "tile sheet: all tiles must have one size");
    const int w = n * int(tiles.size()), h = 2 * n;
    std::vector<uint8_t> rgb(size_t(w) * size_t(h) * 3, 0);
    for (size_t k = 0; k < tiles.size(); ++k) {
        const auto& t = tiles[k].rgba;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                // Top: 2x2 repeats at half resolution, texel (2x mod n, 2y mod n).
                const uint8_t* src =
                    &t[(size_t((2 * y) % n) * size_t(n) + size_t((2 * x) % n)) * 4];
                uint8_t* dst = &rgb[(size_t(y) * size_t(w) + k * size_t(n) + size_t(x)) * 3];
                dst[0] = src[0], dst[1] = src[1], dst[2] = src[2];
                uint8_t height = t[(size_t(y) * size_t(n) + size_t(x)) * 4 + 3];
                uint8_t* low = &rgb[(size_t(y + n) * size_t(w) + k * size_t(n) + size_t(x)) * 3];
                low[0] = low[1] = low[2] = height;
            }
    }
    return detail::encodePng8(w, h, 3, rgb.data());
}

}  // namespace sierra::zones
