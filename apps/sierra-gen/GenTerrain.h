#pragma once
// The terrain of a sierra-gen command, read as every app reads it (the scene
// registrar's terrain options, scene::loadTerrain), without the padding.

#include <sierra/scene/Terrain.h>
#include <sierra/terrain/Heightfield.h>

#include <string>

namespace sierra::apps {

// scene::loadTerrain(source) cut back to its real samples: the padding the
// loader adds on the right and at the bottom is dropped (the bounding box of
// the valid samples from (0, 0)); the mask of no-data samples inside is kept.
// Spacing and vertical scale are the loader's (the renderer's automatic ones).
terrain::Heightfield loadRealTerrain(const scene::TerrainSource& source, std::string* description = nullptr);

}  // namespace sierra::apps
