#pragma once
// Rendering styles built on the curvature analysis, as data: which layers to
// draw (the plain shaded terrain, curvature lines, hatches, contour edges) and
// the parameters of each, read from the "style" object of a scene file. The
// presets assets/presets/fig3a.json ... fig3n.json (line shading) and
// fig4a.json ... fig4h.json (hatch shading) are such fragments.
//
// Their JSON form, and the presets' files, are read and written by the
// programs' layer (scene/StyleJson.h); this module holds the data alone.

#include <sierra/analysis/Curvature.h>
#include <sierra/analysis/Hatch.h>
#include <sierra/analysis/Lines.h>

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

}  // namespace sierra::analysis
