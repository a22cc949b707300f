#include <sierra/scene/Assets.h>

#include <sierra/core/Error.h>

#include <cstdlib>
#include <filesystem>

namespace sierra::scene {

std::string assetDir() {
    const char* env = std::getenv("SIERRA_ASSETS");
    std::string dir = env && *env ? env : SIERRA_ASSET_DIR;
    while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
    return dir;
}

std::string assetPath(const std::string& relative) {
    std::string path = assetDir() + "/" + relative;
    if (!std::filesystem::exists(path))
        throw Error(msg("Sierra's asset ", relative, " is not at ", path,
                        " (set SIERRA_ASSETS to the folder holding tiles/ and palettes/)"));
    return path;
}

}  // namespace sierra::scene
