#pragma once
// The debug UI's panels for one frame of a scene: Source, Renderer, Camera,
// Frame time, Mesh, Memory and Style (with the overlay layers, their curvature
// and the scale drawn), built from what the app knows and what
// the renderer holds (the mesh is measured again on the CPU, see
// MeshInspector.h).

#include <sierra/facade/SceneView.h>
#include <sierra/render/Camera.h>
#include <sierra/render/DebugOverlay.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/Scene.h>
#include <sierra/terrain/Heightfield.h>

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

}  // namespace sierra::facade
