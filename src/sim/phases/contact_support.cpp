// The support the contact phase turns about: the one the contacts call for (impact_support.hpp for several
// points on the wall), whether a line support holds, and the rule that leaves an edge balance.
#include <algorithm>
#include <cmath>

#include "../wall/balance.hpp"
#include "../wall/stability.hpp"
#include "contact.hpp"

namespace repose::sim {

// The support the contacts call for, and the switch to it if it is new (then true).
bool Contact::choose_support(const LineFit& fit, const Vec2& g, const Vec3& omega, const Vec3& com_velocity) {
  Run& run = run_;
  const auto& verts = run.particle.hull.vertices;
  Support next;
  int next_vertex = support_vertex_;
  bool stop = false;  // a plastic impact at several points left no motion (impact_support.hpp)
  auto point_at = [&](int k) {
    next = {world_vertex(run.q, k), verts[static_cast<std::size_t>(k)], false, Vec3::UnitX()};
    next_vertex = k;
  };
  auto line_at = [&](int k, const Vec3& axis) {
    point_at(k);
    next.line = true;
    next.axis = axis.normalized();
  };

  // Several points on the wall: the support that lets the others lift off (impact_support.hpp).
  const SwitchState impact{run.body,     run.q,          run.com,       omega,
                           com_velocity, run.tol.length, run.tol.touch, run.tol.rebound_window};
  touches_.clear();
  for (int k : touching_)
    touches_.push_back({k, world_vertex(run.q, k), verts[static_cast<std::size_t>(k)], z_[k]});
  auto take = [&](const SupportChoice& c) {
    next = c.support;
    next_vertex = c.vertex;
    stop = c.stop;
  };

  if (!run.surface.has_contact_types()) {
    // A smooth surface turns about its lowest touching point (impact_support.hpp).
    const WallVertex current{support_vertex_, world_vertex(run.q, support_vertex_),
                             verts[static_cast<std::size_t>(support_vertex_)], z_[support_vertex_]};
    take(choose_smooth(impact, touches_, current, g));
  } else if (touching_.size() <= 1) {
    // One point on the wall: the paper's kinematics from the contact set (Algorithm 1), a rotation about
    // the best-fit line for a line contact, about the previous axis for a surface contact.
    const int o = touching_.empty() ? support_vertex_ : touching_[0];
    // The best-fit line is taken when the contact becomes a line and kept while the same point touches:
    // refitting as hovering points enter and leave the band makes the axis flip back and forth between
    // two lines, a cycle in which the particle never settles.
    // A pivot chosen from the touching points is kept until a new point enters the band: switching straight
    // back to the band's line would drive the point that just lifted into the wall again, a rocking cycle.
    const bool keep_line = support_.line && support_vertex_ == o;
    const bool keep_point = !support_.line && support_vertex_ == o && !band_entered_;
    const ContactType type = run.record.type();
    Vec3 axis = fit.direction;
    const bool line = type != ContactType::point && !keep_point;
    if (keep_line)
      axis = support_.axis;
    else if (type == ContactType::surface && prev_axis_ &&
             std::hypot(prev_axis_->x(), prev_axis_->y()) > tol::kHorizontalAxis)
      // The hinge lies in the wall, as the fitted line does (a tilted one would hold the particle above
      // it): the previous axis's direction on the wall. A turn about the vertical (a tossed, spinning
      // particle) gives none, and the fitted line serves; about a near-vertical hinge through one touching
      // point a spinning die hung, its damped spin dying out, until the time limit.
      axis = Vec3(prev_axis_->x(), prev_axis_->y(), 0);
    if (line && line_support(Pose{run.q, run.com}, contact_, contact_points_, o, axis).holds) {
      line_at(o, axis);
    } else {
      point_at(o);
    }
  } else {
    take(choose_from_touching(impact, touches_, g));
  }

  const bool same = next_vertex == support_vertex_ && next.line == support_.line &&
                    (!next.line || std::abs(next.axis.dot(support_.axis)) > 1 - tol::kSameAxis);
  if (same && !stop) {
    remember_axis(omega);
    return false;
  }
  const Vec3 momentum =
      stop ? Vec3::Zero() : momentum_after_switch(run.body, run.q, run.com, omega, com_velocity, next);
  // A new support that has sunk by round-off (≤ the event tolerance) is lifted exactly onto the wall; one
  // that touches from above (within the touching tolerance) stays where it is, so the switch never lowers
  // the particle.
  next.world.z() = std::max(next.world.z(), 0.0);
  set_support(next, next_vertex);
  note_penetration();
  rot_.q = run.q;
  rot_.momentum = momentum;
  rot_.omega = omega_from_momentum(run.body, support_, run.q, momentum);
  restart_motion(/*from_rest=*/false);
  remember_axis(rot_.omega);
  return true;
}

void Contact::set_support(const Support& next, int vertex) {
  support_ = next;
  support_vertex_ = vertex;
  reach_radius_ = run_.hull_radius + support_.body.norm();
  run_.com = com_position(support_, run_.q);
}

// The points of a contact line other than the touching point O hover up to ε above the wall; they can only
// push up. The line holds only if upward forces at them can take the part of the weight's moment about O
// that the line constraint removes (the component normal to the axis); otherwise the particle would tip
// about O away from them, and it rotates about the point instead. Without this, a line tilted by up to ε
// would act as a frictionless hinge on which the particle swings like a pendulum for ever.
//
// The reach (contact_decisions.cpp): while the particle turns about this line, every offset d from O keeps
// d·e and |d|, so only the weight's moment and the hovering points' lever turn; the tests on them are signs
// of quantities whose rate per radian is bounded by the product rule (|dc/dθ| ≤ |c| for any vector c turning
// about e): |normal part| and |moment| move at most m·g·|c| per radian (c: centre of mass − O), and
// −normal·arm at most 2·m·g·|c|·|lever|. `points[i]` is the set's vertex set[i] at the pose.
Contact::LineSupport Contact::line_support(const Pose& pose, std::span<const int> set,
                                           const std::vector<Vec3>& points, int o, const Vec3& axis) const {
  const double touch = run_.tol.touch;
  const Vec3 origin = world_vertex(pose.q, o);
  const Vec3 e = axis.normalized();
  const double weight = run_.body.mass * run_.params.gravity;
  const Vec3 moment = (pose.com - origin).cross(Vec3(0, 0, -weight));
  const Vec3 normal_part = moment - moment.dot(e) * e;
  const double weight_arm = weight * (pose.com - origin).norm();  // bounds |moment| and its rate per radian
  const double small = normal_part.norm() - tol::kLineSmall * moment.norm();
  // The rate of `small` per radian is at most (1 + kLineSmall)·weight_arm; kLineRoundoff covers round-off.
  const double small_reach = (std::abs(small) - tol::kLineRoundoff * weight_arm) / (2 * weight_arm);
  if (small <= 0) return {true, small_reach};
  bool ahead = false, behind = false;
  Vec3 lever = Vec3::Zero();
  for (std::size_t i = 0; i < set.size(); ++i) {
    const Vec3 d = points[i] - origin;
    if (set[i] == o || d.norm() <= touch) continue;
    const double s = d.dot(e);
    ahead = ahead || s > touch;
    behind = behind || s < -touch;
    lever += d;
  }
  if (ahead && behind) return {true, INFINITY};  // hovering points on both sides of O: either sense is held
  const Vec3 arm = lever.cross(Vec3::UnitZ());
  if (arm.squaredNorm() == 0) return {false, 0};
  const double need = -normal_part.dot(arm);  // the force needed at the hovering points is upward
  const double scale = weight_arm * lever.norm();
  const double need_reach = (std::abs(need) - tol::kLineRoundoff * scale) / (2 * scale);
  return {need >= 0, std::min(small_reach, need_reach)};
}

void Contact::remember_axis(const Vec3& omega) {
  if (support_.line)
    prev_axis_ = support_.axis;
  else if (omega.norm() > run_.tol.axis_rate)
    prev_axis_ = omega.normalized();
}

std::vector<Vec2> Contact::touching_polygon(const Quat& q) const {
  std::vector<Vec2> pts;
  for (int k : touching_) {
    const Vec3 w = world_vertex(q, k);
    pts.emplace_back(w.x(), w.y());
  }
  return convex_hull_2d(pts, run_.tol.touch);
}

// Static equilibrium on the wall: the touching points surround the centre of mass's projection.
bool Contact::touching_points_hold(const Vec2& g) const {
  if (touching_.size() < 3) return false;
  const std::vector<Vec2> poly = touching_polygon(run_.q);
  return poly.size() >= 3 && polygon_margin(poly, g) > -run_.tol.touch;
}

// With no motion left on a segment of touching points (an edge) whose line passes within the touching
// tolerance of the centre of mass's projection, the particle is balanced: the weight's moment is round-off.
// That is an unstable equilibrium, not a rest. Rule (docs/method.md, wall/balance.hpp): turn the particle
// about the edge until its centre of mass is tol::kBalanceOffset·L beyond it, on the side it leans to by
// round-off (the left of the edge's direction when exactly on it), with no motion; the run then integrates
// the fall, and its time.
// The same on a face whose stability margin is 0 to round-off (the centre of mass on its boundary), tipped
// outwards over that boundary edge. True if it was on a balance (the motion restarts).
bool Contact::tip_off_edge_balance(const Vec2& g) {
  Run& run = run_;
  const double touch = run.tol.touch;
  const std::vector<Vec2> poly = touching_polygon(run.q);
  if (poly.size() < 2) return false;
  // The edge: the touching segment, or, on a face that failed the paper's test (its flush rest was refused
  // before this), the face's boundary edge the centre of mass is on (a face whose stability margin is 0 to
  // round-off: tipped off it, outwards).
  Vec2 a = poly[0], edge = poly[1] - poly[0];
  double outward = 0;  // the side to tip to: +1 left of the edge, −1 right, 0 the side it leans to
  if (poly.size() >= 3) {
    Vec2 centre = Vec2::Zero();
    for (const Vec2& p : poly) centre += p / static_cast<double>(poly.size());
    double nearest = INFINITY;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec2 p = poly[i], side = poly[(i + 1) % poly.size()] - p;
      if (!(side.norm() > 0)) continue;
      const Vec2 n = side.normalized();
      const double distance = std::abs(n.x() * (g.y() - p.y()) - n.y() * (g.x() - p.x()));
      if (distance < nearest) {
        nearest = distance;
        a = p;
        edge = side;
        outward = n.x() * (centre.y() - p.y()) - n.y() * (centre.x() - p.x()) > 0 ? -1.0 : 1.0;
      }
    }
  }
  const Vec2 e = edge.normalized();
  const double along = (g - a).dot(e);
  const double lean = e.x() * (g.y() - a.y()) - e.y() * (g.x() - a.x());  // left of the edge: positive
  if (along < -touch || along > edge.norm() + touch || std::abs(lean) > touch) return false;
  // The pivot: the touching point nearest the edge's first end.
  int pivot_vertex = touching_[0];
  double nearest = INFINITY;
  for (int k : touching_) {
    const Vec3 w = world_vertex(run.q, k);
    const double d = (Vec2(w.x(), w.y()) - a).norm();
    if (d < nearest) {
      nearest = d;
      pivot_vertex = k;
    }
  }
  const Vec3 pivot = world_vertex(run.q, pivot_vertex);
  const double side = outward != 0 ? outward : lean < 0 ? -1.0 : 1.0;
  const BalanceTurn tip =
      tip_off_turn(run.particle.hull.vertices, run.q, run.com, pivot, e, side, run.tol.balance_offset, touch);
  run.q = (tip.turn * run.q).normalized();
  set_support({pivot, run.particle.hull.vertices[static_cast<std::size_t>(pivot_vertex)], true, tip.axis},
              pivot_vertex);
  rot_ = {run.q, Vec3::Zero(), Vec3::Zero()};
  restart_motion(/*from_rest=*/true);
  note_penetration();
  remember_axis(rot_.omega);
  return true;
}

}  // namespace repose::sim
