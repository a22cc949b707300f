#pragma once
// Synthetic zone maps shared by the zones unit tests.

#include <sierra/zones/Borderlines.h>

#include <cmath>
#include <functional>

namespace sierra::zones::test {

// A palette of `count` zones "z0".."zN" with distinct colours and no tile files.
inline Palette testPalette(int count) {
    Palette p;
    for (int k = 0; k < count; ++k) {
        SurfaceType s;
        s.name = std::string(1, 'z').append(std::to_string(k));
        s.colour = Colour(0x102030 + 0x203010 * (k + 1));
        p.surfaces.push_back(s);
    }
    return p;
}

inline ZoneMap makeMap(int w, int h, const std::function<int(int, int)>& zoneAt) {
    ZoneMap m;
    m.width = w;
    m.height = h;
    m.ids.resize(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            m.ids[size_t(y) * size_t(w) + size_t(x)] = int16_t(zoneAt(x, y));
    return m;
}

// The four shapes of the tests, Touching layout.
inline ZoneMap squareMap() {
    return makeMap(32, 32,
                   [](int x, int y) { return x >= 8 && x < 20 && y >= 10 && y < 24 ? 1 : 0; });
}
inline ZoneMap discMap() {
    return makeMap(64, 64, [](int x, int y) {
        double dx = x + 0.5 - 32, dy = y + 0.5 - 30;
        return dx * dx + dy * dy < 18.3 * 18.3 ? 1 : 0;
    });
}
inline ZoneMap checkerMap() {
    return makeMap(32, 32, [](int x, int y) { return ((x / 4) + (y / 4)) % 2; });
}
inline ZoneMap junctionMap() {
    // Three zones meeting at one point: top, bottom-left and bottom-right.
    return makeMap(48, 40, [](int x, int y) {
        if (y < 18 + x / 4) return 0;
        return x < 22 - (y - 20) / 3 ? 1 : 2;
    });
}

}  // namespace sierra::zones::test
