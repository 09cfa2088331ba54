// Internal: a face flush on the wall that slides as a planar body (issue 34; docs/method.md, "Friction after
// the landing"). Its points all slide, or all but one, which sticks (the face turns about it) or starts to
// slide. The face stays on the wall: every point's normal acceleration is zero, so the centre of mass's
// vertical and the tilting accelerations follow from the planar ones. The normal forces vary linearly over
// the points that carry load, N_i = c0 + c1·x_i + c2·y_i, and the others carry none: the pressure under a
// rigid block on a tensionless elastic foundation (exact for three points; for more, the least-norm forces).
// Block Gauss–Seidel (contact_problem.hpp) does not converge on such a face: its normal forces are
// indeterminate and sliding friction makes the iteration unsymmetric.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "contact_forces.hpp"

namespace repose::sim {

/// The forces on the face of points `arms` by their rules; empty where the rule does not apply: fewer than
/// three non-collinear points carrying load (the face tips about an edge or a corner), more than one point at
/// rest, a singular system, or a starting slip whose direction was not found.
std::optional<ContactForces> sliding_face(const ContactBody& body, const Motion& motion,
                                          std::span<const Vec3> arms, double mu,
                                          std::span<const PointCondition> conditions);

}  // namespace repose::sim
