#include <sierra/gpu/Program.h>

#include <sierra/core/Error.h>
#include <sierra/gpu/EmbeddedShaders.h>

#include <regex>
#include <sstream>
#include <vector>

namespace sierra::gpu {

std::string_view embeddedShader(std::string_view name) {
    for (const EmbeddedShader& s : embeddedShaders())
        if (s.name == name) return s.source;
    throw Error(msg("no shader named '", name, "' is embedded (files come from shaders/)"));
}

namespace {

// Source-string numbers used in #line directives: index into `files`.
struct Preprocessed {
    std::string text;
    std::vector<std::string> files;
};

void appendFile(Preprocessed& out, std::string_view file, std::string_view defines,
                std::span<const IncludeAlias> aliases, int depth) {
    SIERRA_CHECK(depth < 8, "shader includes nested too deep at ", file);
    int fileIndex = int(out.files.size());
    out.files.emplace_back(file);
    std::istringstream in{std::string(embeddedShader(file))};
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        if (line.rfind("#version", 0) == 0) {
            out.text += line + "\n" + std::string(defines);
            out.text += msg("#line ", lineNo + 1, " ", fileIndex, "\n");
            continue;
        }
        if (line.rfind("#include", 0) == 0) {
            size_t a = line.find('"'), b = line.rfind('"');
            SIERRA_CHECK(a != std::string::npos && b > a, file, ":", lineNo,
                         ": malformed #include (write #include \"name.glsl\")");
            std::string name = line.substr(a + 1, b - a - 1);
            for (const IncludeAlias& alias : aliases)
                if (alias.name == name) name = std::string(alias.file);
            out.text += msg("#line 1 ", int(out.files.size()), "\n");
            appendFile(out, name, {}, aliases, depth + 1);
            out.text += msg("#line ", lineNo + 1, " ", fileIndex, "\n");
            continue;
        }
        out.text += line + "\n";
    }
}

Preprocessed preprocess(std::string_view file, std::string_view defines,
                        std::span<const IncludeAlias> aliases) {
    Preprocessed out;
    appendFile(out, file, defines, aliases, 0);
    return out;
}

// Rewrites driver log lines "N:L(C): ..." (Mesa) or "N(L) : ..." (NVIDIA) as
// "file:L: ...".
std::string mapLog(const std::string& log, const std::vector<std::string>& files) {
    static const std::regex mesa(R"(^(\d+):(\d+)\(\d+\):\s*(.*)$)");
    static const std::regex nvidia(R"(^(\d+)\((\d+)\)\s*:\s*(.*)$)");
    std::istringstream in(log);
    std::string line, result;
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_match(line, m, mesa) || std::regex_match(line, m, nvidia)) {
            size_t index = std::stoul(m[1]);
            std::string name = index < files.size() ? files[index] : "?";
            line = name + ":" + m[2].str() + ": " + m[3].str();
        }
        if (!line.empty()) result += (result.empty() ? "" : "\n") + line;
    }
    return result;
}

// The info log of a shader or program, through the matching pair of getters.
template <typename GetIv, typename GetLog>
std::string infoLog(GLuint object, GetIv getIv, GetLog getLog) {
    GLint length = 0;
    getIv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    getLog(object, GLsizei(log.size()), nullptr, log.data());
    return log.c_str();  // drop the terminating zero the driver wrote
}

GLuint compile(GLenum stage, std::string_view file, std::string_view defines,
               std::span<const IncludeAlias> aliases) {
    Preprocessed source = preprocess(file, defines, aliases);
    GLuint shader = glCreateShader(stage);
    const char* text = source.text.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        std::string log = infoLog(shader, glGetShaderiv, glGetShaderInfoLog);
        glDeleteShader(shader);
        throw Error(msg("shader ", file, " failed to compile:\n", mapLog(log, source.files)));
    }
    return shader;
}

}  // namespace

std::string preprocessShader(std::string_view file, std::string_view defines,
                             std::span<const IncludeAlias> aliases) {
    return preprocess(file, defines, aliases).text;
}

Program Program::create(const ProgramDesc& desc) {
    GLuint id = glCreateProgram();
    Program program(id, kAdopt);
    std::vector<GLuint> shaders;
    std::string names;
    try {
        auto add = [&](GLenum stage, std::string_view file) {
            if (file.empty()) return;
            shaders.push_back(compile(stage, file, desc.defines, desc.aliases));
            glAttachShader(id, shaders.back());
            names += (names.empty() ? "" : " + ") + std::string(file);
        };
        add(GL_VERTEX_SHADER, desc.vertex);
        add(GL_GEOMETRY_SHADER, desc.geometry);
        add(GL_FRAGMENT_SHADER, desc.fragment);
        add(GL_COMPUTE_SHADER, desc.compute);
    } catch (...) {
        for (GLuint s : shaders) glDeleteShader(s);
        throw;
    }
    SIERRA_CHECK(!shaders.empty(), "a program needs at least one stage");
    glLinkProgram(id);
    for (GLuint s : shaders) {
        glDetachShader(id, s);
        glDeleteShader(s);
    }
    GLint ok = 0;
    glGetProgramiv(id, GL_LINK_STATUS, &ok);
    if (!ok)
        throw Error(msg("program ", names, " failed to link:\n",
                        infoLog(id, glGetProgramiv, glGetProgramInfoLog)));
    return program;
}

}  // namespace sierra::gpu
