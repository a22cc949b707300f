#pragma once
// What every Sierra program does the same way: --version, one error format
// ("PROGRAM: error: MESSAGE" on stderr, one line where the message is one), and
// two exit codes: kExitUsage when the command line or the scene is wrong,
// kExitRuntime when the work itself failed (a bad file, no GL, a write error).
// --help and --version exit 0.

#include <sierra/core/Error.h>

#include <CLI/CLI.hpp>

#include <functional>

namespace sierra::apps {

inline constexpr int kExitRuntime = 1;
inline constexpr int kExitUsage = 2;

// A wrong option value or scene, found after parsing (exit kExitUsage).
class UsageError : public Error {
  public:
    using Error::Error;
};

// Parses `app` (after adding --version), runs `configure` (its sierra::Error
// counts as a usage error), then `run`, and turns every failure into the
// message and exit code above. Exceptions thrown from subcommand callbacks
// during parsing are runtime errors unless they are UsageError.
int runMain(CLI::App& app, int argc, char** argv, const std::function<void()>& configure,
            const std::function<int()>& run);

// Replaces this process with `program` from this program's own directory,
// given this process's arguments unchanged (those runMain was called with, or
// argc/argv). The GL-free programs hand their GL work to such a program beside
// them (sierra-bench frames, sierra-gen curvature --device gpu). Returns only
// by throwing sierra::Error when the program cannot be started.
[[noreturn]] void execBeside(const char* program);
[[noreturn]] void execBeside(const char* program, int argc, char** argv);

// Runs f, rethrowing any sierra::Error as UsageError (for option checks inside
// subcommand callbacks).
void asUsage(const std::function<void()>& f);

}  // namespace sierra::apps
