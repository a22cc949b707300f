#pragma once
// sierra-render's frames of a tiled terrain (a .sierra heightmap).

#include <sierra/scene/Scene.h>

#include <cstdint>
#include <string>

namespace sierra::apps {

struct TiledRenderOptions {
    uint64_t memoryBudget = uint64_t(1) << 30;  // bytes, the CPU and GPU tile caches
    int loaders = 2;
    double tileWaitSeconds = 60.0;  // a single frame waits this long at most for its tiles
};

// True when the scene's heightmap is a tiled terrain file.
bool isTiledTerrain(const scene::Scene& s);
// The frames of `s` (sequenceFrame(s, k) names frame k's file).
int runTiled(const scene::Scene& s, const TiledRenderOptions& options);
// Frame k's output file of the scene (a sequence numbers its frames).
std::string sequenceFrame(const scene::Scene& s, int k);

}  // namespace sierra::apps
