#pragma once
// A scene's layers (scene/MapLayers.h) on a terrain renderer: drapes over
// its surface, vector layers as lines, fills and labels, and the map
// furniture drawn over each frame.

#include <sierra/render/Annotations.h>
#include <sierra/render/DrapeSurface.h>
#include <sierra/render/Surface.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/Scene.h>
#include <sierra/terrain/Heightfield.h>
#include <sierra/terrain/Vector.h>

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sierra::facade {

// Where the terrain's real samples lie in its reference system, when its
// file said (terrain::Heightfield::georeference), and how many there are
// (the padding added for the SBT excluded).
struct TerrainPlacement {
    std::optional<terrain::GridPlacement> placement;  // absent: no georeference
    int width = 0, height = 0;                        // real samples
};
TerrainPlacement terrainPlacement(const render::TerrainRenderer& renderer,
                                  const terrain::Heightfield& field);
// The same for a field whose first width x height samples are real (a 2D map:
// all of them).
TerrainPlacement terrainPlacement(const terrain::Heightfield& field, int width, int height);

// The scene's --label places in sample coordinates (i, j) of `field`.
// Throws sierra::Error for a longitude and latitude on a terrain with no
// georeference, or a place off the real samples.
struct LabelSample {
    std::string text;
    double i = 0.0, j = 0.0;
};
std::vector<LabelSample> labelSamples(const scene::Scene& scene, const terrain::Heightfield& field,
                                      const TerrainPlacement& place);

// What the layers put on the renderer and what each frame draws over it.
struct MapLayers {
    render::AnnotationDesc annotations;  // labels and furniture; empty when none
    bool labelsNeedDepth = false;        // labels to hide behind terrain
    std::vector<std::string> notes;      // one line each: what was read, warnings
    bool drawsOver() const {
        const auto& a = annotations;
        return !a.labels.empty() || a.scaleBar || a.northArrow || !a.title.empty() || a.legend;
    }
};

// Reads the scene's drapes and vector layers and puts them on `renderer`:
// `surface` (the scene's surface, or null for the default ramp) wrapped in
// the drapes and the vector fills, then set; vector lines as line passes.
// Labels and furniture come back for the frames (drawMapLayers). Throws
// sierra::Error for a bad image, vector file or label place; a layer wholly
// off the terrain is a warning in `notes` (and SIERRA_LOG).
MapLayers applyMapLayers(render::TerrainRenderer& renderer, const scene::Scene& scene,
                         const terrain::Heightfield& field,
                         std::unique_ptr<render::Surface> surface);

// `surface` under the scene's drapes, then `fills` (vector fills as drape
// layers) and the far vector `lines` (may be null) over the real samples
// `place`: what applyMapLayers sets, and a tiled terrain's drapes. Notes
// (what was read, warnings) are appended to `notes`. Throws sierra::Error
// for an image that cannot be read or placed.
std::unique_ptr<render::Surface> drapeSurface(const scene::Scene& scene,
                                              const TerrainPlacement& place,
                                              std::unique_ptr<render::Surface> surface,
                                              std::span<const render::DrapeLayer> fills,
                                              const render::LinePyramid* lines,
                                              std::vector<std::string>& notes);

// The title, scale bar and north arrow of `f`, in their corners, with its
// text size: what 3D frames and sierra-gen's maps draw (labels, the units
// and the legend are the caller's).
render::AnnotationDesc furnitureAnnotations(const scene::FurnitureDesc& f);

// The legend of the scene's surface: the zone palette's swatches, or the ramp
// or .cpt over the terrain's heights (in metres when they are metric).
render::Legend sceneLegend(render::TerrainRenderer& renderer, const scene::Scene& scene,
                           const terrain::Heightfield& field);

// Draws the labels and furniture of `layers` over the bound framebuffer of a
// width x height frame seen by `camera`; `depth` (may be null) hides labels
// behind terrain.
void drawMapLayers(render::AnnotationOverlay& overlay, const MapLayers& layers,
                   const render::Camera& camera, int width, int height,
                   const render::DepthImage* depth);

}  // namespace sierra::facade
