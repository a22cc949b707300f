#pragma once
// What a scene lays over its terrain besides the surface: imagery drapes,
// vector layers, labels and map furniture (the scene's "layers"), GL-free.
// The command line's forms (--drape IMAGE[:OPACITY], --vector FILE[:STYLE],
// --label TEXT@X,Z or TEXT@LON[EW],LAT[NS]) are parsed here, so every program reads
// them alike; render/DrapeSurface.h, render/VectorOverlay.h and
// render/Annotations.h draw them.

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace sierra::scene {

struct DrapeDesc {
    std::string image;              // GeoTIFF, PNG, JPEG, ... (read through GDAL)
    float opacity = 1.0f;           // 0..1, times the image's alpha
    std::string blend = "replace";  // replace or multiply (the relief look)
    // Where the image's corners go instead of its georeference: left, top,
    // right, bottom, in `boundsUnits`; absent = its georeference, or
    // stretched over the terrain when it has none.
    std::optional<std::array<double, 4>> bounds;
    std::string boundsUnits = "samples";  // samples (the grid's) or crs (the terrain's system)
    std::string resampling = "bilinear";  // bilinear or cubic
    bool operator==(const DrapeDesc&) const = default;
};

struct VectorDesc {
    std::string file;        // GeoJSON, GeoPackage, Shapefile, GPX, KML, ... (read through OGR)
    std::string where;       // OGR SQL attribute filter; "" = every feature
    std::string labelField;  // the field that labels each feature; "" = none
    std::array<float, 3> colour{0.10f, 0.35f, 0.85f};  // lines, outlines and fills, 0..1
    float width = 2.0f;                                // line width, pixels, > 0
    float opacity = 1.0f;                              // of the lines, 0..1
    float fillOpacity = 0.35f;                         // of polygon fills, 0..1 (0 = outlines only)
    float dashOn = 0.0f, dashOff = 0.0f;  // dashes: pixels drawn, then left out; 0 = solid
    bool operator==(const VectorDesc&) const = default;
};

struct LabelDesc {
    std::string text;
    // World x and z (the ground under them), or longitude and latitude in
    // degrees (WGS 84) on a georeferenced terrain.
    double x = 0.0, z = 0.0;
    bool geographic = false;
    bool operator==(const LabelDesc&) const = default;
};

// Where a piece of map furniture goes; several in one corner stack inwards.
enum class FrameCorner { TopLeft, TopRight, BottomLeft, BottomRight };
const char* toString(FrameCorner corner);  // "top-left" ... "bottom-right"
FrameCorner parseFrameCorner(const std::string& text, const std::string& what);

struct FurnitureDesc {
    bool scaleBar = false;
    bool northArrow = false;
    std::string title;         // "" = none
    bool legend = false;       // the colour ramp, the .cpt or the zone palette, with units
    float textPixels = 16.0f;  // text height, pixels, 6..128
    FrameCorner titleCorner = FrameCorner::TopLeft;
    FrameCorner scaleBarCorner = FrameCorner::BottomLeft;
    FrameCorner northArrowCorner = FrameCorner::TopRight;
    FrameCorner legendCorner = FrameCorner::BottomRight;
    bool operator==(const FurnitureDesc&) const = default;
};

struct MapLayersDesc {
    std::vector<DrapeDesc> drapes;  // blended in order over the surface
    std::vector<VectorDesc> vectors;
    std::vector<LabelDesc> labels;
    FurnitureDesc furniture;
    bool operator==(const MapLayersDesc&) const = default;
    bool empty() const { return *this == MapLayersDesc{}; }
};

// "IMAGE", "IMAGE:OPACITY" (the last colon followed by a number in 0..1; any
// other colon belongs to the path), either followed by ":multiply" (or
// ":replace", the default). Throws sierra::Error naming `what`.
DrapeDesc parseDrapeSpec(const std::string& text, const std::string& what);

// "FILE" or "FILE:STYLE", STYLE a comma-separated list of colour=#RRGGBB,
// width=PX, opacity=A, fill=A (polygon fill opacity), field=NAME (labels),
// dash=ON/OFF (pixels drawn and left out).
VectorDesc parseVectorSpec(const std::string& text, const std::string& what);

// "TEXT@X,Z": the label at world x, z (units); "TEXT@LON,LAT" with each
// number's hemisphere letter ("Summit@15.25E,45.1N", W and S for negative):
// at that longitude and latitude. The last @ splits the text from the place.
LabelDesc parseLabelSpec(const std::string& text, const std::string& what);

// "left,top,right,bottom" (four finite numbers).
std::array<double, 4> parseBounds(const std::string& text, const std::string& what);

// The ranges and names of `layers`; throws sierra::Error naming the key
// (e.g. "layers.drapes[1].opacity") and the option.
void validateMapLayers(const MapLayersDesc& layers);

}  // namespace sierra::scene
