#pragma once
// The options of `sierra-gen map` beside the terrain's: their registration,
// which schemes each applies to, and their checks.

#include "MapSchemes.h"

#include <sierra/scene/Scene.h>
#include <sierra/terrain/DemMaps.h>

#include <CLI/CLI.hpp>

#include <string>

namespace sierra::apps::map {

struct MapOptions {
    scene::Scene scene;  // only its terrain is used
    std::string scheme = "hypsometric";
    std::string cpt;
    bool colourBar = false;
    std::string out;
    std::string values;
    std::string algorithm;  // "" = the scheme's default
    float zFactor = 1.0f;
    bool multidirectional = false, combined = false, igor = false;
    float azimuth = 315.0f;
    float altitude = 45.0f;
    std::string slopeUnits = "degrees";
    bool trigonometric = false, zeroForFlat = false;
    std::string tri = "riley";
    bool computeEdges = false;
    float sunSize = 0.53f;
    float horizonRadius = 0.0f;
    int directions = 16;
};

// Registers the scheme options (all but the terrain's) on `cmd`.
void addMapOptions(CLI::App& cmd, MapOptions& o);

// Throws UsageError naming the option: one given that does not apply to the
// scheme (and where it applies), two shading styles, a value out of range, no
// output or an output of the wrong type.
void checkMapOptions(const CLI::App& cmd, const Scheme& s, const MapOptions& o);

// The DEM field description of a 3x3 scheme (hillshade for relief); throws
// UsageError for an --algorithm, --slope-units or --tri it does not know.
terrain::DemFieldDesc demFieldDesc(const Scheme& s, const MapOptions& o);

}  // namespace sierra::apps::map
