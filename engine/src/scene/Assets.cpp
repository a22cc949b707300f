#include <sierra/scene/Assets.h>

#include <sierra/core/Error.h>

#include <cstdlib>
#include <filesystem>

namespace sierra::scene {

namespace {

// PREFIX/share/sierra/assets for a program in PREFIX/bin, "" otherwise.
std::string installedAssetDir() {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return {};
    const fs::path bin = exe.parent_path();
    if (bin.filename() != fs::path(SIERRA_INSTALL_BINDIR).filename()) return {};
    const fs::path dir = bin.parent_path() / SIERRA_INSTALL_ASSET_SUBDIR;
    return fs::is_directory(dir, ec) ? dir.string() : std::string();
}

}  // namespace

std::string assetDir() {
    const char* env = std::getenv("SIERRA_ASSETS");
    std::string dir = env && *env ? std::string(env) : installedAssetDir();
    if (dir.empty()) dir = SIERRA_ASSET_DIR;
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
