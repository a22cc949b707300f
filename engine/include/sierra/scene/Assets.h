#pragma once
// Where Sierra's own data lives (assets/: tiles, palettes, zone maps, presets):
// the source tree's assets/ folder the build was configured from, or the
// folder named by SIERRA_ASSETS.

#include <string>

namespace sierra::scene {

// The assets folder, without a trailing slash.
std::string assetDir();

// assetDir() + "/" + relative; throws sierra::Error naming the path and
// SIERRA_ASSETS when the file does not exist.
std::string assetPath(const std::string& relative);

}  // namespace sierra::scene
