// Internal: every tolerance and numerical scale of the engine, in one place, each with its reason.
//
// A run's tolerances are built once (make_tolerances) from the particle's length L, the time scale
// τ = sqrt(L/g) and the parameters, so that they mean the same thing for a 50 µm grain and a boulder. The
// constants below are the relative factors they are built from, the dimensionless ones of the geometric
// tests and the impact law, and the solvers' constants and loop bounds. No tolerance literal appears
// anywhere else in src/sim: tests/sim/tolerance_table_test.cpp fails on one.
#pragma once

#include <cstddef>
#include <limits>

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
/// Painlevé's dynamic jam (Génot & Brogliato 1999): a sliding point with W_nn − μ·W_nt·ŝ ≤
/// kJamCompliance·W_nn takes a normal force growing without bound as that goes to 0; once it is
/// kJamForce·m·(the problem's scale) it stops the slip within |u_t|/(μ·kJamForce·scale): resolved as the
/// impact without collision it tends to, leaving out below 1/(μ·kJamForce) of its momentum change
/// (docs/method.md; it stalled the phase before).
inline constexpr double kJamCompliance = 1e-2;
inline constexpr double kJamForce = 1e3;
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

// ---- solver constants and loop bounds (dimensionless; a bound keeps a loop finite, and reaching one is a
// counted fallback where the result could differ)
// The event locator (events.hpp). Events are located to kEventResolution of the step they happen in: 2^-44
// of a step of at most 0.2·sqrt(L/g) is below 1e-14·sqrt(L/g), far below a motion of 1e-9·L (the touching
// tolerance) at any speed the particle can have, and well above the round-off of the step's time. The
// paper's fixed step integrates each trial instant afresh (no dense output): its events are bracketed by
// kPaperHalvings halvings of the step (2^-48), the resolution its pinned reference runs are defined by.
// Bounds: halvings of one bracket, intervals examined by a search for the first instant (only a tangency
// within round-off could reach it), and the depth of halvings of an interval (2^-256 of any step is below
// the smallest spacing of times), which bounds the search's stack.
inline constexpr double kEventResolution = 0x1p-44;
inline constexpr int kPaperHalvings = 48;
inline constexpr int kMaxHalvings = 48;
inline constexpr int kMaxIntervals = 4096;
inline constexpr int kMaxDepth = 256;
/// An adaptive step (contact or frictional phase) is searched for events at this many evenly spaced instants
/// of its dense output, so a vertex that dips below the wall and back up inside one step is still caught.
inline constexpr int kEventSamples = 8;
/// The frictional contact phase's bound on a vertex's vertical acceleration over a step (the wall-crossing
/// search's A, events/wall_crossing.hpp) is this many times the largest mean rates of change of the
/// velocities between the step's event samples: the dense output is smooth to the integrator's tolerance
/// within a step of fixed contact rules, and its rates vary within an eighth of a step by far less than a
/// factor 2 (the 2,000-toss sweep: no vertex deeper than 1e-9·L, the same fallbacks as the 8 samples' Hermite
/// dip test it replaced).
inline constexpr double kAccelerationMargin = 2;
/// The contact phase's event search in a bracket takes part only the vertices that can decide it, by the
/// turn the energy bound allows there (rate_bound times the bracket) times this margin: the bound is on the
/// true motion, and the dense output follows it to the integrator's tolerance.
inline constexpr double kBracketTurnMargin = 2;
/// The contact phase: decisions are also checked at every kDecisionStride-th event sample instant; a support
/// chosen from several touching points is chosen again at once at most kRedecisions times.
inline constexpr std::size_t kDecisionStride = 2;
inline constexpr int kRedecisions = 2;
/// The contact phase: band crossings that change no decision passed over in one call of its step at most
/// (the engine's per-step checks then run, and the next call goes on).
inline constexpr int kQuietCrossings = 1024;
/// A spinning flight's touch search keeps this many samples of its candidates' heights.
inline constexpr std::size_t kFlightCachedSamples = 4;
/// Contact's band of vertex ids is sorted through a bitset from this many ids on (below, a comparison sort is
/// cheaper; above, a tenth of a 10,000-vertex grain's settle went to std::sort).
inline constexpr std::size_t kBitsetSortFrom = 64;
/// convex_hull_2d drops the points deeper than kHullInteriorDepth times its merging tolerance inside the
/// quadrilateral of its extreme points before its sort, from kHullFilterFrom points on (fewer: the sort is
/// cheaper than the pass). A point that deep is neither on the hull nor merged with a point on it.
inline constexpr double kHullInteriorDepth = 64;
inline constexpr std::size_t kHullFilterFrom = 32;

// The impact laws (rigid_impact.cpp, multi_impact.cpp, impact.cpp).
/// Several points on the wall may each need an impact (the first leaves another approaching): bounded.
inline constexpr int kImpactRounds = 16;
/// A run's rebounds are bounded: after this many impacts every touch hands over to the contact phase. A ball
/// with E = 0.99 bounces ~1,300 times before its rebounds fall below the touching tolerance; the bound stops
/// a chatter of ever-shorter flights (a particle with E near 1 rattling on its facets) from taking the run's
/// whole step budget.
inline constexpr std::size_t kMaxImpacts = 10000;
/// The one-point law's integration over the impulse: at most kImpactMaxSteps steps (reaching it falls back to
/// the frictionless law, ImpactOutcome::fallback, counted; no impact of tests/sim's 10,000 random and 10,000
/// grazing ones does). While the point slides its direction may turn: Cash–Karp 5(4) steps whose error
/// estimate is at most kImpactTolerance of the impulse (the larger of the frictionless compression impulse
/// and the impulse so far; the work's, times the approach speed), the first kImpactFirstSteps-th of the
/// compression impulse, each next one grown or shrunk by the error's room (at most kImpactGrowMax, at least
/// kImpactShrinkMin times, with the safety factor kImpactSafety). Where the direction does not turn (in a
/// plane, slipping again after a stop) the rates are constant: no error, and each step reaches its event
/// exactly.
inline constexpr int kImpactMaxSteps = 100000;
inline constexpr double kImpactTolerance = 1e-10;
inline constexpr double kImpactFirstSteps = 8;
inline constexpr double kImpactGrowMax = 5;
inline constexpr double kImpactShrinkMin = 0.2;
inline constexpr double kImpactSafety = 0.9;
inline constexpr double kImpactErrorOrder = 5;
/// A step onto the end of compression or restitution that overshoots it by more than the tolerance is
/// shortened by Newton's step at most this many times (each converges quadratically).
inline constexpr int kImpactEventIterations = 8;
/// Near a slip of zero: steps that change the slip by at most kImpactSlipChangePerStep of itself; a jump to
/// the predicted stop once the turn over it is below kImpactStopTurn rad, or the stop is within
/// kImpactStopReach of the impact's impulse scale; a slip below kImpactStoppedSlip of the approach speed has
/// stopped. A restitution that ends short of its energy target is continued; steps below
/// kImpactNegligibleStep of the normal impulse are round-off, and the target is met.
inline constexpr double kImpactSlipChangePerStep = 0.25;
inline constexpr double kImpactStopTurn = 1e-3;
inline constexpr double kImpactStopReach = 1e-6;
inline constexpr double kImpactStoppedSlip = 1e-6;
inline constexpr double kImpactNegligibleStep = 1e-15;
/// The direction in which sliding starts again is bracketed to round-off in far fewer halvings than this.
inline constexpr int kResumeHalvings = 200;
/// Gauss–Seidel sweeps of impulse_centre (several points without slip: their impulses' centre).
inline constexpr int kImpulseCentreSweeps = 10000;
/// Halvings of the restitution's normal impulses when Poisson's rule with friction would raise the energy
/// (after the last, none: the plastic impact alone); the kinetic energy's relative round-off, beyond which a
/// compression that adds energy has no exact solution's property.
inline constexpr int kRestitutionHalvings = 60;
inline constexpr double kKineticRoundOff = 1e-12;

// The contact forces (contact_problem.cpp, contact_newton.cpp, contact_pivoting.cpp, lemke.cpp,
// contact_forces.cpp, sliding_face.cpp).
/// Block Gauss–Seidel: a face's 4 to 40 points converge in tens of sweeps; the bound keeps an ill-conditioned
/// set (many nearly coincident points) finite. A sweep that changes no point's value by more than
/// kContactConverged of the scale has converged; one that changes the values by no less than the one before,
/// within kContactRoundOff of the terms they are summed from (64 ulps), has met round-off. The sweeps have
/// diverged once a value exceeds kContactDiverged times the scale (with sliding friction and μ above about 1
/// they need not contract).
inline constexpr int kContactSweeps = 5000;
inline constexpr double kContactConverged = 1e-14;
inline constexpr double kContactRoundOff = 64 * std::numeric_limits<double>::epsilon();
inline constexpr double kContactDiverged = 1e12;
/// Newton's method polishes the reactions where after kSweepsBeforeNewton sweeps they still contract by less
/// than kSlowSweep a sweep (and again after twice as many more each time it did not end them): most problems
/// converge within 30 sweeps, but an edge at the limit of its friction cone can take thousands. Its step
/// costs O((3n)³): beyond kMaxPolishedPoints points the sweeps alone are cheaper. Lemke's reactions polished
/// by it are a solution of the exact problem where a sweep from them changes no value by more than
/// kPolished of the scale (else the pyramid's answer is kept, counted).
inline constexpr int kSweepsBeforeNewton = 10;
inline constexpr double kSlowSweep = 0.2;
inline constexpr std::size_t kMaxPolishedPoints = 8;
inline constexpr double kPolished = 1e-10;
/// Newton's steps (quadratic near the solution; the bound keeps a problem without or with several solutions
/// finite), the halvings of its line search, and the points up to which its matrices live on the stack (a
/// face's corners, an edge: no allocation per step).
inline constexpr int kNewtonSteps = 30;
inline constexpr int kNewtonHalvings = 40;
inline constexpr int kNewtonStackPoints = 8;
/// The points up to which the contact solvers' per-point arrays are held inline (solver/point_list.hpp): a
/// frictional step on a face's corners or a grain's few allocates nothing; more points grow on the heap.
inline constexpr std::size_t kInlinePoints = 8;
/// A point at rest's force on its cone: Newton's steps on the secular equation (converges in a few; the
/// bound keeps it finite), and its bracket's doublings or halvings (2^±1100 covers every double).
inline constexpr int kCapSearchSteps = 200;
inline constexpr int kDoublingsOfADouble = 1100;
/// A floor for a scale that divides (the smallest scale of any problem here is far above it).
inline constexpr double kTinyScale = 1e-300;
/// The pivoting fallback's friction cone at points at rest: a pyramid of this many edges (the inscribed
/// polygon's force falls short of the cone by at most 1 − cos(π/12) = 3.4 %). Lemke's method ends within a
/// few pivots per unknown: kLemkePivotsPerUnknown·n + kLemkePivotsBase bounds a degenerate problem.
inline constexpr int kPyramidEdges = 12;
inline constexpr int kLemkePivotsPerUnknown = 50;
inline constexpr int kLemkePivotsBase = 100;
/// Lemke's tableau: the largest natural residual |min(z_i, w_i)| accepted relative to its vector's scale
/// (round-off of a well-posed tableau is ~1e-14; a pivot sequence that went astray leaves order one); ratios
/// within kLemkeTie of each other are a tie; entries below kLemkeTiny of the scale are zero.
inline constexpr double kLemkeResidual = 1e-9;
inline constexpr double kLemkeTie = 1e-12;
inline constexpr double kLemkeTiny = 1e-12;
/// Sliding points whose problem no solver reached are decided by enumerating the complementary sets of their
/// normal forces' LCP (2^n small solves) up to this many points (beyond, the failure is counted); a set's
/// forces and accelerations are non-negative within kEnumerationSlack of the scale; a point's value below
/// kModeTiny of the scale is none (its mode: stick, not slide).
inline constexpr std::size_t kMaxEnumeratedPoints = 10;
inline constexpr double kEnumerationSlack = 1e-12;
inline constexpr double kModeTiny = 1e-12;
/// A sliding face: its points hold no face where the smallest singular value of their scaled coordinates is
/// below kCollinearFace of the largest (collinear: an edge). A starting slip's direction: kDirectionRounds
/// fixed-point rounds, else a scan at kDirectionSamples angles (no two roots of a face's slip equation were
/// closer than 2π/40 in 1,500 random faces) and kDirectionBisections bisections of each sign change (to
/// round-off in the angle); a slip acceleration below kStillSlip·g has no direction, and a direction within
/// kStillSlip (relative) of the acceleration's is it.
inline constexpr double kCollinearFace = 1e-6;
inline constexpr int kDirectionRounds = 20;
inline constexpr int kDirectionSamples = 72;
inline constexpr int kDirectionBisections = 60;
inline constexpr double kStillSlip = 1e-12;

// The frictional contact phase (frictional_contact.cpp).
/// Impacts and impacts without collision at one instant: each round leaves no point approaching the wall, so
/// a few suffice; the bound keeps a degenerate set finite (counted: bounded_rounds).
inline constexpr int kSegmentRounds = 8;
/// Segments shorter than kStallTime·τ, kStalls of them in a row, are a stall (handed over, counted).
inline constexpr double kStallTime = 1e-12;
inline constexpr int kStalls = 8;
/// Balances tipped off in one phase (each leaves a face; a bound, never reached in the tests).
inline constexpr int kTipOffs = 8;
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
