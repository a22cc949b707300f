#pragma once
// Where Sierra's own data lives (assets/: tiles, palettes, zone maps, presets),
// the first of:
//   - the folder named by SIERRA_ASSETS;
//   - PREFIX/share/sierra/assets when the running program sits in PREFIX/bin
//     (an installed Sierra, wherever the prefix was moved);
//   - the source tree's assets/ folder the build was configured from.

#include <string>

namespace sierra::scene {

// The assets folder, without a trailing slash.
std::string assetDir();

// assetDir() + "/" + relative; throws sierra::Error naming the path and
// SIERRA_ASSETS when the file does not exist.
std::string assetPath(const std::string& relative);

}  // namespace sierra::scene
