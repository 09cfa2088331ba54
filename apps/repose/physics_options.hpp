// The physical options `settle` and `poses` share: density, units and the engine's parameters.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <exception>
#include <string>

#include "repose/error.hpp"
#include "repose/model/params.hpp"

namespace repose::cli {

struct PhysicsOptions {
  double density = 1.0;
  std::string units = "si";
  std::string smooth = "auto";
  std::string integrator;  ///< empty: the library's default
  std::string friction = "inf";
  SettleParams params;

  /// --friction: a number >= 0 or "inf" (no slip). Throws repose::Error otherwise.
  double friction_value() const {
    std::size_t used = 0;
    double mu = -1;
    try {
      mu = std::stod(friction, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (friction.empty() || used != friction.size() || std::isnan(mu) || mu < 0)
      throw Error("option --friction takes a number >= 0 or inf (no slip), got '" + friction + "'");
    return mu;
  }

  Integrator integrator_kind() const {
    return integrator.empty() ? SettleParams{}.integrator : parse_integrator(integrator);
  }

  UnitSystem unit_system() const { return units == "cgs" ? UnitSystem::cgs : UnitSystem::si; }
  SmoothMode smooth_mode() const {
    return smooth == "on" ? SmoothMode::on : smooth == "off" ? SmoothMode::off : SmoothMode::automatic;
  }
};

/// Registers --density, --units, --damping (with `damping_help`), --integrator, --dt, --tolerance,
/// --contact-threshold,
/// --line-threshold, --smooth, --drop-height, --drop-speed, --max-time and --max-steps on `sub`.
inline void add_physics_options(CLI::App& sub, PhysicsOptions& o, const std::string& damping_help) {
  sub.add_option("--density", o.density, "Density (kg/m^3 in si, g/cm^3 in cgs; default 1)");
  sub.add_option("--units", o.units, "si (m, kg, s; g = 9.81) or cgs (cm, g, s; g = 981)")
      ->check(CLI::IsMember({"si", "cgs"}));
  sub.add_option("--damping", o.params.damping, damping_help);
  sub.add_option("--integrator", o.integrator,
                 "Rotation phases: adaptive (Dormand-Prince 5(4) with events located on its dense output) or "
                 "paper (the paper's fixed step with its pseudo-time iteration); default " +
                     std::string(to_string(SettleParams{}.integrator)))
      ->check(CLI::IsMember({"paper", "adaptive"}));
  sub.add_option("--dt", o.params.dt,
                 "paper: the time step; adaptive: the longest step (0 or unset: automatic, 1e-3*sqrt(L/g) "
                 "for paper, 0.2*sqrt(L/g) for adaptive)");
  sub.add_option("--tolerance", o.params.tolerance,
                 "adaptive: local error bound per step, relative to L and sqrt(L/g) (default 1e-9)");
  sub.add_option("--contact-threshold", o.params.contact_threshold,
                 "Contact threshold as a fraction of L (default 0.05, as in the paper)");
  sub.add_option("--line-threshold", o.params.line_threshold,
                 "Line vs surface: RSS of the best-fit line below this fraction of L^2 (default 0.1)");
  sub.add_option("--smooth", o.smooth, "Smooth-particle model: auto | on | off (default auto)")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  sub.add_option("--drop-height", o.params.drop_height,
                 "Initial height of the lowest point above the wall (default 0: touching, at rest)");
  sub.add_option("--drop-speed", o.params.drop_speed, "Initial downward speed (default 0)");
  sub.add_option("--max-time", o.params.max_time,
                 "Simulated-time limit per run (0 or unset: automatic, 2000*sqrt(L/g) plus the fall time)");
  sub.add_option("--max-steps", o.params.max_steps, "Step limit per run (default 2e7)");
}

/// Registers --restitution and --friction (impacts while airborne) on `sub`.
inline void add_impact_options(CLI::App& sub, PhysicsOptions& o) {
  sub.add_option(
      "--restitution", o.params.restitution,
      "Impacts while airborne: Stronge's energetic coefficient of restitution E in [0, 1] (default 0: "
      "no rebound, the paper's touch)");
  sub.add_option(
      "--friction", o.friction,
      "Impacts while airborne: Coulomb's friction coefficient mu >= 0, or inf: no slip (default inf)");
}

}  // namespace repose::cli
