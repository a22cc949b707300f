#pragma once
// Map furniture over a frame: labels anchored at 3D points, a scale bar, a
// north arrow, a title and a legend, drawn with a real font (DejaVu Sans by
// default) through Dear ImGui's draw lists after the terrain.
//
// Two steps. layoutAnnotations() is GL-free: it projects the labels' points,
// hides those behind terrain (by the frame's linear depth), places the rest
// greedily by priority so that no two overlap, and sizes the scale bar and
// the north arrow to the frame. AnnotationOverlay then draws a layout into the
// bound framebuffer. Text is measured through a TextMeasure, so the layout's
// rules are testable without a font or a GL context.

#include <sierra/render/Camera.h>
#include <sierra/render/passes/DepthPass.h>

#include <glm/glm.hpp>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sierra::render {

enum class Corner { TopLeft, TopRight, BottomLeft, BottomRight };

struct Label {
    std::string text;
    glm::vec3 point{0.0f};  // world units; the anchor
    float priority = 0.0f;  // higher is placed first
};

// A legend: a colour ramp (stops by value) or named swatches (zone palettes).
struct Legend {
    std::string title;  // e.g. "Elevation"
    std::string units;  // e.g. "m"; shown after the ramp's values
    struct Stop {
        float value = 0.0f;
        std::array<float, 3> colour{};  // RGB 0..1
    };
    std::vector<Stop> ramp;  // ascending values; empty when swatches are given
    std::vector<std::pair<std::array<float, 3>, std::string>> swatches;
    Corner corner = Corner::BottomRight;
};

struct AnnotationDesc {
    std::vector<Label> labels;
    float textPixels = 16.0f;  // label and furniture text height, pixels
    bool scaleBar = false;
    Corner scaleBarCorner = Corner::BottomLeft;
    // World units per metre of ground: 1 for a metric terrain. 0 = units
    // unknown: the bar is labelled in world units.
    float unitsPerMetre = 1.0f;
    bool northArrow = false;
    Corner northArrowCorner = Corner::TopRight;
    std::string title;
    Corner titleCorner = Corner::TopLeft;
    std::optional<Legend> legend;
};

// Width and height in pixels of a line of text at the overlay's size.
using TextMeasure = std::function<glm::vec2(const std::string&)>;

struct PlacedLabel {
    int index = 0;       // into AnnotationDesc::labels
    glm::vec2 anchor{};  // the point projected, pixels from the top left
    glm::vec2 boxMin{};  // the text's box, halo included
    glm::vec2 boxMax{};
    bool leader = false;  // the box is away from the anchor: a leader line joins them
};

struct ScaleBar {
    double groundLength = 0.0;  // metres (or world units when unitsPerMetre is 0)
    float pixels = 0.0f;        // the bar's length on the frame
    std::string text;           // "2 km", with "at the target" in perspective
    bool atTarget = false;      // perspective: true only at the target's distance
    glm::vec2 origin{};         // its left end, pixels from the top left
};

struct NorthArrow {
    glm::vec2 centre{};     // pixels from the top left
    glm::vec2 direction{};  // unit vector on the frame (y down) pointing north
    float length = 0.0f;    // pixels
};

struct AnnotationLayout {
    int width = 0, height = 0;
    std::vector<PlacedLabel> labels;  // the shown ones, in placement order
    int hiddenBehindTerrain = 0;      // labels whose point terrain hides
    int outsideFrame = 0;             // labels whose point is off the frame or behind the eye
    int crowdedOut = 0;               // labels with no free place left
    std::optional<ScaleBar> scaleBar;
    std::optional<NorthArrow> northArrow;
    std::optional<glm::vec2> titleOrigin;   // the title's box, top left
    std::optional<glm::vec2> legendOrigin;  // the legend's box, top left
    glm::vec2 legendSize{};
};

// Ground units per pixel on the frame: perspective at the target's distance
// (2 d tan(fovY / 2) / height), orthographic exactly (orthoHeight / height).
double worldUnitsPerPixel(const Camera& camera, int height);

// The longest 1, 2 or 5 x 10^k metres that fits in `maxPixels` at
// `metresPerPixel`, its length in pixels and its text ("500 m", "2 km").
ScaleBar chooseScaleBar(double metresPerPixel, float maxPixels);

// North (-z) at the target as a unit direction on the frame (y down); {0, -1}
// (straight up) when north is along the view direction.
glm::vec2 northOnFrame(const Camera& camera, float aspect);

// Lays the annotations out on a width x height frame seen by `camera`.
// `depth` (linear eye depth, NaN = sky; may be null) hides labels whose point
// lies more than 1% of its distance behind the terrain drawn at its pixel.
AnnotationLayout layoutAnnotations(const AnnotationDesc& desc, const Camera& camera, int width,
                                   int height, const DepthImage* depth, const TextMeasure& measure);

// The default font: DejaVu Sans (Debian's fonts-dejavu-core).
inline constexpr const char* kDefaultFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

class AnnotationOverlay {
  public:
    // An ImGui context with `fontPath` rasterised at `textPixels`, and its
    // OpenGL3 backend, on the current GL context. Throws sierra::Error naming
    // the font when it cannot be read.
    explicit AnnotationOverlay(float textPixels = 16.0f,
                               const std::string& fontPath = kDefaultFont);
    ~AnnotationOverlay();
    AnnotationOverlay(const AnnotationOverlay&) = delete;
    AnnotationOverlay& operator=(const AnnotationOverlay&) = delete;

    // Text size with this overlay's font (for layoutAnnotations).
    glm::vec2 measure(const std::string& text) const;
    TextMeasure measurer() const;

    // Draws `layout` (made with this overlay's measurer) into the bound
    // framebuffer, restoring the GL state it changes.
    void draw(const AnnotationDesc& desc, const AnnotationLayout& layout);

  private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace sierra::render
