// Parameters of a settling run: units, gravity, damping, thresholds, time step, limits.
//
// Units: repose works in any consistent unit system; `gravity` fixes it. For --units si that is m, kg, s
// (g = 9.81 m/s²); for --units cgs it is cm, g, s (g = 981 cm/s²). Thresholds are fractions of the
// particle's characteristic length L, so they mean the same thing for a 50 µm grain and a 5 cm part.
#pragma once

#include <cmath>
#include <string>

#include "repose/geometry/types.hpp"

namespace repose {

enum class UnitSystem { si, cgs };

/// Standard gravity in the given unit system: 9.81 m/s² or 981 cm/s².
double standard_gravity(UnitSystem units);

/// The names of the units results are in, for output. repose computes in whatever consistent units the
/// caller's lengths, density and gravity are in; the command line offers these two systems.
struct UnitNames {
  const char* system;  ///< "si", "cgs", or "consistent" (a gravity of neither)
  const char* length;
  const char* mass;
  const char* time;
  const char* area;
  const char* volume;
  const char* density;       ///< mass per volume
  const char* area_density;  ///< mass per area (the shell inertia model)
  const char* inertia;       ///< mass·length²
  const char* energy;
  const char* speed;
  const char* angular_speed;
  const char* damping;  ///< torque per angular speed, mass·length²/time
  const char* acceleration;
};

/// The unit names of a system: m, kg, s, J (si) or cm, g, s, erg (cgs).
const UnitNames& unit_names(UnitSystem units);

/// The unit names of a run with this gravity: si's for 9.81, cgs's for 981 (what the command line sets),
/// otherwise generic ones ("length", "mass·length²/time²", ...).
const UnitNames& unit_names_for_gravity(double gravity);

/// How the particle's surface is treated (section 2.2 of the paper).
enum class SmoothMode {
  automatic,  ///< decide from the mesh: smooth if convex with every dihedral angle below 30°
  on,         ///< always rotate about the single lowest point
  off,        ///< point / line / surface contacts with the stability tests
};

/// How a rotation phase is integrated between contact events.
enum class Integrator {
  paper,     ///< the paper's fixed step: trapezoidal rule solved by pseudo-time iteration (Eqs 10-16)
  adaptive,  ///< Dormand–Prince 5(4) with error control and dense output; events located on the dense output
};

/// Every field is an entry of the parameter table (param_table.hpp), which names it for the CLI, scenario
/// files, JSON and Python and holds its range: a new field needs an entry there.
struct SettleParams {
  double gravity = 9.81;  ///< magnitude of g, length/time², along −z
  double damping = 0.0;   ///< C in Eq 4, torque per angular velocity (mass·length²/time)
  Integrator integrator = Integrator::adaptive;
  /// paper: the time step; adaptive: the longest step (time); 0 = automatic: 1e-3·sqrt(L/g) for paper,
  /// 0.2·sqrt(L/g) for adaptive.
  double dt = 0.0;
  /// adaptive: local error bound per step on the state scaled by L and sqrt(L/g) (absolute and relative).
  double tolerance = 1e-9;
  double contact_threshold = 0.05;  ///< ε as a fraction of L: points within ε·L of the wall are contacts
  /// Line vs surface (Algorithm 1): the contact set is a line when the residual sum of squares of its
  /// best-fit line is below this fraction of L². The paper's 0.1 (cm², for a particle of L ≈ 1 cm) is 0.1·L².
  double line_threshold = 0.1;
  SmoothMode smooth = SmoothMode::automatic;
  double drop_height = 0.0;  ///< initial height of the lowest point above the wall (length)
  double drop_speed = 0.0;   ///< initial downward speed (length/time), ≥ 0
  /// A toss (issue 14): the centre of mass's initial velocity (length/time) and the initial angular velocity
  /// (rad/time), world frame. The velocity's z adds to −drop_speed (give the downward speed one way only).
  Vec3 velocity = Vec3::Zero();
  Vec3 spin = Vec3::Zero();
  /// Impacts while airborne (docs/method.md, "Rebound"): Stronge's energetic coefficient of restitution E in
  /// [0, 1] and Coulomb's friction coefficient μ ≥ 0 (infinite: no slip). E = 0 with no spin and no
  /// horizontal velocity keeps the paper's touch (translation stops, rotation from rest).
  double restitution = 0.0;
  double friction = INFINITY;
  /// Impacts slower than this are plastic (E = 0): the approach speed of the fastest point that strikes,
  /// along the normal (length/time). A low-speed cut-off of restitution, as Bullet's restitution velocity
  /// threshold (0.2 m/s) and Box2D's (1 m/s) have: it ends a lively body's cascade of ever smaller
  /// rebounds. 0 (the default): E at every speed.
  double restitution_threshold = 0.0;
  double max_time = 0.0;        ///< simulated-time limit (time); 0 = automatic: 2000·sqrt(L/g) + fall time
  long max_steps = 20'000'000;  ///< step limit
  double quaternion_tolerance = 1e-8;  ///< convergence of the pseudo-time iteration (Eqs 12-16)
  int max_iterations = 100;            ///< bound on pseudo-time iterations per step
};

/// "paper" / "adaptive", and back (throws repose::Error for any other name).
const char* to_string(Integrator integrator);
Integrator parse_integrator(const std::string& name);

/// "auto" / "on" / "off", and back (throws repose::Error for any other name).
const char* to_string(SmoothMode mode);
SmoothMode parse_smooth_mode(const std::string& name);

/// Whether a run's touches are rigid-body impacts (restitution, friction, momentum carried over) rather than
/// the paper's (translation stops at the first touch, §2.1): a toss with spin or horizontal velocity, or E >
/// 0.
bool uses_impacts(const SettleParams& params);

/// Throws repose::Error naming the offending parameter if any is non-finite or out of its range in the
/// parameter table ("parameter NAME must be ...").
void validate(const SettleParams& params);

}  // namespace repose
