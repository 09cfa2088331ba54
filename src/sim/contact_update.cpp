// After every step: the contact set and type (Algorithm 1), the paper's stability test (section 2.4), and the
// support the contacts call for (impact_support.hpp for several points on the wall).
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <utility>

#include "settler.hpp"

namespace repose {

// Heights of all hull vertices for orientation `qq` about the current support (only the third row of R).
void Settler::Impl::heights(const Quat& qq, std::vector<double>& out) const {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  const auto& verts = particle.hull.vertices;
  for (std::size_t k = 0; k < verts.size(); ++k) out[k] = support.world.z() + r3.dot(verts[k] - support.body);
}

// Recomputes the contact and touching sets, checks for rest, and switches the support if the contacts call
// for another one. `omega` and `com_velocity` are the motion just before (for the impact law).
void Settler::Impl::update_contacts(const Vec3& omega, const Vec3& com_velocity, bool heights_known) {
  // A margin of 1e-9·L: points that reach the band together (mirror images) join together, and a point
  // sitting on the band's edge (on a rotation axis) does not flicker in and out with round-off.
  const double contact_level = band + touch_tol;
  // Who may join: a vertex outside the set joins by entering the band (z ≤ ε, an event both integrators
  // locate), and at that event, or when contact begins, every vertex within the margin joins with it. With
  // no such event a vertex hovering in (ε, ε + margin] stays out: else it would join only if a step
  // happened to end while it hovered, which made the two integrators' contact sets differ (issue 12's
  // convergence check). Once the stability test has passed the set is the pose's own (no band events).
  const bool joins_to_margin = !band_events() || band_entered || contact.empty();
  if (adaptive) {
    // Only the vertices near the wall: picked from the step's event candidates when they hold the band
    // (the step's first update, before any change of support), else by a walk (the lowest vertex is among
    // them). Both give the same set, in index order.
    std::vector<int>& members = next_contact;
    if (band_in_candidates) {
      vertices_below_among(q, contact_level, event_candidates, members);
      assert(band_matches_walk(contact_level, members));
    } else {
      vertices_below(q, contact_level, members, true);
    }
    band_in_candidates = false;
    const Vec3 r3 = q.toRotationMatrix().row(2).transpose();
    if (!joins_to_margin)
      std::erase_if(members, [&](int k) { return !in_contact[k] && height_of(r3, k) > band; });
    for (int k : contact) in_contact[k] = 0;
    contact.swap(members);
    for (int k : contact) {
      z[k] = height_of(r3, k);
      in_contact[k] = 1;
    }
  } else {
    if (!heights_known) heights(q, z);
    contact.clear();
    for (std::size_t k = 0; k < z.size(); ++k) {
      in_contact[k] = z[k] <= contact_level && (joins_to_margin || in_contact[k] || z[k] <= band);
      if (in_contact[k]) contact.push_back(static_cast<int>(k));
    }
  }
  touching.clear();
  double lowest = INFINITY;
  for (int k : contact) {
    lowest = std::min(lowest, z[k]);
    if (z[k] <= touch_tol) {
      touching.push_back(k);
      in_contact[k] = kTouchingPoint;
    }
  }
  max_penetration = std::max(max_penetration, -lowest);

  // The regression of Algorithm 1 is done on the contact points' footprints on the wall, so the fitted
  // contact line lies in the wall plane: a hinge tilted by the ε band would make the particle swing about
  // an unphysical equilibrium above the wall.
  contact_points.clear();
  footprints.clear();
  for (int k : contact) {
    contact_points.push_back(world_vertex(k));
    footprints.emplace_back(contact_points.back().x(), contact_points.back().y(), 0.0);
  }
  sim::LineFit fit;
  const ContactType new_type =
      smooth ? ContactType::point : sim::classify_contact(footprints, rss_threshold, &fit);
  set_type(new_type);

  const Vec2 g(com.x(), com.y());
  if (smooth) {
    // Three or more points on the wall around the centre of mass: the discretised surface has landed on a
    // face and the inelastic impact leaves no motion (this also ends the ever-faster rocking between the
    // corners of the bottom face). That landing is the only rest: a damped particle creeps onto its facet.
    if (touching.size() >= 3 && touching_points_hold(g) && come_to_rest()) return;
  } else {
    // The paper's test first: a particle that rests at once (landed flat) has passed it too.
    if (!finishing && stability_margin(contact_points, g) > 0) {
      finishing = true;
      stable_time = t;
    }
    if (touching_points_hold(g) && come_to_rest()) return;
  }
  // A surface contact turns about the previous rotation axis: the paper's step remembers it at the end of
  // each step (dt before), the adaptive one from the motion just before this update, which the paper's
  // converges to as dt → 0 (its steps are up to 0.05·τ apart).
  if (adaptive) remember_axis(omega);
  choose_support(fit, g, omega, com_velocity);
  // An edge balance with no motion is left by the documented rule (rest.cpp), on a smooth surface too:
  // otherwise only round-off would tip it, after a time no model sets.
  if (kinetic_energy() < 1e-9 * body.mass * params.gravity * length) tip_off_edge_balance(g);
  trace_update();
}

// After a step that changed nothing the update decides (adaptive_step.cpp): the heights of the contact
// points, the penetration bookkeeping and the remembered axis move on, nothing else.
void Settler::Impl::quiet_update() {
  const Vec3 r3 = q.toRotationMatrix().row(2).transpose();
  double lowest = INFINITY;
  for (int k : contact) {
    z[k] = height_of(r3, k);
    lowest = std::min(lowest, z[k]);
  }
  max_penetration = std::max(max_penetration, -lowest);
  remember_axis(rot.omega);
  trace_update();
}

void Settler::Impl::trace_update() const {
  if (trace)
    std::fprintf(stderr,
                 "t=%.9g type=%s contact=%zu touching=%zu finishing=%d support=%d line=%d axis=%g,%g,%g "
                 "omega=%g,%g,%g\n",
                 t, to_string(type), contact.size(), touching.size(), finishing, support_vertex, support.line,
                 support.axis.x(), support.axis.y(), support.axis.z(), rot.omega.x(), rot.omega.y(),
                 rot.omega.z());
}

void Settler::Impl::set_type(ContactType new_type) {
  if (!phases.empty() && phases.back().contact == new_type) return;
  if (!phases.empty()) phases.back().t1 = t;
  phases.push_back({new_type, t, t});
  type = new_type;
}

// §2.4: a contact element (a hull face all of whose vertices are contacts) hit by the downward ray from the
// centre of mass, or the centre of mass's projection inside the polygon of contact points; either suffices.
// The first implies the second (an element's vertices are contacts, so the ray's foot, the centre of mass's
// projection, lies in their polygon) everywhere but on that polygon's boundary, so the polygon decides,
// as a margin (length) that is positive when the test passes. Fewer than three contacts: −∞. Outside the
// contacts' bounding box: minus the distance to the box, an upper bound of the true (negative) margin that
// spares most calls the 2-D hull (thousands of band points on a fine mesh). Collinear contacts give a
// segment, whose margin is minus the distance to it (never positive): a line of contacts holds nothing.
double Settler::Impl::stability_margin(const std::vector<Vec3>& contact_points, const Vec2& g) const {
  if (contact_points.size() < 3) return -INFINITY;
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const Vec3& p : contact_points) {
    x0 = std::min(x0, p.x());
    x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y());
    y1 = std::max(y1, p.y());
  }
  const double dx = std::max({x0 - g.x(), g.x() - x1, 0.0}), dy = std::max({y0 - g.y(), g.y() - y1, 0.0});
  if (dx > 0 || dy > 0) return -std::hypot(dx, dy);
  std::vector<Vec2> plan;
  plan.reserve(contact_points.size());
  for (const Vec3& p : contact_points) plan.emplace_back(p.x(), p.y());
  return sim::polygon_margin(sim::convex_hull_2d(std::move(plan), touch_tol), g);
}

// The support the contacts call for (see the file comment), and the switch to it if it is new.
void Settler::Impl::choose_support(const sim::LineFit& fit, const Vec2& g, const Vec3& omega,
                                   const Vec3& com_velocity) {
  sim::Support next;
  int next_vertex = support_vertex;
  bool stop = false;  // a plastic impact at several points left no motion (impact_support.hpp)
  auto point_at = [&](int k) {
    next = {world_vertex(k), particle.hull.vertices[k], false, Vec3::UnitX()};
    next_vertex = k;
  };
  auto line_at = [&](int k, const Vec3& axis) {
    point_at(k);
    next.line = true;
    next.axis = axis.normalized();
  };

  // Several points on the wall: the support that lets the others lift off (impact_support.hpp).
  const sim::Impact impact{body, q, com, omega, com_velocity, length, touch_tol, rebound_window};
  touches.clear();
  for (int k : touching) touches.push_back({k, world_vertex(k), particle.hull.vertices[k], z[k]});
  auto take = [&](const sim::SupportChoice& c) {
    next = c.support;
    next_vertex = c.vertex;
    stop = c.stop;
  };

  if (smooth) {
    const sim::Touch current{support_vertex, world_vertex(support_vertex),
                             particle.hull.vertices[support_vertex], z[support_vertex]};
    take(sim::choose_smooth(impact, touches, current, g));
  } else if (touching.size() <= 1) {
    // One point on the wall: the paper's kinematics from the contact set (Algorithm 1), a rotation about
    // the best-fit line for a line contact, about the previous axis for a surface contact.
    const int o = touching.empty() ? support_vertex : touching[0];
    // The best-fit line is taken when the contact becomes a line and kept while the same point touches:
    // refitting as hovering points enter and leave the band makes the axis flip back and forth between
    // two lines, a cycle in which the particle never settles.
    // A pivot chosen from the touching points is kept until a new point enters the band: switching straight
    // back to the band's line would drive the point that just lifted into the wall again, a rocking cycle.
    const bool keep_line = support.line && support_vertex == o;
    const bool keep_point = !support.line && support_vertex == o && !band_entered;
    Vec3 axis = fit.direction;
    const bool line = type != ContactType::point && !keep_point;
    if (keep_line)
      axis = support.axis;
    else if (type == ContactType::surface && has_prev_axis && std::hypot(prev_axis.x(), prev_axis.y()) > 1e-6)
      // The hinge lies in the wall, as the fitted line does (a tilted one would hold the particle above
      // it): the previous axis's direction on the wall. A turn about the vertical (a tossed, spinning
      // particle) gives none, and the fitted line serves; about a near-vertical hinge through one touching
      // point a spinning die hung, its damped spin dying out, until the time limit.
      axis = Vec3(prev_axis.x(), prev_axis.y(), 0);
    if (line && line_support(o, axis).holds) {
      line_at(o, axis);
    } else {
      point_at(o);
    }
  } else {
    take(sim::choose_from_touching(impact, touches, g));
  }

  const bool same = next_vertex == support_vertex && next.line == support.line &&
                    (!next.line || std::abs(next.axis.dot(support.axis)) > 1 - 1e-14);
  if (same && !stop) {
    remember_axis(omega);
    return;
  }
  const Vec3 momentum =
      stop ? Vec3::Zero() : sim::momentum_after_switch(body, q, com, omega, com_velocity, next);
  // A new support that has sunk by round-off (≤ 1e-12·L) is lifted exactly onto the wall; one that touches
  // from above (within 1e-9·L) stays where it is, so the switch never lowers the particle.
  next.world.z() = std::max(next.world.z(), 0.0);
  support = next;
  support_vertex = next_vertex;
  reach_radius = hull_radius + support.body.norm();
  com = sim::com_position(support, q);
  note_penetration();
  rot.q = q;
  rot.momentum = momentum;
  rot.omega = sim::omega_from_momentum(body, support, q, momentum);
  restart = true;
  remember_axis(rot.omega);
}

// The points of a contact line other than the touching point O hover up to ε above the wall; they can only
// push up. The line holds only if upward forces at them can take the part of the weight's moment about O
// that the line constraint removes (the component normal to the axis); otherwise the particle would tip
// about O away from them, and it rotates about the point instead. Without this, a line tilted by up to ε
// would act as a frictionless hinge on which the particle swings like a pendulum for ever.
//
// The reach (decisions.cpp): while the particle turns about this line, every offset d from O keeps d·e and
// |d|, so only the weight's moment and the hovering points' lever turn; the tests on them are signs of
// quantities whose rate per radian is bounded by the product rule (|dc/dθ| ≤ |c| for any vector c turning
// about e): |normal part| and |moment| move at most m·g·|c| per radian (c: centre of mass − O), and
// −normal·arm at most 2·m·g·|c|·|lever|.
Settler::Impl::LineSupport Settler::Impl::line_support(int o, const Vec3& axis) const {
  const Vec3 origin = world_vertex(o);
  const Vec3 e = axis.normalized();
  const double weight = body.mass * params.gravity;
  const Vec3 moment = (com - origin).cross(Vec3(0, 0, -weight));
  const Vec3 normal_part = moment - moment.dot(e) * e;
  const double weight_arm = weight * (com - origin).norm();  // bounds |moment| and its rate per radian
  const double small = normal_part.norm() - 1e-9 * moment.norm();
  // The rate of `small` per radian is at most (1 + 1e-9)·weight_arm; a relative 1e-12 covers round-off.
  const double small_reach = (std::abs(small) - 1e-12 * weight_arm) / (2 * weight_arm);
  if (small <= 0) return {true, small_reach};
  bool ahead = false, behind = false;
  Vec3 lever = Vec3::Zero();
  // contact_points[i] is world_vertex(contact[i]) at this pose: both callers have just filled them.
  for (std::size_t i = 0; i < contact.size(); ++i) {
    const Vec3 d = contact_points[i] - origin;
    if (contact[i] == o || d.norm() <= touch_tol) continue;
    const double s = d.dot(e);
    ahead = ahead || s > touch_tol;
    behind = behind || s < -touch_tol;
    lever += d;
  }
  if (ahead && behind)
    return {true, INFINITY};  // hovering points on both sides of O: either sense can be held
  const Vec3 arm = lever.cross(Vec3::UnitZ());
  if (arm.squaredNorm() == 0) return {false, 0};
  const double need = -normal_part.dot(arm);  // the force needed at the hovering points is upward
  const double scale = weight_arm * lever.norm();
  const double need_reach = (std::abs(need) - 1e-12 * scale) / (2 * scale);
  return {need >= 0, std::min(small_reach, need_reach)};
}

// After the support or the pose changed: the lowest vertex's depth, if any, counts as penetration. The
// paper's integrator refreshes every height (its next step reads them); the adaptive one walks to the
// lowest vertex.
void Settler::Impl::note_penetration() {
  if (adaptive) {
    max_penetration = std::max(max_penetration, -lowest_height());
    return;
  }
  heights(q, z);
  max_penetration = std::max(max_penetration, -*std::min_element(z.begin(), z.end()));
}

void Settler::Impl::remember_axis(const Vec3& omega) {
  if (support.line) {
    prev_axis = support.axis;
    has_prev_axis = true;
  } else if (omega.norm() > 1e-12 * std::sqrt(params.gravity / length)) {
    prev_axis = omega.normalized();
    has_prev_axis = true;
  }
}

int Settler::Impl::nearest_touching(const Vec2& p) const {
  int best = touching[0];
  double best_d = INFINITY;
  for (int k : touching) {
    const Vec3 w = world_vertex(k);
    const double d = (Vec2(w.x(), w.y()) - p).norm();
    if (d < best_d) {
      best_d = d;
      best = k;
    }
  }
  return best;
}
}  // namespace repose
