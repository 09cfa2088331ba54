// The quasi-static design's descent (design.cpp, toss_design.cpp): Levenberg–Marquardt from a design point
// toward a target, with the tape's exact Jacobian; every trial point a new hull and a new landscape, kept
// only if the objective falls and the bounds hold.
#pragma once

#include <string>
#include <vector>

#include "design_point.hpp"
#include "repose/design/design.hpp"

namespace repose::detail {

// What every descent of one design shares: the start, what may vary and the bounds (in the start's body
// frame, from where the start's vertices and planes were: a later descent keeps the first one's bounds).
struct DesignSetup {
  const Particle* start = nullptr;
  ShapeFreedom shape = ShapeFreedom::none;
  MassModel mass = MassModel::fixed;
  double length = 0;  // L of the start: the unit of every bound
  Bounds bounds;
};

// Checks `options` and builds the setup (throws repose::Error naming the option out of range).
DesignSetup design_setup(const Particle& start, const DesignOptions& options);

// The start evaluated for `target` (its outcomes assigned to the start's hull; throws repose::Error naming
// --outcome-angle if an outcome gets no face).
Point start_point(const DesignSetup& setup, DesignTarget target, const DesignOptions& options);

// `at` scored for another target of the same outcomes (another probability per outcome; `at`'s normals and
// faces).
Point retarget(const Point& at, const DesignTarget& target);

// DesignOptions::follow_outcome_normals: each outcome's normal moved to its most probable stable face's, the
// faces assigned afresh within `max_angle` and `p` scored again; true if a face changed outcome. If that
// would leave an outcome without a face, nothing changes and `kept` is set.
bool follow_outcome_normals(Point& p, double max_angle, bool& kept);

struct Descent {
  Point at;  // the last accepted point
  std::vector<DesignStep> history;
  std::string stop;  // "converged", "iterations" or "stalled" (DesignResult::stop)
};

// Levenberg–Marquardt iterations from `from` (evaluated for `target`) until every outcome is within
// options.tolerance, options.max_iterations have run, or no trial step lowers the objective.
Descent descend(Point from, const DesignTarget& target, const DesignSetup& setup,
                const DesignOptions& options);

// The public result of a descent: the design in the input mesh's frame, the start's and the design's
// probabilities.
DesignResult design_result(const DesignSetup& setup, const Point& start, const Descent& descent);

}  // namespace repose::detail
