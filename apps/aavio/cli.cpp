#include "cli.hpp"

#include <CLI/CLI.hpp>
#include <ostream>

#include "aavio/version.hpp"

namespace aavio::cli {

std::string VersionString() {
  return std::string("aavio ") + kVersion + " (git " + kGitRevision + ")";
}

std::unique_ptr<CLI::App> MakeApp(Context& ctx) {
  auto app = std::make_unique<CLI::App>(
      "aavio: IMU-aided event-based stereo visual odometry (Niu, Zhong, Zhou, ICRA 2024)", "aavio");
  app->require_subcommand(0, 1);
  app->set_version_flag("--version", VersionString());
  app->footer("Run `aavio COMMAND --help` for a command's options.");
  RegisterInfo(*app, ctx);
  RegisterConfig(*app, ctx);
  RegisterConvert(*app, ctx);
  RegisterSimulate(*app, ctx);
  RegisterRepresentations(*app, ctx);
  RegisterRun(*app, ctx);
  RegisterReplay(*app, ctx);
  RegisterDemo(*app, ctx);
  RegisterEval(*app, ctx);
  RegisterReport(*app, ctx);
  return app;
}

int RunCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  Context ctx{out, err, {}};
  const std::unique_ptr<CLI::App> made = MakeApp(ctx);
  CLI::App& app = *made;

  std::vector<std::string> reversed(args.rbegin(), args.rend() - (args.empty() ? 0 : 1));
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    out << app.help();  // the selected subcommand's help when there is one
    return kExitOk;
  } catch (const CLI::CallForAllHelp&) {
    out << app.help("", CLI::AppFormatMode::All);
    return kExitOk;
  } catch (const CLI::CallForVersion&) {
    out << VersionString() << "\n";
    return kExitOk;
  } catch (const CLI::ParseError& e) {
    err << "aavio: " << e.what() << "\n(run `aavio --help` for usage)\n";
    return kExitUsage;
  }
  if (!ctx.action) {
    out << app.help();
    return kExitUsage;
  }
  return ctx.action();
}

}  // namespace aavio::cli
