// repose: predicts how a rigid particle settles on a flat wall and where it comes to rest.
//
// Exit codes: 0 success; 2 bad input (options, files, specs), with a one-line message on stderr; 3 a run
// that ended without coming to rest (settle), or drops that did not (poses; their results are still
// written); 130 interrupted by Ctrl-C (143 by SIGTERM), with a line saying what was kept; 1 an unexpected
// internal error.
#include <exception>
#include <iostream>
#include <vector>

#include "cli_numbers.hpp"
#include "commands.hpp"
#include "format.hpp"
#include "repose/error.hpp"
#include "suggest.hpp"

int main(int argc, char** argv) {
  CLI::App app{"repose: where and how an arbitrary-shaped particle comes to rest on a flat wall"};
  app.footer(
      "Run repose SUBCOMMAND --help for its options. Exit codes: 0 done; 1 internal error; 2 bad input (one "
      "line on stderr); 3 not at rest (settle: the run; poses: some drops, results still written); 130 "
      "interrupted by Ctrl-C (143 by SIGTERM).");
  app.require_subcommand(1);
  app.set_version_flag("--version", "repose 0.1.0");
  const std::vector<repose::cli::Command> commands = {
      repose::cli::add_info_command(app),  repose::cli::add_settle_command(app),
      repose::cli::add_paper_command(app), repose::cli::add_poses_command(app),
      repose::cli::add_merge_command(app), repose::cli::add_design_command(app),
  };
  repose::cli::accept_exponent_integers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "repose: error: " << repose::cli::parse_error_message(app, e, argc, argv) << "\n";
    return 2;
  }
  try {
    for (const auto& command : commands)
      if (command.app->parsed()) return command.run();
  } catch (...) {
    return repose::cli::report_error(std::current_exception());
  }
  return 1;
}
