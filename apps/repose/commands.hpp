// The subcommands of the repose command-line tool. Each registers itself and its options on the CLI11 app;
// the CLI parses, calls the library and prints, nothing more.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace repose::cli {

struct Command {
  CLI::App* app = nullptr;   ///< the subcommand, to ask whether it was given
  std::function<int()> run;  ///< runs it after parsing; returns the exit code
};

Command add_info_command(CLI::App& app);
Command add_settle_command(CLI::App& app);
Command add_paper_command(CLI::App& app);
Command add_poses_command(CLI::App& app);
Command add_merge_command(CLI::App& app);
Command add_design_command(CLI::App& app);

}  // namespace repose::cli
