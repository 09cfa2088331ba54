// Internal: every tolerance and numerical scale of the engine, in one place, each with its reason.
//
// A run's tolerances are built once (make_tolerances) from the particle's length L, the time scale
// τ = sqrt(L/g) and the parameters, so that they mean the same thing for a 50 µm grain and a boulder. The
// constants below are the relative factors they are built from, and the few dimensionless ones of the
// geometric tests and the impact law. No tolerance literal appears anywhere else in src/sim.
#pragma once

#include "repose/model/params.hpp"
#include "repose/model/particle.hpp"

namespace repose::sim {

namespace tol {
// ---- lengths, × L
inline constexpr double kTouch = 1e-9;  ///< a vertex this close to the wall is on it (touching set)
/// The frictional contact phase's points on the wall: within this of it and not leaving. A hundred times the
/// touching tolerance, so that the integrator's drift (its tolerance, 1e-9 of L per step at most) never
/// takes a point pressed on the wall out of the set between two steps.
inline constexpr double kFrictionalBand = 1e-7;
inline constexpr double kEvent = 1e-12;  ///< a vertex this far below where it started has pierced the wall
/// Below-the-wall is measured from where a vertex started, down to at most this many event tolerances, so
/// a vertex that already touches within round-off does not re-trigger at once.
inline constexpr double kPierceFloor = 100;
/// An edge balance (no motion, the centre of mass over the edge within the touching tolerance) is an
/// unstable equilibrium, not a rest: the particle is turned about the edge until its centre of mass is this
/// far beyond it and falls from there. Ten times the touching tolerance, so round-off never puts it back on
/// the balance; the fall from an offset δ takes about ln(d/δ)/λ (d: centre of mass to edge, λ: the inverted
/// pendulum's rate).
inline constexpr double kBalanceOffset = 1e-8;
/// A contact decision's margin within this much of its threshold gives no reach: the 2-D hull's
/// tolerances and round-off act there.
inline constexpr double kReachSlack = 1e-6;

// ---- times, × τ
inline constexpr double kPaperStep = 1e-3;       ///< the paper's fixed step unless set (its Fig 3 converges)
inline constexpr double kAdaptiveMaxStep = 0.2;  ///< the adaptive step's longest: decisions re-checked then
inline constexpr double kFirstStep = 0.05;       ///< the adaptive integrator's first trial step from rest
/// The impact rule's "pulled back within a tenth of a step" (impact_support.cpp) is on the paper's step;
/// the adaptive integrator's steps have no fixed length, so it uses this fixed time scale instead.
inline constexpr double kReboundWindow = 0.05;
inline constexpr double kSampleInterval = 1e-3;  ///< a time series' spacing unless set (adaptive runs)
/// × τ: a frictional contact phase still moving after this long (a polygon rolling on over its edges, a
/// slow creep) hands over to the paper's phase, which ends it in a rest: the run's time limit is ten times
/// as long, and every convex shape of the test suite's sweeps rests well within it.
inline constexpr double kFrictionalTime = 200;
inline constexpr double kMaxTime =
    2000;  ///< the automatic time limit, beyond the fall or the tosses' flights
/// A toss's bounces take at most (1 + E)/(1 − E) times its first fall (a ball's series); the factor is
/// kept within [1, kMaxBounceFactor] and 1 − E at least kMinOneMinusE for the automatic time limit.
inline constexpr double kMaxBounceFactor = 1e3;
inline constexpr double kMinOneMinusE = 1e-3;

// ---- speeds, energies, rates
inline constexpr double kSpeed = 1e-9;  ///< × sqrt(g·L): a contact point slower than this is not moving
/// × sqrt(g·L): the frictional contact phase takes a point on the wall as sliding along its slip above this
/// speed, and at rest (sticking, or starting to slide by Coulomb's law at zero slip) below it. Well above
/// kSpeed, since a sticking point's slip drifts by the integrator's error (its tolerance per step): the
/// slip of a point that stops sliding is located down to kSpeed, and a drift of a sticking point past this
/// is a slide that friction stops again at once.
inline constexpr double kSlipSpeed = 1e-6;
/// A point at rest slides once its slip exceeds this many slip_speeds, and a sliding point whose slip turned
/// back below that is at rest (issue 48): without the band a slip of about slip_speed whose direction turns
/// fast (a tiny slip under a sideways acceleration) alternated between the two rules at every event.
inline constexpr double kSlipHysteresis = 2;
/// × separation_speed: an impact's rebound slower than this is tested for a Zeno capture (the point's normal
/// acceleration under the other points' forces turning it back within the band: normal accelerations up to
/// kZenoReach² · g can capture); a faster rebound leaves the band under any acceleration met in the tests.
inline constexpr double kZenoReach = 10;
inline constexpr double kAccel = 1e-9;  ///< × g: a contact point's acceleration below this is none
inline constexpr double kStill = 1e-9;  ///< × m·g·L: kinetic energy below this is no motion (edge balances)
inline constexpr double kAxisRate = 1e-12;  ///< × sqrt(g/L): an angular velocity below this has no axis
/// × tolerance × m·g·L: the adaptive integrator's energy error allowed for in the bounds on how far a step
/// can turn the particle (measured at most 5.2 × tolerance × m·g·L).
inline constexpr double kEnergyErrorMargin = 10;
/// × the step: a rising point pulled back within this fraction of a step does not separate (a ping-pong
/// of near-empty steps).
inline constexpr double kPullBackFraction = 0.1;

// ---- dimensionless
/// A previous rotation axis whose horizontal part is shorter than this is vertical: it gives no hinge.
inline constexpr double kHorizontalAxis = 1e-6;
/// Two unit axes are the same line when |a·b| exceeds 1 minus this (round-off of normalised vectors).
inline constexpr double kSameAxis = 1e-14;
/// A line support's weight moment normal to the axis is none below this fraction of the whole moment, and
/// quantities of a line's tests are round-off below kLineRoundoff of their scale.
inline constexpr double kLineSmall = 1e-9;
inline constexpr double kLineRoundoff = 1e-12;
/// The ray test counts a hit on a triangle's edge within this relative barycentric tolerance, so a centre
/// of mass exactly above an edge is "on" the face; a determinant below kParallel is a ray in its plane.
inline constexpr double kRayEdge = 1e-12;
inline constexpr double kParallel = 1e-300;
/// The impact law: speeds below kTinySpeed of the approach speed are zero (its round-off); an energy target
/// is met within kEnergyMet of itself; Gauss–Seidel stops when a sweep changes the impulses by less than
/// kSweepChange of their scale.
inline constexpr double kTinySpeed = 1e-14;
inline constexpr double kEnergyMet = 1e-15;
inline constexpr double kSweepChange = 1e-16;
/// A sliding step that should stop the slip stops it if less than this fraction of its tangential speed is
/// left (the linear prediction is exact when the direction is fixed).
inline constexpr double kStopFraction = 1e-9;
/// A quaternion shorter than this is no orientation.
inline constexpr double kQuaternionNorm = 1e-12;
}  // namespace tol

/// One run's tolerances and scales, built from L, τ and the parameters.
struct Tolerances {
  double length = 0;           ///< L
  double time_scale = 0;       ///< τ = sqrt(L/g)
  double band = 0;             ///< ε: points within it are contacts (Algorithm 1), length
  double touch = 0;            ///< a vertex this close to the wall is on it, length
  double event = 0;            ///< a vertex this far below its start has pierced the wall, length
  double rss_threshold = 0;    ///< Algorithm 1's line/surface threshold, length²
  double speed = 0;            ///< a contact point slower than this is not moving, length/time
  double frictional_band = 0;  ///< the frictional contact phase's points on the wall: within this, length
  double slip_speed = 0;       ///< and sliding above this slip, length/time (kSlipSpeed)
  /// ... at rest when its kinetic energy is below m·g·band (it cannot lift the body out of the band) and
  /// nothing accelerates with the velocities at zero.
  double rest_energy = 0;
  /// A touch slower than this cannot carry the point out of that band again (sqrt(2·g·band)): plastic, so
  /// a rocking or hopping body's rebounds do not cascade without end.
  double separation_speed = 0;
  double still_acceleration = 0;  ///< an acceleration below this is none (kAccel·g), length/time²
  double still_energy = 0;        ///< kinetic energy below this is no motion, mass·length²/time²
  double axis_rate = 0;           ///< an angular velocity below this has no axis, rad/time
  double balance_offset = 0;      ///< how far beyond an edge balance the centre of mass is put, length
  double reach_slack = 0;         ///< see tol::kReachSlack, length
  double energy_margin = 0;       ///< the integrator's energy error allowed for, mass·length²/time²
  double dt = 0;                  ///< paper: the step; adaptive: the longest step (time)
  double first_step = 0;          ///< the adaptive integrator's first trial step from rest (time)
  double flight_max_step = 0;     ///< a spinning flight's longest step (time)
  double rebound_window = 0;      ///< the impact rule's step (impact_support.hpp): dt, or 0.05·τ (adaptive)
  double max_time = 0;            ///< the run's time limit (time)
  double frictional_time = 0;     ///< the frictional contact phase's longest (time), kFrictionalTime
};

/// The tolerances of a run of `particle` (mass m) with `params` (validated).
Tolerances make_tolerances(const Particle& particle, const SettleParams& params);

}  // namespace repose::sim
