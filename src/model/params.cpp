#include "repose/model/params.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "repose/error.hpp"
#include "repose/model/param_table.hpp"

namespace repose {

double standard_gravity(UnitSystem units) { return units == UnitSystem::si ? 9.81 : 981.0; }

const UnitNames& unit_names(UnitSystem units) {
  static const UnitNames si{"si",    "m",     "kg", "s",   "m²",    "m³",      "kg/m³",
                            "kg/m²", "kg·m²", "J",  "m/s", "rad/s", "kg·m²/s", "m/s²"};
  static const UnitNames cgs{"cgs",   "cm",    "g",   "s",    "cm²",   "cm³",     "g/cm³",
                             "g/cm²", "g·cm²", "erg", "cm/s", "rad/s", "g·cm²/s", "cm/s²"};
  return units == UnitSystem::si ? si : cgs;
}

const UnitNames& unit_names_for_gravity(double gravity) {
  static const UnitNames consistent{"consistent",
                                    "length",
                                    "mass",
                                    "time",
                                    "length²",
                                    "length³",
                                    "mass/length³",
                                    "mass/length²",
                                    "mass·length²",
                                    "mass·length²/time²",
                                    "length/time",
                                    "rad/time",
                                    "mass·length²/time",
                                    "length/time²"};
  for (const UnitSystem units : {UnitSystem::si, UnitSystem::cgs})
    if (gravity == standard_gravity(units)) return unit_names(units);
  return consistent;
}

namespace {

// The first value of the parameter outside its range, if any (a choice's enum always holds a valid one).
std::optional<double> outside_range(const ParamInfo& info, const SettleParams& p) {
  const ParamRange& r = info.range;
  const auto check = [&](double v) { return r.contains(v) ? std::nullopt : std::optional<double>(v); };
  return std::visit(Overloaded{[&](double SettleParams::*m) { return check(p.*m); },
                               [&](long SettleParams::*m) { return check(static_cast<double>(p.*m)); },
                               [&](int SettleParams::*m) { return check(p.*m); },
                               [&](Vec3 SettleParams::*m) {
                                 for (int i = 0; i < 3; ++i)
                                   if (!r.contains((p.*m)[i])) return check((p.*m)[i]);
                                 return std::optional<double>();
                               },
                               [](const ParamChoice&) { return std::optional<double>(); }},
                    info.member);
}

}  // namespace

const char* to_string(Integrator integrator) {
  return integrator == Integrator::adaptive ? "adaptive" : "paper";
}

Integrator parse_integrator(const std::string& name) {
  if (name == "adaptive") return Integrator::adaptive;
  if (name == "paper") return Integrator::paper;
  throw Error("unknown integrator '" + name + "' (expected paper or adaptive)");
}

const char* to_string(SmoothMode mode) {
  return mode == SmoothMode::on ? "on" : mode == SmoothMode::off ? "off" : "auto";
}

SmoothMode parse_smooth_mode(const std::string& name) {
  if (name == "auto") return SmoothMode::automatic;
  if (name == "on") return SmoothMode::on;
  if (name == "off") return SmoothMode::off;
  throw Error("unknown smooth mode '" + name + "' (expected auto, on or off)");
}

bool uses_impacts(const SettleParams& p) {
  return p.restitution > 0 || p.spin != Vec3::Zero() || p.velocity.x() != 0 || p.velocity.y() != 0;
}

void validate(const SettleParams& p) {
  for (const ParamInfo& info : param_table())
    if (const std::optional<double> bad = outside_range(info, p)) {
      char shown[32];
      std::snprintf(shown, sizeof shown, "%.10g", *bad);
      throw Error("parameter " + option_name(info) + " must be " + info.range.text + ", got " + shown);
    }
  if (p.drop_speed != 0 && p.velocity.z() != 0)
    throw Error("give the initial downward speed once: --drop-speed or the z of --velocity, not both");
}

}  // namespace repose
