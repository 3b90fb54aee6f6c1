// Every option of every command refuses absurd values before any work starts, and output
// folders are never mixed with or silently replaced by a new run.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <sstream>

#include "cli.hpp"
#include "tests/test_utils.hpp"

namespace aavio::cli {
namespace {

namespace fs = std::filesystem;

bool IsNumeric(const CLI::Option* option) {
  const std::string type = option->get_type_name();
  return type.find("FLOAT") != std::string::npos || type.find("INT") != std::string::npos ||
         type.find("NUMBER") != std::string::npos;
}

TEST(Options, EveryNumericOptionRefusesNanInfinitiesAndAbsurdValues) {
  std::ostringstream out, err;
  Context ctx{out, err, {}};
  const std::unique_ptr<CLI::App> app = MakeApp(ctx);
  int checked = 0;
  for (const CLI::App* command : app->get_subcommands({})) {
    for (const CLI::Option* option : command->get_options()) {
      if (!IsNumeric(option) || option->get_lnames().empty()) continue;
      const std::string name = "--" + option->get_lnames().front();
      for (const char* value : {"nan", "inf", "-inf", "1e300", "-1e300"}) {
        std::ostringstream o, e;
        Context c{o, e, {}};
        const std::unique_ptr<CLI::App> fresh = MakeApp(c);
        const std::string line = command->get_name() + " " + name + "=" + value;
        try {
          fresh->parse(line, false);
          ADD_FAILURE() << "aavio " << line << " was accepted";
        } catch (const CLI::ValidationError&) {
        } catch (const CLI::ConversionError&) {
        } catch (const CLI::ParseError& other) {
          ADD_FAILURE() << "aavio " << line << ": " << other.get_name() << ": " << other.what();
        }
      }
      ++checked;
    }
  }
  EXPECT_GE(checked, 14);  // simulate 3, run 2, eval 4, demo 2, convert 1, representations 2
}

TEST(Options, AbsurdValuesNameTheOptionAndItsRange) {
  std::ostringstream out, err;
  EXPECT_EQ(RunCli({"aavio", "simulate", "--out", "x", "--duration", "-1"}, out, err), kExitUsage);
  EXPECT_NE(err.str().find("--duration: Value -1 not in range [0.001, 86400]"), std::string::npos)
      << err.str();
  err.str("");
  EXPECT_EQ(RunCli({"aavio", "simulate", "--out", "x", "--seed", "-3"}, out, err), kExitUsage);
  EXPECT_NE(err.str().find("--seed"), std::string::npos) << err.str();
  for (const char* seed : {"18446744073709551616", "99999999999999999999", "1e3", "2.5"}) {
    err.str("");
    EXPECT_EQ(RunCli({"aavio", "simulate", "--out", "x", "--seed", seed}, out, err), kExitUsage);
    EXPECT_NE(err.str().find("is not a seed: give a whole number from 0 to 18446744073709551615"),
              std::string::npos)
        << err.str();
  }
  err.str("");
  EXPECT_EQ(RunCli({"aavio", "run", "seq", "--out", "x", "--duration", "nan"}, out, err),
            kExitUsage);
  EXPECT_NE(err.str().find("--duration: 'nan' is not a number; give one in [0, 1e+06]"),
            std::string::npos)
      << err.str();
  err.str("");
  EXPECT_EQ(RunCli({"aavio", "run", "seq", "--out", "x", "--start", "abc"}, out, err), kExitUsage);
  EXPECT_NE(err.str().find("--start: 'abc' is not a number; give one in [0, 1e+06]"),
            std::string::npos)
      << err.str();
  err.str("");
  EXPECT_EQ(RunCli({"aavio", "eval", "--est", "a", "--gt", "b", "--fractions", "0.5,2"}, out, err),
            kExitUsage);
  EXPECT_NE(err.str().find("--fractions: Value 2 not in range [1e-06, 1]"), std::string::npos)
      << err.str();
  // Disturbances of a twin: their form, then their ranges.
  err.str("");
  EXPECT_EQ(RunCli({"aavio", "simulate", "--out", "x", "--dark", "1"}, out, err), kExitUsage);
  EXPECT_NE(err.str().find("--dark 1: expected START:SECONDS in seconds of data"),
            std::string::npos)
      << err.str();
  err.str("");
  EXPECT_EQ(RunCli({"aavio", "simulate", "--out", "x", "--stop", "1:4:0"}, out, err), kExitUsage);
  EXPECT_NE(err.str().find("--stop 1:4:0: expected START:SECONDS in seconds of data"),
            std::string::npos)
      << err.str();
  err.str("");
  EXPECT_EQ(RunCli({"aavio", "simulate", "--out", "x", "--fast", "1:0.5:50"}, out, err),
            kExitUsage);
  EXPECT_NE(err.str().find("--fast 1:0.5:50: FACTOR must be in [1, 20]"), std::string::npos)
      << err.str();
  err.str("");
  EXPECT_EQ(RunCli({"aavio", "simulate", "--out", "x", "--fast", "0.1:0"}, out, err), kExitUsage);
  EXPECT_NE(err.str().find("--fast 0.1:0: SECONDS must be in [0.001, 86400]"), std::string::npos)
      << err.str();
}

TEST(Options, OutputFoldersAreNeverMixedOrSilentlyReplaced) {
  const fs::path dir = testing::ScratchDir();
  const std::string sequence = (dir / "sequence").string();
  const std::vector<std::string> simulate = {"aavio",  "simulate",   "--preset", "mini",   "--out",
                                             sequence, "--duration", "0.3",      "--quiet"};
  std::ostringstream out, err;
  ASSERT_EQ(RunCli(simulate, out, err), kExitOk) << err.str();
  // Again into the same folder: refused, the sequence untouched; --overwrite replaces it.
  err.str("");
  EXPECT_EQ(RunCli(simulate, out, err), kExitError);
  EXPECT_NE(err.str().find(sequence + ": holds the outputs of an earlier run (sequence.yaml, "),
            std::string::npos)
      << err.str();
  EXPECT_NE(err.str().find("pass --overwrite to replace them, or give --out another folder"),
            std::string::npos)
      << err.str();
  std::vector<std::string> again = simulate;
  again.push_back("--overwrite");
  ASSERT_EQ(RunCli(again, out, err), kExitOk) << err.str();

  const std::string run = (dir / "run").string();
  testing::WriteFile(fs::path(run) / "notes.txt", "mine");
  const std::vector<std::string> run_args = {"aavio", "run", sequence, "--out", run, "--quiet"};
  ASSERT_EQ(RunCli(run_args, out, err), kExitOk) << err.str();
  err.str("");
  EXPECT_EQ(RunCli(run_args, out, err), kExitError);
  EXPECT_NE(
      err.str().find(run + ": holds the outputs of an earlier run (stamped_traj_estimate.txt, "
                           "summary.json, timings.csv, config.yaml, map.ply, depth)"),
      std::string::npos)
      << err.str();
  std::vector<std::string> rerun = run_args;
  rerun.push_back("--overwrite");
  ASSERT_EQ(RunCli(rerun, out, err), kExitOk) << err.str();
  EXPECT_TRUE(fs::exists(fs::path(run) / "notes.txt"));  // not the run's: kept

  // Converting into the sequence's own folder would replace the input.
  err.str("");
  EXPECT_EQ(RunCli({"aavio", "convert", sequence, "--to", "txt", "--out", sequence, "--overwrite"},
                   out, err),
            kExitError);
  EXPECT_NE(err.str().find("is the folder of the sequence being converted"), std::string::npos)
      << err.str();
  EXPECT_TRUE(fs::exists(fs::path(sequence) / "sequence.yaml"));
}

TEST(Options, AnUnwritableOutputFolderIsRefusedBeforeTheRun) {
  const fs::path dir = testing::ScratchDir();
  std::ostringstream out, err;
  EXPECT_EQ(RunCli({"aavio", "simulate", "--preset", "mini", "--out", "/proc/self/aavio",
                    "--duration", "0.1", "--quiet"},
                   out, err),
            kExitError);
  EXPECT_NE(err.str().find("/proc/self/aavio: cannot create the folder"), std::string::npos)
      << err.str();
}

}  // namespace
}  // namespace aavio::cli
