#pragma once
// The subcommands of sierra-gen, each registering itself on the app.

#include <sierra/analysis/Curvature.h>
#include <sierra/scene/Scene.h>
#include <sierra/terrain/Heightfield.h>
#include <sierra/terrain/Maps.h>

#include <CLI/CLI.hpp>

namespace sierra::apps {

// `map`: a 2D map PNG of a heightfield (height colours, hillshade or slope).
void addMapCommand(CLI::App& app);
// `zones`: a zone map (or auto-zoning of a heightfield) to vector borderlines (JSON, SVG).
void addZonesCommand(CLI::App& app);
// `tiles`: the procedural surface tiles as PNGs.
void addTilesCommand(CLI::App& app);
// `curvature`: the 4-direction curvature field as .npy, and its Figure 2 intensity image.
void addCurvatureCommand(CLI::App& app);

// `curvature --device gpu` in sierra-gen-gpu, the GL program built beside
// sierra-gen (sierra-gen itself links no GL and runs it for that option).
analysis::CurvatureField computeCurvatureOnGpu(const terrain::Heightfield& field,
                                               const analysis::CurvatureOptions& options);

// `map` with labels or map furniture, in sierra-gen-gpu: `s.layers`' labels,
// title, scale bar and north arrow drawn over `image`, the map of `field`
// (one pixel a sample, row 0 at the top).
void drawMapFurniture(terrain::RgbImage& image, const scene::Scene& s,
                      const terrain::Heightfield& field);

}  // namespace sierra::apps
