// Static equilibrium on the touching points, the flush rest on a hull face, and edge balances (section 2.4).
#include <algorithm>
#include <cmath>

#include "settler.hpp"

namespace repose {

std::vector<Vec2> Settler::Impl::touching_polygon() const {
  std::vector<Vec2> pts;
  for (int k : touching) {
    const Vec3 w = world_vertex(k);
    pts.emplace_back(w.x(), w.y());
  }
  return sim::convex_hull_2d(pts, touch_tol);
}

// Static equilibrium on the wall: the touching points surround the centre of mass's projection.
bool Settler::Impl::touching_points_hold(const Vec2& g) const {
  if (touching.size() < 3) return false;
  const std::vector<Vec2> poly = touching_polygon();
  return poly.size() >= 3 && sim::polygon_margin(poly, g) > -touch_tol;
}

// With no motion left on a segment of touching points (an edge) whose line passes within touch_tol of the
// centre of mass's projection, the particle is balanced: the weight's moment is round-off. That is an
// unstable equilibrium, not a rest. Rule (docs/method.md): turn the particle about the edge until its
// centre of mass is kBalanceOffset·L beyond it, on the side it leans to by round-off (the left of the
// edge's direction when exactly on it), with no motion; the run then integrates the fall, and its time.
void Settler::Impl::tip_off_edge_balance(const Vec2& g) {
  const std::vector<Vec2> poly = touching_polygon();
  if (poly.size() != 2) return;
  const Vec2 a = poly[0], edge = poly[1] - poly[0];
  const Vec2 e = edge.normalized();
  const double along = (g - a).dot(e);
  const double lean = e.x() * (g.y() - a.y()) - e.y() * (g.x() - a.x());  // left of the edge: positive
  if (along < -touch_tol || along > edge.norm() + touch_tol || std::abs(lean) > touch_tol) return;
  const int pivot_vertex = nearest_touching(a);
  const Vec3 pivot = world_vertex(pivot_vertex);
  const Vec3 axis(e.x(), e.y(), 0.0);
  const double height = com.z() - pivot.z();
  const double d = std::hypot(height, lean);
  const double target = (lean < 0 ? -1.0 : 1.0) * kBalanceOffset * length;
  // A rotation by −α about the edge direction moves the centre of mass to the left by d·sin α.
  const double alpha = std::asin(target / d) - std::atan2(lean, height);
  const Quat turn(Eigen::AngleAxisd(-alpha, axis));
  q = (turn * q).normalized();
  support = {pivot, particle.hull.vertices[pivot_vertex], true, axis};
  support_vertex = pivot_vertex;
  reach_radius = hull_radius + support.body.norm();
  com = sim::com_position(support, q);
  rot = {q, Vec3::Zero(), Vec3::Zero()};
  restart = true;
  restart_step = 0;
  note_penetration();
  remember_axis(rot.omega);
}

// Finds the hull face under the centre of mass; if it is a statically stable face, sets it exactly flush on
// the wall and ends the run. Returns false (and changes nothing) otherwise.
bool Settler::Impl::come_to_rest() {
  const Vec3 down(0, 0, -1);
  int best = -1;
  double best_down = -INFINITY;
  for (std::size_t f = 0; f < particle.hull.faces.size(); ++f) {
    const HullFace& face = particle.hull.faces[f];
    const Vec3 n = q * face.normal;
    if (n.z() >= 0 || -n.z() <= best_down) continue;
    const Vec3 a = world_vertex(face.loop[0]);
    for (std::size_t i = 1; i + 1 < face.loop.size(); ++i) {
      if (sim::ray_hits_triangle(com, down, a, world_vertex(face.loop[i]), world_vertex(face.loop[i + 1]))) {
        best = static_cast<int>(f);
        best_down = -n.z();
        break;
      }
    }
  }
  if (best < 0 || particle.face_stability_margin[best] <= 0) return false;

  // Rotate the face flush about the support point, then lift or lower it onto the wall exactly.
  const HullFace& face = particle.hull.faces[best];
  const Quat align = Quat::FromTwoVectors(q * face.normal, down);
  q = (align * q).normalized();
  const Vec3 pivot = support.world;
  com = pivot + align * (com - pivot);
  support.world = com + q * support.body;
  double lowest = INFINITY;
  for (int k : face.loop) lowest = std::min(lowest, (com + q * particle.hull.vertices[k]).z());
  com.z() -= lowest;
  support.world.z() -= lowest;

  rest_points.clear();
  double deepest = 0;
  for (const Vec3& v : particle.hull.vertices) deepest = std::min(deepest, (com + q * v).z());
  max_penetration = std::max(max_penetration, -deepest);
  for (int k : face.loop) rest_points.push_back(com + q * particle.hull.vertices[k]);
  rest_face = best;
  rest = smooth ? RestKind::smooth : (particle.face_is_flat[best] ? RestKind::surface : RestKind::points);
  rot = {q, Vec3::Zero(), Vec3::Zero()};
  status = Status::rest;
  // Whatever the band looked like on the way down, the particle now rests on a face: a surface contact.
  if (!smooth) set_type(ContactType::surface);
  if (!phases.empty()) phases.back().t1 = t;
  return true;
}
}  // namespace repose
