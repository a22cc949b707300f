#pragma once
// The files of shaders/, embedded into the library at build time
// (cmake/EmbedShaders.cmake): programs never read shaders from the disk.

#include <span>
#include <string_view>

namespace sierra::gpu {

struct EmbeddedShader {
    std::string_view name;    // file name, e.g. "terrain.vert"
    std::string_view source;  // file contents
};

std::span<const EmbeddedShader> embeddedShaders();

// The source of shaders/<name>; throws sierra::Error if there is no such file.
std::string_view embeddedShader(std::string_view name);

}  // namespace sierra::gpu
