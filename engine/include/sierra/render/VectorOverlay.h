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
#include <vector>

namespace sierra::render {

struct VectorStyle {
    glm::vec4 colour{0.10f, 0.35f, 0.85f, 1.0f};  // lines and outlines, RGBA 0..1
    float width = 2.0f;                           // line width, pixels
    float fillOpacity = 0.35f;                    // polygon fill, 0..1, in the line colour
    bool outlines = true;                         // polygon outlines as lines
};

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
