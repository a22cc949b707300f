#pragma once
// The JSON export of zones::Borderlines (sierra-gen zones --json, docs/zones.md).

#include <sierra/zones/Borderlines.h>

#include <string>

namespace sierra::scene {

// JSON: {"width", "height", "layout", "frame": [x0, y0, x1, y1],
//        "vertices": [[x, y], ...], "edges": [[from, to, leftZone, rightZone], ...],
//        "zones": [{"id", "name", "colour": "#rrggbb", "band_of": [a, b]?}, ...]},
// keys in alphabetical order, on one line ending with a newline.
std::string borderlinesToJson(const zones::Borderlines& lines);

}  // namespace sierra::scene
