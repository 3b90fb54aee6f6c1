#pragma once
/// The `aavio` command line: one file per subcommand (docs/cli.md). RunCli is the whole program
/// minus process setup, so tests run commands in-process and read what they print.

#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace aavio::cli {

/// Exit codes of every subcommand.
enum ExitCode : int {
  kExitOk = 0,
  kExitError = 1,          ///< bad input or a failed operation; the message says which
  kExitUsage = 2,          ///< wrong arguments
  kExitInterrupted = 130,  ///< stopped by Ctrl-C or SIGTERM; the outputs hold what was done
};

/// What a subcommand's callback needs: where to print, and where to put the action to run once
/// the command line has parsed.
struct Context {
  std::ostream& out;
  std::ostream& err;
  std::function<int()> action;
};

void RegisterInfo(CLI::App& app, Context& ctx);
void RegisterConfig(CLI::App& app, Context& ctx);
void RegisterConvert(CLI::App& app, Context& ctx);
void RegisterSimulate(CLI::App& app, Context& ctx);
void RegisterRepresentations(CLI::App& app, Context& ctx);
void RegisterRun(CLI::App& app, Context& ctx);
void RegisterDemo(CLI::App& app, Context& ctx);
void RegisterEval(CLI::App& app, Context& ctx);
void RegisterReport(CLI::App& app, Context& ctx);
void RegisterReplay(CLI::App& app, Context& ctx);

/// The whole command line, its commands registered; parsing sets ctx.action.
std::unique_ptr<CLI::App> MakeApp(Context& ctx);

/// Runs `aavio` with the given arguments (argv[0] included) and returns the exit code.
int RunCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

std::string VersionString();

}  // namespace aavio::cli
