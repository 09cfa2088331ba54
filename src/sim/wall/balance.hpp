// Internal: the tip-off rule (docs/method.md, "An edge balance is not a rest"). A body with no motion left,
// balanced on a line of the wall (an edge of touching points, or a face's boundary edge with the centre of
// mass on it to round-off), is turned about that line until its centre of mass is an offset beyond it, from
// where gravity tips it off. Both contact phases apply it: the paper's (phases/contact_support.cpp) and the
// frictional one (phases/frictional_balance.cpp).
#pragma once

#include <span>

#include "repose/geometry/types.hpp"

namespace repose::sim {

/// A turn of the body about a horizontal line through a pivot: orientation q → turn·q, a point x (world)
/// → pivot + turn·(x − pivot).
struct BalanceTurn {
  Quat turn = Quat::Identity();
  Vec3 axis =
      Vec3::UnitX();  ///< the line's direction (unit, in the wall's plane): turn is by `angle` about it
  double angle = 0;   ///< rad
};

/// The tip-off rule's turn of the body at orientation `q` with its centre of mass at `com` (world) and its
/// hull vertices `vertices` (body frame, about the centre of mass): about the horizontal line through `pivot`
/// (world) along `line` (a unit vector in the wall's plane), until the centre of mass is `offset` (length)
/// beyond the line on its left (`side` +1: towards ẑ × line) or its right (`side` −1). No hull vertex is
/// turned below the wall: the turn stops where the first reaches it (a new support); the vertices within
/// `on_line` (length) of the line are on it and do not stop it.
BalanceTurn tip_off_turn(std::span<const Vec3> vertices, const Quat& q, const Vec3& com, const Vec3& pivot,
                         const Vec2& line, double side, double offset, double on_line);

}  // namespace repose::sim
