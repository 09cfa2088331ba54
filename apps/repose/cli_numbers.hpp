// Integer options in the forms the help shows: "2e7" and "1e3" are accepted where they are exact integers.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

namespace repose::cli {

/// `text` as the decimal digits of a whole number >= 0 if it is one exactly: "2000", "2e7", "1.5e3", "1E3";
/// nullopt for anything else ("1.5", "-3", "1e30" beyond 2^63, "0x10", "").
inline std::optional<std::string> exact_whole_number(const std::string& text) {
  if (text.empty() || text.find_first_not_of("0123456789") == std::string::npos)
    return text.empty() || text.size() > 19 ? std::nullopt : std::optional<std::string>(text);
  // Decimal scientific forms only: no hex, no inf/nan, no sign, no spaces.
  if (text.find_first_not_of("0123456789.eE+") != std::string::npos || !std::isdigit(text[0]))
    return std::nullopt;
  std::size_t used = 0;
  double x = NAN;
  try {
    x = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  // Below 2^53 every whole double is exact, and so is its decimal text.
  if (used != text.size() || !(x >= 0) || x > 9007199254740992.0 || x != std::floor(x)) return std::nullopt;
  return std::to_string(static_cast<std::uint64_t>(x));
}

/// A whole number >= `min`, in any form exact_whole_number takes (rewritten to digits before CLI11 converts
/// it, which would also wrap "-5" into a huge unsigned count).
inline CLI::Validator whole_number(std::uint64_t min) {
  return CLI::Validator(
      [min](std::string& text) -> std::string {
        const std::optional<std::string> digits = exact_whole_number(text);
        if (digits && std::stoull(*digits) >= min) {
          text = *digits;
          return {};
        }
        return "must be a whole number >= " + std::to_string(min) + ", got '" + text + "'";
      },
      "INT >= " + std::to_string(min));
}

/// Lets every integer option of `app` and its subcommands take "2e7" for 20000000 (a text that is not an
/// exact whole number is left to the option's own conversion and its message).
inline void accept_exponent_integers(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    if (type.rfind("INT", 0) != 0 && type.rfind("UINT", 0) != 0) continue;
    option->transform(CLI::Validator(
        [](std::string& text) -> std::string {
          if (const auto digits = exact_whole_number(text)) text = *digits;
          return {};
        },
        ""));
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) accept_exponent_integers(*sub);
}

}  // namespace repose::cli
