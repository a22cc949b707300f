#pragma once
// Shader programs built from the embedded files of shaders/.
//
// A stage file may pull in shared code with a line `#include "name.glsl"`; the
// text is inlined with #line directives, so a compile error names the real file
// and line: "terrain.vert:42: error: ...".

#include <sierra/gpu/Objects.h>

#include <span>
#include <string>
#include <string_view>

namespace sierra::gpu {

// `#include "name"` resolved to another file: how a stage picks one of several
// implementations of a function (terrain.frag's "surface.glsl" becomes
// "surface_hypsometric.glsl", say) when the program is built.
struct IncludeAlias {
    std::string_view name;
    std::string_view file;
};

struct ProgramDesc {
    std::string_view vertex;  // file names in shaders/; empty = no such stage
    std::string_view fragment;
    std::string_view compute;
    std::string_view geometry;  // between vertex and fragment; empty = none
    std::string_view defines;   // extra lines inserted after #version, e.g. "#define X 1\n"
    std::span<const IncludeAlias> aliases;  // include names resolved to other files
};

class Program : public GlObject<Program, detail::deleteProgram> {
  public:
    using GlObject::GlObject;
    // Compiles and links; throws sierra::Error with the file, line and driver
    // message on failure.
    static Program create(const ProgramDesc& desc);
    // Location of a uniform, -1 if the linker removed it (setting -1 is a no-op).
    GLint uniform(const char* name) const { return glGetUniformLocation(id_, name); }
};

// The source of `file` with #include lines inlined and `defines` after #version:
// what the driver (and glslangValidator in tests) compiles.
std::string preprocessShader(std::string_view file, std::string_view defines = {},
                             std::span<const IncludeAlias> aliases = {});

}  // namespace sierra::gpu
