// "Did you mean": the closest valid subcommand or option to a mistyped one.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace repose::cli {

/// The candidates closest to `typed` (leading dashes ignored): those at the least edit distance if it is at
/// most max(1, length / 3) (a transposition counts one), else those that begin with it or that it begins
/// with. Empty if none is close; several if they tie.
std::vector<std::string> closest(const std::string& typed, const std::vector<std::string>& candidates);

/// The message for a parse error of `argv` on `app` (one line, no "repose: error: "): for an unknown
/// subcommand or option, the closest valid ones and the help to read.
std::string parse_error_message(const CLI::App& app, const CLI::ParseError& error, int argc,
                                const char* const* argv);

}  // namespace repose::cli
