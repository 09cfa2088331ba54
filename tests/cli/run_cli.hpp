// Runs the repose executable in a test and captures what it printed.
#pragma once

#include <string>

namespace repose::test {

struct CliResult {
  int exit_code = -1;
  std::string out;  ///< standard output
  std::string err;  ///< standard error
};

/// Runs `LAUNCHER repose ARGS` through /bin/sh (ARGS is shell-quoted by the caller; LAUNCHER is, for
/// instance, "mpirun -np 2").
CliResult run_cli(const std::string& args, const std::string& launcher = "");

}  // namespace repose::test
