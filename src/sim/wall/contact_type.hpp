// Internal: the contact set and its type (section 2.2, Algorithm 1).
#pragma once

#include <vector>

#include "repose/geometry/types.hpp"
#include "repose/sim/settle.hpp"

namespace repose::sim {

/// Best-fit straight line through points (orthogonal regression: the principal direction of their scatter),
/// with the residual sum of squared distances to it.
struct LineFit {
  Vec3 centroid = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();
  double rss = 0;
};
LineFit fit_line(const std::vector<Vec3>& points);

/// Algorithm 1: one point → point; else line if the RSS of the best-fit line is below `rss_threshold`
/// (length²), else surface.
ContactType classify_contact(const std::vector<Vec3>& points, double rss_threshold, LineFit* fit = nullptr);

}  // namespace repose::sim
