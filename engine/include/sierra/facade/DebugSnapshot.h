#pragma once
// The debug UI's panels for one frame of a scene: Source, Renderer, Camera,
// Frame time, Mesh, Memory and Style (with the overlay layers, their curvature
// and the scale drawn), built from what the app knows and what
// the renderer holds (the mesh is measured again on the CPU, see
// MeshInspector.h).

#include <sierra/facade/SceneRenderer.h>
#include <sierra/facade/SceneView.h>
#include <sierra/render/Camera.h>
#include <sierra/render/DebugOverlay.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/Scene.h>
#include <sierra/terrain/Heightfield.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sierra::facade {

struct SnapshotFacts {
    const scene::Scene* scene = nullptr;
    const terrain::Heightfield* field = nullptr;  // as loaded and padded
    std::string glRenderer, glVersion, eglPlatform;
    render::TerrainRenderer* renderer = nullptr;
    render::Camera camera;  // of the frame shown
    int frameWidth = 0;     // the frame's viewport beside the column, pixels
    int height = 0;
    render::DrawOptions draw;
    std::vector<render::DrawStats> frames;  // every frame so far, oldest first
    std::vector<float> frameMs;             // wall-clock ms per frame, same order
    OverlayInfo overlays;  // what addOverlayPasses added (the scene's overlay style)
};

// Width of the debug column (two halves of sections) for a snapshot `width`
// pixels wide: 45% of it, clamped to 480..720 pixels, and at most two thirds
// of it (small frames get a cramped panel rather than no frame).
int debugColumnWidth(int width);

// The panels. `deterministic` replaces measured times by placeholders.
render::DebugPanel buildDebugPanel(const SnapshotFacts& facts, bool deterministic);

// Debug snapshots of a SceneRenderer's frames: frame k drawn again narrower
// with the panels in a column beside it, or the panels alone on the UI's
// background. A frame too short for the whole panel gets a taller snapshot
// (the frame at its top, the UI's background below it) rather than a column
// cut off by a scroll bar.
class SnapshotRenderer {
  public:
    explicit SnapshotRenderer(SceneRenderer& renderer);
    ~SnapshotRenderer();
    // The snapshot of frame k, RGBA8, top row first; `frames` and `frameMs`
    // are the statistics of the frames so far, oldest first (not empty).
    gpu::Image render(int k, bool uiOnly, const std::vector<render::DrawStats>& frames,
                      const std::vector<float>& frameMs);

  private:
    SceneRenderer& renderer_;
    std::unique_ptr<render::DebugOverlay> overlay_;  // made by the first snapshot
    std::optional<SceneCameraPath> cameras_;         // for the narrower frame
};

}  // namespace sierra::facade
