#pragma once
// The analysis module: curvature analysis of a heightfield and the styles
// built on it. No OpenGL: everything here runs on the CPU and is the
// reference the GPU passes are checked against.
//
//   Normals.h    vertex normals: edge, triangle or quad (default) averaging
//   Curvature.h  a width x height x 4 float32 CurvatureField: +x, +z, x+z,
//                x-z, by two-normal, three-normal, three-vertex or edge-angle,
//                with reinforcement, scale, level control and sign; the
//                border (clamp) and no-data (NaN) rules
//   Lines.h      polylines through high curvature (once per terrain and style)
//   Hatch.h      per-vertex stroke direction and opacity (what the hatch
//                shader computes)
//   Style.h      StyleParams: the layers and parameters of a style (its
//                JSON form and the presets are scene/StyleJson.h's)
//
// Typical use:
//   auto style = sierra::scene::loadStyleFile("assets/presets/fig3a.json");  // programs' layer
//   auto field = sierra::analysis::computeCurvature(heightfield, style.curvature);
//   auto lines = sierra::analysis::traceLines(field, sierra::analysis::lineOptions(style));
//   // lines.vertices (x = column, z = row, alpha) and lines.offsets go to a
//   // vertex buffer; the overlay pass looks each vertex's height up itself.
//
// Units: spacing and vertical scale are applied, so curvature is in 1/world
// length (edge-angle is dimensionless in [0, 1]). Threads: curvature,
// normals and the hatch field are cut into row chunks on sierra::parallelChunks
// (serial below kParallelMinSamples samples); the result does not depend on
// the thread count, bit for bit. Measured times and the method definitions:
// docs/curvature.md.

#include <sierra/analysis/Curvature.h>
#include <sierra/analysis/Hatch.h>
#include <sierra/analysis/Lines.h>
#include <sierra/analysis/Normals.h>
#include <sierra/analysis/Style.h>
