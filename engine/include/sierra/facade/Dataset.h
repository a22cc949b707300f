#pragma once
// The dataset outputs of a scene's frames (scene::OutputDesc: depth, normals,
// zone ids, mask, camera JSON, transforms.json), each written through
// writeFileAtomic with the frame-index naming of the depth output
// (sequencePath: NAME_0000.EXT in a sequence, NAME.EXT for one frame). The
// file forms are described in docs/dataset.md.

#include <sierra/render/Camera.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/CameraJson.h>
#include <sierra/scene/Scene.h>
#include <sierra/terrain/Heightfield.h>

#include <string>
#include <vector>

namespace sierra::facade {

class DatasetWriter {
  public:
    // For `scene`'s outputs. `sequence`: the scene has more than one frame,
    // so the files take frame indices.
    DatasetWriter(const scene::Scene& scene, bool sequence);

    // True when the scene asks for any dataset output (depth included).
    bool any() const;
    // ensureWritableLocation for every output asked for, before any work.
    void checkLocations() const;
    // Renders and writes frame k's outputs for `camera` (the frame's, drawn
    // width x height with `options`) over `field` (the terrain as loaded: its
    // spacing and georeference go into the camera JSON), and keeps its camera
    // for finish().
    void write(render::TerrainRenderer& renderer, const terrain::Heightfield& field, int k,
               const render::Camera& camera, int width, int height,
               const render::DrawOptions& options);
    // Writes transforms.json for the frames written so far (nothing when it
    // is not asked for or no frame was written).
    void finish();

    // The file of output `base` for frame k.
    std::string framePath(const std::string& base, int k) const;
    // The palette JSON beside a zone-id image: NAME.json for NAME.png.
    static std::string palettePath(const std::string& zoneIds);

  private:
    scene::OutputDesc output_;
    std::string palette_;  // the zone palette file; "" without zones
    bool sequence_;
    bool paletteWritten_ = false;
    std::vector<scene::TransformsFrame> frames_;
};

}  // namespace sierra::facade
