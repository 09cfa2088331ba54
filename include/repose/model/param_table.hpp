// One table of the settling parameters (issue 32): every field of SettleParams with its name, unit, range,
// help text and member. The CLI's options (apps/repose/physics_options.hpp), the scenario files' keys
// (scenario.cpp), the `settle --json` echo (report.cpp), a poses study's settings (study_settings.cpp), the
// Python keywords (python/src/runs.cpp) and validate() are all generated from it, so a new parameter is one
// entry in param_table.cpp plus its use in the engine.
//
// Defaults are SettleParams's own member initialisers (the engine's), read through the member:
// param_text(info, SettleParams{}) is the default, written once.
#pragma once

#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "repose/model/params.hpp"

namespace repose {

/// An enum-valued parameter, written as one of its names.
struct ParamChoice {
  std::span<const char* const> names;  ///< every accepted name, in the order messages list them
  const char* (*get)(const SettleParams&);
  void (*set)(SettleParams&, const std::string& name);  ///< throws repose::Error for an unknown name
};

/// Where in SettleParams a parameter lives. The alternative is its kind: a number, a whole number (long or
/// int), a vector [x, y, z] or a choice.
using ParamMember = std::variant<double SettleParams::*, long SettleParams::*, int SettleParams::*,
                                 Vec3 SettleParams::*, ParamChoice>;

/// The valid values of a number (of each component of a vector): between min and max, each bound open or
/// closed. A closed bound at infinity admits infinity (friction: no slip); NaN is never valid.
struct ParamRange {
  double min = -INFINITY, max = INFINITY;
  bool min_open = true, max_open = true;
  const char* text = "";  ///< the range in words, for messages: "must be TEXT" / "takes TEXT"

  bool contains(double x) const { return (min_open ? x > min : x >= min) && (max_open ? x < max : x <= max); }
  bool allows_infinity() const { return max == INFINITY && !max_open; }
};

/// Where a parameter is read and written besides the engine: bits of ParamInfo::uses.
enum ParamUse : unsigned {
  in_scenario = 1u << 0,     ///< a key of scenario files (scenario.hpp)
  in_summary = 1u << 1,      ///< the "parameters" of `settle --json` and of Python's settle results
  in_study = 1u << 2,        ///< the "settings" of poses result files and checkpoints: required when read...
  study_optional = 1u << 3,  ///< ...unless files written before it existed lack it (read_settings)
  in_python = 1u << 4,       ///< a keyword argument of repose.settle, repose.poses and repose.Settler
};

/// Which CLI options a parameter becomes, in groups registered where --help should list them.
enum class CliGroup {
  none,     ///< not an option
  physics,  ///< `settle` and `poses`, after --density and --units
  toss,     ///< `settle` only (`poses` draws its tosses: --velocity-max, --spin-max)
  impact,   ///< `settle` and `poses`, after the mesh options
};

struct ParamInfo {
  const char* name;  ///< snake_case: the JSON key and Python keyword; the CLI option is --name-with-dashes
  /// In words: "length/time"; "1": dimensionless; "L" ("L^2"): a fraction of the particle's characteristic
  /// length (squared).
  const char* unit;
  ParamMember member;
  ParamRange range = {};  ///< unused for a choice
  unsigned uses = 0;      ///< ParamUse bits
  CliGroup cli = CliGroup::none;
  const char* help = "";            ///< one line; "{default}" and "{unit}" are filled in by param_help
  const char* study_key = nullptr;  ///< the key in a study's settings when not `name` (files keep theirs)
};

/// Every parameter, in the order messages and --help list them.
std::span<const ParamInfo> param_table();

/// The entry named `name` (snake_case), or nullptr.
const ParamInfo* find_param(std::string_view name);

/// The CLI option's name without its dashes, as validate() names the parameter: "contact-threshold".
std::string option_name(const ParamInfo& info);

/// Sets the parameter in `to` to its value in `from`.
void copy_param(const ParamInfo& info, const SettleParams& from, SettleParams& to);

/// The value as a person writes it: "0.05", "1e-9", "2e7", "inf", "adaptive", "0,0,0".
std::string param_text(const ParamInfo& info, const SettleParams& params);

/// `help` (the entry's own if empty) with "{default}" and "{unit}" filled in.
std::string param_help(const ParamInfo& info, std::string_view help = {});

/// The names of the entries with every bit of `uses`, comma-separated, in table order.
std::string param_names(unsigned uses);

/// Calls the overload of `f` that fits the member's type, e.g. std::visit(Overloaded{...}, info.member).
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace repose
