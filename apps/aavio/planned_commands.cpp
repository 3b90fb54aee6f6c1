// Subcommands of the CLI contract (design.md §4) that are registered but not built yet: they say
// so, with the issue that builds them, and exit with kExitNotImplemented.
#include <CLI/CLI.hpp>
#include <ostream>

#include "cli.hpp"

namespace aavio::cli {

void RegisterPlanned(CLI::App& app, Context& ctx) {
  struct Planned {
    const char* name;
    const char* description;
    const char* issue;
  };
  static const Planned kPlanned[] = {
      {"eval", "Evaluate a trajectory (ATE, RPE) or a run against ground truth", "#9"},
      {"report", "Plots and a self-contained report.html of one or more runs", "#9"},
  };
  for (const Planned& planned : kPlanned) {
    CLI::App* sub =
        app.add_subcommand(planned.name, std::string(planned.description) +
                                             " (not built yet: issue " + planned.issue + ")");
    sub->allow_extras();
    sub->callback([&ctx, planned] {
      ctx.action = [&ctx, planned] {
        ctx.err << "aavio " << planned.name << ": not built yet (planned in issue " << planned.issue
                << "); see `aavio --help` for what works today\n";
        return kExitNotImplemented;
      };
    });
  }
}

}  // namespace aavio::cli
