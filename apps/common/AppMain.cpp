#include "AppMain.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

namespace sierra::apps {

namespace {
// The arguments runMain was given, for execBeside from a subcommand's callback.
int savedArgc = 0;
char** savedArgv = nullptr;

void report(const std::string& program, const std::string& message, bool hint) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), message.c_str());
    if (hint) std::fprintf(stderr, "Run %s --help for the options.\n", program.c_str());
}
}  // namespace

void execBeside(const char* program, int argc, char** argv) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    const fs::path path = (ec ? fs::path(argv[0]).parent_path() : self.parent_path()) / program;
    std::vector<char*> args(argv, argv + argc);
    args.push_back(nullptr);
    std::fflush(nullptr);
    ::execv(path.c_str(), args.data());
    throw Error(msg("cannot start ", path.string(), " (", std::strerror(errno),
                    "); it is built beside this program and does its GL work"));
}

void execBeside(const char* program) {
    SIERRA_CHECK(savedArgv, "execBeside(", program, ") before runMain");
    execBeside(program, savedArgc, savedArgv);
}

void asUsage(const std::function<void()>& f) {
    try {
        f();
    } catch (const UsageError&) {
        throw;
    } catch (const Error& e) {
        throw UsageError(e.what());
    }
}

int runMain(CLI::App& app, int argc, char** argv, const std::function<void()>& configure,
            const std::function<int()>& run) {
    const std::string program = app.get_name().empty() ? std::string(argv[0]) : app.get_name();
    app.set_version_flag("--version", program + " " + SIERRA_VERSION, "Print the version and exit");
    savedArgc = argc;
    savedArgv = argv;
    try {
        app.parse(argc, argv);
        if (configure) asUsage(configure);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        report(program, e.what(), true);
        return kExitUsage;
    } catch (const UsageError& e) {
        report(program, e.what(), false);
        return kExitUsage;
    } catch (const std::exception& e) {
        // A subcommand's callback does its work during parsing.
        report(program, e.what(), false);
        return kExitRuntime;
    }
    try {
        return run ? run() : 0;
    } catch (const UsageError& e) {
        report(program, e.what(), false);
        return kExitUsage;
    } catch (const std::exception& e) {
        report(program, e.what(), false);
        return kExitRuntime;
    }
}

}  // namespace sierra::apps
