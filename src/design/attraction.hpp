// Outcomes that cannot start (issue 50): an outcome with a target above 0 whose faces are all unstable has
// probability 0 and a zero gradient, so the descent alone would never give it any (the ends of an elongated
// body). Such an outcome gets an attraction residual a = t·max(0, m₀ − m)/(κL), m the best stability margin
// among its faces (how far the centre of mass's projection lies inside the face's polygon; negative
// outside) and m₀ = DesignOptions::min_margin·L (0 by default, and for an outcome whose stable face starts
// closer to the edge): it pulls that face toward stability, and it is 0 once a face of the outcome is stable
// with margin m₀, where the probability's own residual takes over. With m₀ > 0 it also keeps a stable
// outcome's face from sliding to the edge of stability, where the descent stalls (an outcome about to lose
// its face refuses every step that goes on) and where a print error would make the face roll off.
// (convex_dice attracts unstable faces, and keeps stable faces central in their basins, with terms of its
// own.)
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

// Per outcome: its attraction residual (0 for an outcome with a target of 0, or with a stable face whose
// margin is at least the outcome's `margin_floor` (× L)).
std::vector<double> attraction(const Particle& particle, const RestLandscape& landscape,
                               const DesignTarget& target, const std::vector<double>& margin_floor);

// One row per outcome over the design variables (as jacobian()'s): the attraction's derivative (its margin,
// the centre of mass if it follows the shape, and L through the volume), the hull's structure and the
// margin's critical face and edge held (central differences, h = 1e-7·L), zero where the attraction is 0.
Eigen::MatrixXd attraction_rows(const Point& p, MassModel mass, ShapeFreedom shape);

}  // namespace repose::detail
