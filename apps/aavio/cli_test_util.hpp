#pragma once
// Runs the aavio command line in-process, for the CLI's tests.

#include <sstream>
#include <string>
#include <vector>

#include "cli.hpp"

namespace aavio::cli::testing_cli {

struct Result {
  int code;
  std::string out, err;
};

inline Result RunAavio(const std::vector<std::string>& args) {
  std::vector<std::string> argv;
  argv.reserve(args.size() + 1);
  argv.emplace_back("aavio");
  for (const std::string& arg : args)
    argv.push_back(arg);
  std::ostringstream out, err;
  const int code = RunCli(argv, out, err);
  return {code, out.str(), err.str()};
}

}  // namespace aavio::cli::testing_cli
