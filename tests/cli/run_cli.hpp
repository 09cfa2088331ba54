// Runs the repose executable in a test and captures what it printed.
#pragma once

#include <string>

namespace repose::test {

struct CliResult {
  int exit_code = -1;
  std::string out;  ///< standard output
  std::string err;  ///< standard error
};

/// Runs `repose ARGS` through /bin/sh (ARGS is shell-quoted by the caller).
CliResult run_cli(const std::string& args);

}  // namespace repose::test
