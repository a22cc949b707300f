#pragma once
// The ImGui debug panel, drawn over a frame with no window and no input: the
// figures of the frame (source, renderer, mesh, memory, stage times, style
// parameters), so a snapshot image shows what the pipeline did.
//
// Two layouts: a floating panel at the top left (columnWidth 0), or a column
// of columnWidth pixels down the right edge, its sections in two halves side
// by side (DebugSection::column), for which the caller narrows the frame (see
// snapshotFrameWidth) so the panel never covers the terrain.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace sierra::render {

// A time series of one pipeline stage, plotted with its median and 95th
// percentile over the frames kept.
struct StageSeries {
    std::string name;           // "refine + strip", ...
    std::string unit = "ms";    // of the values
    std::vector<float> values;  // oldest first
};

// A bar chart: counts[k] is bin firstBin + k.
struct Histogram {
    std::string name;
    std::string binLabel;  // what a bin is, e.g. "SBT level"
    int firstBin = 0;
    std::vector<double> counts;
};

// A style parameter shown as a (read-only) widget, so a snapshot documents the
// settings of its frame.
struct StyleParam {
    enum class Kind { Flag, Number, Text };
    Kind kind = Kind::Number;
    std::string name;
    bool flag = false;
    float value = 0.0f, min = 0.0f, max = 1.0f;  // Number: slider range
    std::string text;                            // Text; Number: the unit
};

struct DebugSection {
    std::string title;
    std::vector<std::pair<std::string, std::string>> rows;  // label, value
    std::vector<StageSeries> series;
    std::vector<Histogram> histograms;
    std::vector<StyleParam> params;
    std::string note;  // a line under the rows, e.g. what is not available
    int column = 0;    // column layout: 0 = left half of the panel, 1 = right half
    // A legend: colour swatches (RGB 0..1) with what they mean.
    std::vector<std::pair<std::array<float, 3>, std::string>> swatches;
};

struct DebugPanel {
    std::string title = "Sierra";
    std::vector<std::pair<std::string, std::string>> rows;  // label, value (before the sections)
    std::vector<float> frameTimesMs;                        // plotted from two frames on
    std::vector<DebugSection> sections;                     // collapsing headers, all open
    int columnWidth = 0;  // > 0: a right-hand column this wide (pixels), full height
    // Golden images: series are drawn as placeholders ("-- ms") and not plotted.
    bool deterministic = false;
};

// Median and 95th percentile (nearest rank) of `values`; {0, 0} when empty.
std::pair<float, float> medianAndP95(std::vector<float> values);

// The width of the frame beside a debug column of `columnWidth` pixels in a
// snapshot `width` pixels wide: at least a third of the snapshot; 0 when the
// column takes the whole width (the UI alone).
int snapshotFrameWidth(int width, int columnWidth);

class DebugOverlay {
  public:
    // Creates the ImGui context and its OpenGL3 backend on the current GL context.
    DebugOverlay();
    ~DebugOverlay();
    DebugOverlay(const DebugOverlay&) = delete;
    DebugOverlay& operator=(const DebugOverlay&) = delete;

    // Draws the panel into the bound framebuffer (width x height pixels),
    // restoring the GL state it changes.
    void draw(const DebugPanel& panel, int width, int height);

    // The height in pixels a right-hand column (panel.columnWidth > 0) needs
    // to show all of the panel without scrolling, laid out as draw() would
    // in a framebuffer `width` pixels wide; draws nothing. A snapshot shorter
    // than this cuts the column off (a scroll bar shows it).
    int contentHeight(const DebugPanel& panel, int width, int height);

  private:
    void layout(const DebugPanel& panel, int width, int height);
    // Two frames of layout(), the second rendered (ImGui's draw data) or not.
    void layOutTwice(const DebugPanel& panel, int width, int height, bool render);
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace sierra::render
