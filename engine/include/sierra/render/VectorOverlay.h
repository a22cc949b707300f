#pragma once
// Vector layers (terrain::readVectorLayer) drawn over the terrain:
// - lines (and polygon outlines) as antialiased lines a width in pixels
//   (LinePass, never thinned), subdivided to at most one sample apart so they
//   follow the full-resolution surface; each point is lifted by the SBT's
//   error bound, so no tau hides them under the mesh;
// - polygons filled (even-odd, holes included) into a drape layer over the
//   grid (DrapeSurface), so the fill is lit like the ground it covers;
// - points as markers, and any feature's label, through the map furniture
//   (Annotations.h), anchored at the ground under them.

#include <sierra/analysis/Lines.h>
#include <sierra/render/Annotations.h>
#include <sierra/render/passes/LinePass.h>
#include <sierra/terrain/Drape.h>
#include <sierra/terrain/Heightfield.h>
#include <sierra/terrain/Vector.h>

#include <glm/glm.hpp>

#include <memory>
#include <span>
#include <vector>

namespace sierra::render {

struct VectorStyle {
    glm::vec4 colour{0.10f, 0.35f, 0.85f, 1.0f};  // lines and outlines, RGBA 0..1
    float width = 2.0f;                           // line width, pixels
    float fillOpacity = 0.35f;                    // polygon fill, 0..1, in the line colour
    bool outlines = true;                         // polygon outlines as lines
};

// Lines far from the camera are drawn into a texture over the grid instead of
// as quads: a million vertices would cost the vertex stage (on llvmpipe, one
// CPU thread) several times the frame. Each mip level of the texture is
// rasterised on its own, with the line `width` texels wide, so where GL's mip
// selection makes a texel about a pixel the line is about `width` pixels
// wide, at any distance; near the camera, where a texel of the finest level
// covers more than a pixel, the quads take over (LinePassDesc::nearTexelSize).
struct LineStyle {
    glm::vec4 colour{0.10f, 0.35f, 0.85f, 1.0f};  // RGBA 0..1, alpha = opacity
    float width = 2.0f;                           // pixels = texels of each level
    float dashOn = 0.0f, dashOff = 0.0f;          // pixels; dashOn 0 = solid
};
struct LineLayer {
    const analysis::LineSet* lines = nullptr;  // sample coordinates
    LineStyle style;
};
struct LinePyramid {
    int width = 0, height = 0;                 // level 0, texels
    float texelsPerSample = 1.0f;              // level 0 texels per grid sample
    std::vector<std::vector<uint8_t>> levels;  // premultiplied RGBA8, level 0 finest, down to 1x1
    int levelWidth(int level) const { return std::max(1, width >> level); }
    int levelHeight(int level) const { return std::max(1, height >> level); }
};
// The layers (in order, each over the ones before) over a gridWidth x
// gridHeight grid, level 0 at most maxSide texels a side (default 4096: 85
// MiB with its mips; 2 texels a sample below that).
LinePyramid rasteriseLines(std::span<const LineLayer> layers, int gridWidth, int gridHeight,
                           int maxSide = 4096);

// The layer's lines and polygon outlines as polylines in sample coordinates,
// each segment cut to at most `step` samples (0 < step).
analysis::LineSet vectorLines(const terrain::VectorLayer& layer, bool outlines = true,
                              float step = 1.0f);

// The layer's polygons filled into a drape over a gridWidth x gridHeight
// grid, `texelsPerSample` texels a sample: colour RGB, alpha = opacity
// inside, 0 outside. Texel centres decide, by the even-odd rule over each
// polygon's rings.
terrain::DrapeImage polygonDrape(const terrain::VectorLayer& layer, int gridWidth, int gridHeight,
                                 glm::vec4 colour, float opacity, int texelsPerSample = 2);

// Markers and labels: one Label per point feature (its label text, or none),
// and per labelled line or polygon at its first vertex, anchored at the world
// point on `field`'s surface (bilinear height) under it. Points off the
// grid's real samples are skipped.
std::vector<Label> vectorLabels(const terrain::VectorLayer& layer,
                                const terrain::Heightfield& field);

// The world point on `field`'s surface at sample coordinates (i, j): the
// bilinear height of the four samples around it (clamped to the grid).
glm::vec3 surfacePoint(const terrain::Heightfield& field, double i, double j);

}  // namespace sierra::render
