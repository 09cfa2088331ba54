// Outcomes that cannot start (issue 50): an outcome with a target above 0 whose faces are all unstable has
// probability 0 and a zero gradient, so the descent alone would never give it any (the ends of an elongated
// body). Such an outcome gets an attraction residual a = t·max(0, −m)/(κL), m the best stability margin
// among its faces (how far the centre of mass's projection lies inside the face's polygon; negative
// outside): it pulls that face toward stability, and it is 0 once a face of the outcome is stable, where the
// probability's own residual takes over. (convex_dice attracts such faces with a term of its own.)
#pragma once

#include <Eigen/Core>
#include <vector>

#include "repose/design/basin_gradient.hpp"
#include "repose/design/design.hpp"
#include "repose/design/target.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace repose::detail {

struct Point;

// × L: a stability margin this far below 0 costs as much as the outcome's whole target.
constexpr double kAttractionLength = 0.1;

// Per outcome: its attraction residual (0 for an outcome with a stable face or a target of 0).
std::vector<double> attraction(const Particle& particle, const RestLandscape& landscape,
                               const DesignTarget& target);

// One row per outcome over the design variables (as jacobian()'s): the attraction's derivative (its margin,
// the centre of mass if it follows the shape, and L through the volume), the hull's structure and the
// margin's critical face and edge held (central differences, h = 1e-7·L), zero where the attraction is 0.
Eigen::MatrixXd attraction_rows(const Point& p, MassModel mass, ShapeFreedom shape);

}  // namespace repose::detail
