// The free fall (section 2.1), exact, and the first touch that ends it.
#include <algorithm>

#include "settler.hpp"

namespace repose {

// The fall is exact: the closed form from its start, z(t) = z0 − v0·t − ½·g·t², to the touch time
// (−v0 + sqrt(v0² + 2·g·h))/g. Steps end on the grid of multiples of dt (observers see the fall there); a
// stop at the time limit or at advance_to() is not a step, so where a run is stopped never changes it.
void Settler::Impl::fall_step() {
  const double g = params.gravity, v0 = params.drop_speed;
  const double grid = static_cast<double>(fall_steps + 1) * dt;
  const double end = std::min({grid, touch_time, max_time, limit});
  t = end;
  if (end == touch_time) {
    ++steps;
    com.z() = -lowest_body_height;  // exactly touching
    fall_speed = v0 + g * touch_time;
    begin_contact(Vec3(0, 0, -fall_speed));
    return;
  }
  if (end == grid) {
    ++fall_steps;
    ++steps;
  }
  com.z() = params.drop_height - lowest_body_height - (v0 * t + 0.5 * g * t * t);
  fall_speed = v0 + g * t;
}

// First touch (or the start of a run at drop height 0): translation stops and the particle pivots about its
// lowest point; the impact conserves angular momentum about the new support.
void Settler::Impl::begin_contact(const Vec3& com_velocity) {
  falling = false;
  int lowest = 0;
  for (std::size_t k = 0; k < particle.hull.vertices.size(); ++k)
    if ((q * particle.hull.vertices[k]).z() < (q * particle.hull.vertices[lowest]).z())
      lowest = static_cast<int>(k);
  const Vec3 p = particle.hull.vertices[lowest];
  support = {Vec3(com.x() + (q * p).x(), com.y() + (q * p).y(), 0.0), p, false, Vec3::UnitX()};
  support_vertex = lowest;
  reach_radius = hull_radius + support.body.norm();
  com = sim::com_position(support, q);
  rot = {q, Vec3::Zero(), Vec3::Zero()};
  restart = true;
  restart_step = 0;
  update_contacts(Vec3::Zero(), com_velocity);
}
}  // namespace repose
