#pragma once
// Rendering styles built on the curvature analysis, as data: which layers to
// draw (the plain shaded terrain, curvature lines, hatches, contour edges) and
// the parameters of each, read from the "style" object of a scene file. The
// presets assets/presets/fig3a.json ... fig3n.json (line shading) and
// fig4a.json ... fig4h.json (hatch shading) are such fragments.
//
// JSON form (every key optional; unknown keys are errors, to catch typos):
//   "style": {
//     "description": "free text",
//     "styles": ["shaded", "lines", "hatch", "contours"],   // any combination
//     "curvature": {"method": "two-normal" | "three-normal" | "three-vertex" | "edge-angle",
//                   "distance": 1,          // reinforcement distance, integer >= 1 (1 = none)
//                   "scale": 1.0,           // >= 0, or "auto" (StyleParams::autoScale)
//                   "normals": "quad",      // "edge" | "triangle" | "quad"
//                   "signed": false,
//                   "levels": {"black": 0, "white": 1, "gamma": 1}},   // present = on
//     "lines": {"min_length": 5,            // vertices, >= 2
//               "width": 1.0,               // pixels, > 0
//               "threshold": 0.5,           // curvature needed, >= 0
//               "polarity": "any",          // "any" | "ridges" | "valleys"
//               "blended": false},          // the refinement of Lines.h
//     "hatch": {"length": 0.75,             // grid units, > 0
//               "width": 1.0,               // pixels, > 0
//               "direction": "along"},      // "along" | "across"
//     "contours": false
//   }
// Without "styles", the layers are "shaded" plus "lines" / "hatch" where their
// objects are present; "contours": true adds contour edges either way
// (contradicting "styles" is an error).

#include <sierra/analysis/Curvature.h>
#include <sierra/analysis/Hatch.h>
#include <sierra/analysis/Lines.h>

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <string_view>

namespace sierra::analysis {

struct StyleLayers {
    bool shaded = true;     // the plain shaded terrain
    bool lines = false;     // curvature lines (line shading)
    bool hatch = false;     // hatch strokes (hatch shading)
    bool contours = false;  // view-dependent contour edges
    bool operator==(const StyleLayers&) const = default;

    // Turns on the layer named `name` (shaded, lines, hatch or contours);
    // false for any other name, which is left to the caller to report.
    bool enable(std::string_view name);
};

// The layer names StyleLayers::enable takes, for messages.
inline constexpr const char* kStyleLayerNames = "shaded, lines, hatch or contours";

struct LineStyle {
    int minLength = 5;       // shortest polyline kept, in vertices (Figure 3 "Min. Len")
    float width = 1.0f;      // pixels
    float threshold = 0.5f;  // curvature a vertex needs, after scale and levels
    LinePolarity polarity = LinePolarity::Any;
    bool blended = false;  // blended directions (LineOptions::blended)
    bool operator==(const LineStyle&) const = default;
};

struct HatchStyle {
    float length = 0.75f;  // stroke length in grid units (Figure 4 "Hatch Len.")
    float width = 1.0f;    // pixels
    HatchDirection direction = HatchDirection::Along;  // Figure 4 "With" = along, "Perp." = across
    bool operator==(const HatchStyle&) const = default;
};

struct StyleParams {
    std::string description;
    StyleLayers layers;
    CurvatureOptions curvature;  // method, normals, distance, scale, levels, signed
    // "scale": "auto": the curvature scale is chosen per terrain rather than
    // taken from curvature.scale, so that the top 5% of the samples (by their
    // largest value) reach the line threshold, or with hatches alone full
    // opacity (render::autoCurvatureScale). Not with levels.
    bool autoScale = false;
    LineStyle lines;
    HatchStyle hatch;
    bool operator==(const StyleParams&) const = default;
};

// The LineOptions that trace this style's lines.
LineOptions lineOptions(const StyleParams& style);

// What "scale": "auto" brings a field's top 5% to: the line threshold with
// lines on, else 1, hatches' full opacity.
float autoCurvatureTarget(const StyleParams& style);

// The curvature scale of "scale": "auto" (StyleParams::autoScale) for a field
// computed at style.curvature.scale: scaleToReach of the field's top 5%
// (topFivePercent of largestMagnitudes) and autoCurvatureTarget. Values are
// proportional to the scale (no levels with auto), so the field computed
// again at the returned scale has its top 5% there. style.curvature.scale
// itself when that value is 0 (a flat terrain, or no data) or the scale is 0.
float autoCurvatureScale(const CurvatureField& field, const StyleParams& style);

// Reads a "style" object. `source` names it in errors (a file name, or
// "style"). Throws sierra::Error with one message naming the source, the key
// path and what would be right, e.g.
// "fig3a.json: style.curvature.distance must be an integer >= 1 (1 = no reinforcement), got 0".
StyleParams styleFromJson(const nlohmann::json& style, const std::string& source = "style");

// Reads a scene-file fragment {"style": {...}} from a file (a preset).
StyleParams loadStyleFile(const std::string& path);

// The "style" object of a StyleParams (every key written); styleFromJson of
// it gives the same StyleParams back.
nlohmann::json styleToJson(const StyleParams& style);

}  // namespace sierra::analysis
