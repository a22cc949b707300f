#pragma once
// Forwarding header: the terrain source and its loading moved to the GL-free
// scene module (<sierra/scene/Terrain.h>); these names keep render code building.

#include <sierra/scene/Scene.h>

namespace sierra::render {
using scene::loadTerrain;
using scene::parseFrameSize;
using scene::TerrainSource;
}  // namespace sierra::render
