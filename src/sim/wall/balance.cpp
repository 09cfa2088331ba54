// The tip-off rule (balance.hpp).
#include "balance.hpp"

#include <algorithm>
#include <cmath>

namespace repose::sim {

BalanceTurn tip_off_turn(std::span<const Vec3> vertices, const Quat& q, const Vec3& com, const Vec3& pivot,
                         const Vec2& line, double side, double offset, double on_line) {
  // The centre of mass's distance to the line's left (negative: to its right) and its height above the
  // pivot. A rotation by −α about the line moves it to the left: lean(α) = d·sin(α + atan2(lean, height)),
  // which is side·offset at α = asin(side·offset / d) − atan2(lean, height).
  const double lean = line.x() * (com.y() - pivot.y()) - line.y() * (com.x() - pivot.x());
  const double height = com.z() - pivot.z(), d = std::hypot(height, lean);
  double alpha = std::asin(std::min(1.0, side * offset / d)) - std::atan2(lean, height);
  // No vertex is turned below the wall: a vertex at (x, z) from the line (x towards the side the turn lowers)
  // goes to z·cos α − x·sin α; the turn stops where the first reaches the wall. A vertex within `on_line` of
  // the line is on it (the edge's other end): the turn moves it by at most on_line·α, and its x is round-off
  // whose sign, with the pivot on the wall, would stop the turn at 0 (atan2(x, z) ≥ π/2 for z ≤ 0).
  const Vec2 left(-line.y(), line.x());
  const double sense = alpha >= 0 ? 1.0 : -1.0;
  for (const Vec3& v : vertices) {
    const Vec3 r = com + q * v - pivot;
    const double x = sense * r.head<2>().dot(left), z = r.z(), reach = std::hypot(x, z);
    if (!(x > 0) || !(reach > on_line)) continue;
    const double limit = std::acos(std::clamp(-pivot.z() / reach, -1.0, 1.0)) - std::atan2(x, z);
    if (sense * alpha > limit) alpha = sense * std::max(limit, 0.0);
  }
  BalanceTurn tip;
  tip.axis = Vec3(line.x(), line.y(), 0.0);
  tip.angle = -alpha;
  tip.turn = Quat(Eigen::AngleAxisd(-alpha, tip.axis));
  return tip;
}

}  // namespace repose::sim
