// The physical options `settle` and `poses` share: density, units and the engine's parameters, one option
// per entry of the parameter table (repose/model/param_table.hpp) named --name-with-dashes.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <exception>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "format.hpp"
#include "repose/error.hpp"
#include "repose/model/param_table.hpp"
#include "repose/poses/study.hpp"

namespace repose::cli {

struct PhysicsOptions {
  double density = 1.0;
  std::string units = "si";
  SettleParams params;  ///< numbers are bound to their fields
  /// Vectors, choices and numbers that may be inf, by parameter name: kept as given, parsed by apply_given.
  std::map<std::string, std::string> text;
  /// Parameters this command does not offer (an option of its own has the name): neither registered nor
  /// applied.
  std::set<std::string> skip;

  UnitSystem unit_system() const { return units == "cgs" ? UnitSystem::cgs : UnitSystem::si; }

  /// Sets in `p` every parameter whose option `sub` was given: on top of the defaults or a scenario's.
  /// Throws repose::Error naming the option for a value it cannot take.
  void apply_given(const CLI::App& sub, SettleParams& p) const;
};

/// Whether the option is taken as text (its own parser names it in errors) rather than bound to the field.
inline bool taken_as_text(const ParamInfo& info) {
  if (std::holds_alternative<double SettleParams::*>(info.member)) return info.range.allows_infinity();
  return std::holds_alternative<Vec3 SettleParams::*>(info.member) ||
         std::holds_alternative<ParamChoice>(info.member);
}

/// A number in the parameter's range, "inf" included (--friction); throws repose::Error naming `option`.
inline double parse_number_or_inf(const ParamInfo& info, const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double x = NAN;
  try {
    x = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || !info.range.contains(x))
    throw Error("option " + option + " takes " + info.range.text + ", got '" + text + "'");
  return x;
}

inline void PhysicsOptions::apply_given(const CLI::App& sub, SettleParams& p) const {
  for (const ParamInfo& info : param_table()) {
    const std::string option = "--" + option_name(info);
    const bool offered = info.cli != CliGroup::none && !skip.contains(info.name);
    const CLI::Option* given = offered ? sub.get_option_no_throw(option) : nullptr;
    if (given == nullptr || given->count() == 0) continue;  // not an option of this command, or not given
    const auto as_text = [&] { return text.at(info.name); };
    std::visit(Overloaded{[&](double SettleParams::*m) {
                            p.*m = taken_as_text(info) ? parse_number_or_inf(info, option, as_text())
                                                       : params.*m;
                          },
                          [&](Vec3 SettleParams::*m) { p.*m = parse_vector(option, as_text()); },
                          [&](const ParamChoice& c) { c.set(p, as_text()); },  // checked by IsMember
                          [&](auto m) { p.*m = params.*m; }},
               info.member);
  }
}

/// Registers the options of the table's `group` on `sub`, in table order; `help` replaces one entry's help
/// text (by parameter name; "{unit}" and "{default}" are filled in).
inline void add_param_options(CLI::App& sub, PhysicsOptions& o, CliGroup group,
                              const std::map<std::string, std::string>& help = {}) {
  for (const ParamInfo& info : param_table()) {
    if (info.cli != group || o.skip.contains(info.name)) continue;
    const std::string option = "--" + option_name(info);
    const auto own = help.find(info.name);
    const std::string text = param_help(info, own == help.end() ? std::string() : own->second);
    if (taken_as_text(info)) {
      CLI::Option* added = sub.add_option(option, o.text[info.name], text);
      if (const auto* c = std::get_if<ParamChoice>(&info.member))
        added->check(CLI::IsMember(std::vector<std::string>(c->names.begin(), c->names.end())));
      continue;
    }
    std::visit(Overloaded{[&](const ParamChoice&) {}, [&](Vec3 SettleParams::*) {},
                          [&](auto m) { sub.add_option(option, o.params.*m, text); }},
               info.member);
  }
}

/// Registers --density, --units and the table's physics options on `sub`; `damping_help`, if given, replaces
/// the table's help of --damping (a command where damping has another default).
inline void add_physics_options(CLI::App& sub, PhysicsOptions& o, const std::string& damping_help = {}) {
  sub.add_option("--density", o.density, "Density (kg/m^3 in si, g/cm^3 in cgs; default 1)");
  sub.add_option("--units", o.units, "si (m, kg, s; g = 9.81) or cgs (cm, g, s; g = 981)")
      ->check(CLI::IsMember({"si", "cgs"}));
  add_param_options(sub, o, CliGroup::physics, {{"damping", damping_help}});
}

/// Registers --restitution and --friction (impacts while airborne) on `sub`.
inline void add_impact_options(CLI::App& sub, PhysicsOptions& o) {
  add_param_options(sub, o, CliGroup::impact);
}

/// The toss distribution and the damping ratio, as `repose poses` and `repose design --model tossed` take
/// them.
struct TossDistributionOptions {
  double velocity_max = 0, spin_max = 0;  // the toss (length/time, rad/time)
  double damping_ratio = 0.05;            // C / (m sqrt(g L^3)), unless --damping is given
};

/// Registers --velocity-max, --spin-max and --damping-ratio on `sub`; `prefix` begins each help text (what
/// the options belong to, e.g. "Tossed: ").
inline void add_toss_distribution_options(CLI::App& sub, TossDistributionOptions& o,
                                          const std::string& prefix) {
  sub.add_option(
      "--velocity-max", o.velocity_max,
      prefix +
          "drop i's centre-of-mass speed uniform in [0, V] in a random direction (length/time; from "
          "drop i's own random stream)");
  sub.add_option("--spin-max", o.spin_max,
                 prefix + "drop i's angular speed uniform in [0, W] about a random axis (rad/time)");
  sub.add_option("--damping-ratio", o.damping_ratio,
                 prefix + "damping as C / (m*sqrt(g*L^3)) (default 0.05; the paper's ellipsoid used 0.063)");
}

/// Checks the damping ratio and the toss (before any output is written) and sets both on `s`.
inline void apply_toss_distribution(const TossDistributionOptions& o, StudySettings& s) {
  if (!std::isfinite(o.damping_ratio) || o.damping_ratio < 0)
    throw Error("option --damping-ratio must be a finite number >= 0, got " + num(o.damping_ratio));
  s.damping_ratio = o.damping_ratio;
  s.toss = {o.velocity_max, o.spin_max};
  validate(s.toss);
}

}  // namespace repose::cli
