// Design for the toss (issue 50, `repose design --model tossed`): the shape and/or centre of mass whose
// tossed landings (the dynamic model: a toss distribution, restitution, friction) have the target
// probabilities, started from the quasi-static design (docs/inverse-design.md, "Design for the toss").
//
// The objective is a Monte Carlo estimate over the same drops at every iterate (common random numbers: drop i
// has the same orientation and toss whatever the shape; an estimate of n drops uses drops 0 .. n−1, so that
// smaller estimates are prefixes of larger ones). The optimiser works in the space of quasi-static
// probabilities: each iterate is a quasi-static design (design.hpp) from the start toward a surrogate target
// q, and q is moved by quasi-Newton steps on the tossed residual (output space mapping): the Jacobian
// d(tossed)/dq by finite differences at the quasi-static design, then Broyden's updates; each step's length
// by a secant line search along it; at most 0.1 of change in any q per step. Each estimate's size follows the
// residual: its standard error about a third of it, up to `drops`.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "repose/design/design.hpp"
#include "repose/design/target.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/study.hpp"

namespace repose {

/// The tossed model a design is for, and how it is sampled.
struct TossModel {
  /// The toss as `repose poses` takes it: params (drop height, restitution, friction, gravity, ...), the toss
  /// distribution, damping ratio and seed. Always the dynamic method; every stable face its own pose.
  StudySettings settings;
  std::uint64_t drops = 20000;  ///< drops [0, drops) of settings.seed: the same at every iterate
  /// Drops [drops, drops + check_drops): the final check, never seen by the optimiser. Fewer than `drops`:
  /// the design is fitted to the common drops' noise, which adds (check_drops / drops) to the check's
  /// variance.
  std::uint64_t check_drops = 10000;
  int threads = 0;  ///< 0 = all cores (the results do not depend on it)
  /// If set, read between drops: once true, the design stops and throws repose::Cancelled.
  const std::atomic<bool>* cancel = nullptr;
};

/// The tossed landings of a set of drops, by outcome.
struct TossedOutcomes {
  DropRange drops;
  /// Per outcome, then the faces of no outcome, then the drops that did not rest (max_time/max_steps).
  std::vector<std::uint64_t> counts;
  std::vector<double> probability;          ///< counts / drops, the same order
  std::vector<std::array<double, 2>> ci95;  ///< Wilson 95 % intervals, the same order
  double max_error = 0;                     ///< max over the outcomes of |probability − target|
  /// Pearson's χ² of the outcomes' counts against the target (the drops that landed on an outcome; the
  /// other two entries are reported, not tested), its degrees of freedom (outcomes − 1) and p-value.
  double chi_square = 0;
  int dof = 0;
  double p_value = 1;
  bool all_within_ci95 = false;  ///< every outcome's target inside its interval, and no drop elsewhere
  /// The same with simultaneous intervals: Wilson's at 1 − 0.05/outcomes each (Bonferroni), so that all of
  /// them hold together with probability ≥ 95 % (five 95 % intervals all hold only ~77 % of the time).
  bool all_within_simultaneous = false;
  /// The tossed design's check only: the drops its design was fitted on (0 for any other estimate), and
  /// whether every outcome's check lies within t ± z·sqrt(t(1 − t)(1/N_fit + 1/M)) of its target t, the
  /// fit's own sampling noise counted with the check's (z = 1.96 each; Bonferroni's z for all together): a
  /// design fitted to N drops is off its target by that sample's noise, so the check's own intervals cover
  /// the target less often than they say (docs/inverse-design.md, "Design for the toss").
  std::uint64_t fit_drops = 0;
  bool all_within_fit_and_check = false;
  bool all_within_fit_and_check_simultaneous = false;
};

struct TossDesignOptions {
  DesignOptions shape;  ///< what may change and its bounds: every quasi-static design uses them
  TossModel model;
  int max_iterations = 12;  ///< quasi-Newton steps (each trial one tossed estimate; retries count)
  int max_retries = 2;      ///< a step that does not lower the tossed objective is tried shorter this often
  std::uint64_t min_drops = 1000;  ///< the smallest estimate (while the residual is large)
  /// The finite differences' change of an outcome's quasi-static probability (the first Jacobian).
  double difference_step = 0.05;
  /// Done when every outcome's estimate over `drops` is within this of its target; 0: when its χ² against the
  /// target is below the median of χ² (outcomes − 1 degrees of freedom), as close as a typical sample of the
  /// target itself, below which the sample's own noise would be fitted rather than the physics.
  double tolerance = 0;
};

/// One tossed estimate of the optimiser.
struct TossDesignStep {
  std::string kind;                  ///< "start" (the quasi-static design), "difference" or "step"
  std::vector<double> surrogate;     ///< the quasi-static target it was designed toward (per outcome)
  std::vector<double> quasi_static;  ///< what that design achieved quasi-statically (per outcome, other)
  TossedOutcomes tossed;             ///< its tossed estimate over the common drops
  /// Σ over the outcomes of (tossed − target)² less its sampling variance Σ p(1 − p)/(n − 1): unbiased for
  /// the true Σ (p − target)², so that estimates of different sizes compare.
  double objective = 0;
  int inner_iterations = 0;  ///< the quasi-static design's iterations
  std::string inner_stop;    ///< and how it stopped (DesignResult::stop)
  bool inner_restarted =
      false;              ///< it stopped short from the accepted design and was designed again from the start
  bool accepted = false;  ///< the tossed objective fell (the first step: the start, accepted)
  bool jacobian_reset = false;  ///< the secant Jacobian was singular: its steps from the identity
};

struct TossDesignResult {
  DesignResult quasi_static_design;  ///< the starting point: the quasi-static design for the target
  DesignResult design;               ///< the tossed design (its quasi-static probabilities in `achieved`)
  std::vector<TossDesignStep> history;
  /// The final check on drops the optimiser never saw: the tossed design and, on the same drops, the
  /// quasi-static design.
  TossedOutcomes check, check_quasi_static;
  std::uint64_t settles = 0;  ///< tossed drops simulated, the checks included
  std::string stop;           ///< "converged", "iterations" or "stalled" (no shorter step lowered it)
  bool reached() const { return stop == "converged"; }
};

/// The tossed landings of `particle` over `drops` under `model`, by the outcomes of `target` (assigned to
/// the particle's hull within options.outcome_angle).
TossedOutcomes tossed_outcomes(const Particle& particle, const DesignTarget& target, const TossModel& model,
                               DropRange drops, double outcome_angle);

/// Designs from `start` toward `target` under the tossed model. Throws repose::Error for options out of
/// range (a zero number of drops, a quasi-static method) and as design_quasi_static does.
TossDesignResult design_for_toss(const Particle& start, const DesignTarget& target,
                                 const TossDesignOptions& options);

}  // namespace repose
