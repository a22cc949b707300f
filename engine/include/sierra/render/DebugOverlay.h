#pragma once
// The ImGui debug panel, drawn over a frame with no window and no input: the
// figures of the frame (renderer, mesh, stage times) and a frame-time plot, so
// a snapshot image shows what the pipeline did.

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace sierra::render {

struct DebugPanel {
    std::string title = "Sierra";
    std::vector<std::pair<std::string, std::string>> rows;  // label, value
    std::vector<float> frameTimesMs;                        // plotted from two frames on
};

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

private:
    void layout(const DebugPanel& panel);
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace sierra::render
