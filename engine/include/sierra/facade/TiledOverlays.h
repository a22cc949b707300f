#pragma once
// Curvature lines and hatches on a tiled terrain, near the camera. A tiled
// terrain is too large for the whole grid's curvature field, so the
// overlays are computed on a window of at most kMaxSide x kMaxSide samples
// read at full resolution from the tile file (sbt::readWindow): the window
// gets an in-memory renderer of its own whose added passes are the scene's
// overlays (addOverlayPasses: the same field, lines and strokes as on an
// in-memory terrain), drawn with no terrain pass over the tiled terrain's
// frame, by the same camera moved into the window's coordinates, so they
// are depth-tested against the tiled mesh. The window follows the camera:
// it is read again when the camera has moved a quarter of a window. Contour
// edges need no window (render::TiledFrameOptions::contourWidth).
//
// A window is the view's near ground, not the whole frame: farther lines
// and strokes, which thin out with distance anyway, are not drawn.
//
// Memory: the window's renderer, curvature field and lines take about 110
// bytes a sample beside the tile caches' budget (470 MB at 2049^2 on a
// software rasteriser, where the GPU's share is in the process too).

#include <sierra/facade/SceneView.h>
#include <sierra/render/Camera.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/sbt/TileFile.h>
#include <sierra/scene/Scene.h>

#include <cstdint>
#include <memory>

namespace sierra::facade {

// Samples [i0, i0 + width) x [j0, j0 + height) of a tiled terrain.
struct SampleWindow {
    int64_t i0 = 0, j0 = 0;
    int width = 0, height = 0;
    bool operator==(const SampleWindow&) const = default;
};

// The window of at most maxSide x maxSide real samples that the overlays of
// `camera` are drawn in: centred on its focus, the point towards the target
// that lies half a window's ground distance from the eye (the target itself
// when nearer), so the window holds the ground under the eye and what it
// looks at first; moved inside the real samples where it would leave them.
SampleWindow nearWindow(const sbt::TileFileInfo& info, const render::Camera& camera, int maxSide);

class TiledOverlays {
  public:
    // Samples a side of the window at most (the relief overview's side).
    static constexpr int kMaxSide = 2049;

    // The scene's curvature lines and hatches over `file`'s terrain; nullptr
    // when its style has neither. The window is read at the first draw.
    static std::unique_ptr<TiledOverlays> create(const sbt::TileFile& file,
                                                 const scene::Scene& scene, int maxSide = kMaxSide);
    ~TiledOverlays();

    // Draws the overlays seen by `camera` into the bound framebuffer, over
    // the tiled terrain drawn there (its depth buffer); reads the window
    // anew first when nearWindow for `camera` lies a quarter of a side or
    // more from the current one (or there is none yet). tau: the tiled
    // frame's, pixels.
    void draw(const render::Camera& camera, int width, int height, float tau);

    const SampleWindow& window() const { return window_; }
    int windowsRead() const { return windowsRead_; }
    // What the window's overlays hold (polylines traced, the curvature scale).
    const OverlayInfo& info() const { return info_; }

  private:
    TiledOverlays(const sbt::TileFile& file, const scene::Scene& scene, int maxSide);
    void readWindow(const SampleWindow& window);

    const sbt::TileFile& file_;
    scene::Scene scene_;
    int maxSide_;
    SampleWindow window_;
    int windowsRead_ = 0;
    OverlayInfo info_;
    terrain::Heightfield field_;  // the window, padded to 2^n + 1
    std::unique_ptr<render::TerrainRenderer> renderer_;
};

}  // namespace sierra::facade
