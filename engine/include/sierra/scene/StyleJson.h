#pragma once
// The JSON form of an analysis::StyleParams: the curvature-overlay keys of a
// scene file's "style" object, and the presets assets/presets/fig3a.json ...
// fig3n.json (line shading) and fig4a.json ... fig4h.json (hatch shading),
// which are scene-file fragments {"style": {...}}. Read by the strict layer of
// JsonRead.h (snake_case keys, unknown keys refused, one number rule).
//
// JSON form (every key optional):
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

#include <sierra/analysis/Style.h>
#include <sierra/scene/JsonRead.h>

#include <string>

namespace sierra::scene {

// The keys of the "style" object styleFromJson reads.
inline constexpr const char* kStyleJsonKeys[] = {"description", "styles", "curvature",
                                                 "lines",       "hatch",  "contours"};

// Reads a "style" object. `source` names it in errors (a file name, or
// "style"). Throws sierra::Error with one message naming the source, the key
// path and what would be right, e.g.
// "fig3a.json: style.curvature.distance: must be an integer >= 1 (1 = no reinforcement), got 0".
analysis::StyleParams styleFromJson(const Json& style, const std::string& source = "style");

// Reads a scene-file fragment {"style": {...}} from a file (a preset).
analysis::StyleParams loadStyleFile(const std::string& path);

// The "style" object of a StyleParams (every key written); styleFromJson of
// it gives the same StyleParams back.
Json styleToJson(const analysis::StyleParams& style);

}  // namespace sierra::scene
