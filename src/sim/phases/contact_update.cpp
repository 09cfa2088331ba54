// After every step of the contact phase: the contact set and type (Algorithm 1), the paper's stability test
// (section 2.4), the rest test, and the support the contacts call for (contact_support.cpp).
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <utility>

#include "../wall/stability.hpp"
#include "contact.hpp"

namespace repose::sim {

// Recomputes the contact and touching sets, checks for rest, and switches the support if the contacts call
// for another one. `omega` and `com_velocity` are the motion just before (for the impact law).
Contact::Outcome Contact::update(const Vec3& omega, const Vec3& com_velocity, bool heights_known,
                                 BandSource band_source) {
  Run& run = run_;
  const Tolerances& tol = run.tol;
  // A margin of the touching tolerance: points that reach the band together (mirror images) join together,
  // and a point sitting on the band's edge (on a rotation axis) does not flicker in and out with round-off.
  const double contact_level = tol.band + tol.touch;
  // Who may join: a vertex outside the set joins by entering the band (z ≤ ε, an event both integrators
  // locate), and at that event, or when contact begins, every vertex within the margin joins with it. With
  // no such event a vertex hovering in (ε, ε + margin] stays out: else it would join only if a step
  // happened to end while it hovered, which made the two integrators' contact sets differ (issue 12's
  // convergence check). Once the stability test has passed the set is the pose's own (no band events).
  const bool joins_to_margin = !band_events() || band_entered_ || contact_.empty();
  if (std::holds_alternative<AdaptiveStepper>(stepper_)) {
    // Only the vertices near the wall: picked from the step's event candidates when they hold the band
    // (the step's first update, before any change of support), else by a walk (the lowest vertex is among
    // them). Both give the same set, in index order.
    std::vector<int>& members = next_contact_;
    if (band_source == BandSource::step_candidates) {
      vertices_below_among(run.q, contact_level, event_candidates_, members);
      assert(band_matches_walk(contact_level, members));
    } else {
      vertices_below(run.q, contact_level, members, true);
    }
    const Vec3 r3 = run.q.toRotationMatrix().row(2).transpose();
    if (!joins_to_margin)
      std::erase_if(members, [&](int k) { return !in_contact_[k] && height_of(r3, k) > tol.band; });
    for (int k : contact_) in_contact_[k] = 0;
    contact_.swap(members);
    for (int k : contact_) {
      z_[k] = height_of(r3, k);
      in_contact_[k] = 1;
    }
  } else {
    if (!heights_known) heights(run.q, z_);
    contact_.clear();
    for (std::size_t k = 0; k < z_.size(); ++k) {
      in_contact_[k] = z_[k] <= contact_level && (joins_to_margin || in_contact_[k] || z_[k] <= tol.band);
      if (in_contact_[k]) contact_.push_back(static_cast<int>(k));
    }
  }
  touching_.clear();
  double lowest = INFINITY;
  for (int k : contact_) {
    lowest = std::min(lowest, z_[k]);
    if (z_[k] <= tol.touch) {
      touching_.push_back(k);
      in_contact_[k] = kTouchingPoint;
    }
  }
  run.record.note_depth(-lowest);

  // The regression of Algorithm 1 is done on the contact points' footprints on the wall, so the fitted
  // contact line lies in the wall plane: a hinge tilted by the ε band would make the particle swing about
  // an unphysical equilibrium above the wall.
  contact_points_.clear();
  footprints_.clear();
  for (int k : contact_) {
    contact_points_.push_back(world_vertex(run.q, k));
    footprints_.emplace_back(contact_points_.back().x(), contact_points_.back().y(), 0.0);
  }
  LineFit fit;
  run.record.set_type(run.surface.contact_type(footprints_, tol.rss_threshold, &fit), run.t);

  const Vec2 g(run.com.x(), run.com.y());
  // The paper's test first: a particle that rests at once (landed flat) has passed it too.
  if (run.surface.has_stability_test() && !finishing_ && stability_margin(contact_points_, g) > 0) {
    finishing_ = true;
    run.record.stable_time = run.t;
  }
  // The rest: three or more touching points hold the centre of mass. On a smooth surface, which has no
  // stability test, that landing is the only rest (the discretised surface has landed on a face and the
  // inelastic impact leaves no motion; this also ends the ever-faster rocking between the corners of the
  // bottom face): a damped particle creeps onto its facet.
  if (touching_points_hold(g) && (rest_ = flush_rest(run, support_))) return Outcome::rest;
  // A surface contact turns about the previous rotation axis: the paper's step remembers it at the end of
  // each step (dt before), the adaptive one from the motion just before this update, which the paper's
  // converges to as dt → 0 (its steps are up to 0.05·τ apart).
  if (std::holds_alternative<AdaptiveStepper>(stepper_)) remember_axis(omega);
  bool switched = choose_support(fit, g, omega, com_velocity);
  // An edge balance with no motion is left by the documented rule (contact_support.cpp), on a smooth surface
  // too: otherwise only round-off would tip it, after a time no model sets.
  if (kinetic_energy() < tol.still_energy) switched = tip_off_edge_balance(g) || switched;
  trace_update();
  return switched ? Outcome::new_support : Outcome::same_support;
}

// After a step that changed nothing the update decides (contact_adaptive_step.cpp): the heights of the
// contact points, the penetration bookkeeping and the remembered axis move on, nothing else.
void Contact::quiet_update() {
  const Vec3 r3 = run_.q.toRotationMatrix().row(2).transpose();
  double lowest = INFINITY;
  for (int k : contact_) {
    z_[k] = height_of(r3, k);
    lowest = std::min(lowest, z_[k]);
  }
  run_.record.note_depth(-lowest);
  remember_axis(rot_.omega);
  trace_update();
}

// After a step that ended where a vertex crossed the ε band (step.crossing) before the stability test has
// passed, with one touching point that is the support's: the update would take the new contact set and
// change nothing else if the decisions on it are those in force before the crossing (the test failing, no
// hold) and no point came within the touching tolerance of the wall, and the support's rule keeps it
// (choose_support): a line its point holds is kept with its axis (while the type is no point and the line
// holds), and a point pivot is kept until a point enters the band (so across a vertex leaving it). One
// touching point holds no rest and no edge balance. Then only the set changes (and the remembered axis, as
// the update remembers it), and true.
bool Contact::quiet_crossing(AdaptiveStepper& step) {
  const Tolerances& tol = run_.tol;
  if (!band_events() || touching_.size() > 1 || (!touching_.empty() && touching_[0] != support_vertex_))
    return false;
  const Decision& before = step.before;
  if (before.stable || before.hold) return false;
  if (support_.line ? before.type == ContactType::point || !before.line_holds : band_entered_) return false;
  // The set the update takes (update(): picked from the step's candidates; a vertex outside joins only
  // with an entry).
  const Vec3 r3 = run_.q.toRotationMatrix().row(2).transpose();
  std::vector<int>& members = next_contact_;
  vertices_below_among(run_.q, tol.band + tol.touch, event_candidates_, members);
  if (!band_entered_)
    std::erase_if(members, [&](int k) { return !in_contact_[k] && height_of(r3, k) > tol.band; });
  decision_touching_.clear();
  for (int k : members)
    if (height_of(r3, k) <= tol.touch) decision_touching_.push_back(k);
  if (decision_touching_ != touching_) return false;
  contact_.swap(members);
  const Decision after = decision_at(run_.q, true, event_candidates_);
  if (!(after == before)) {
    contact_.swap(members);
    return false;
  }
  for (int k : members) in_contact_[k] = 0;
  double lowest = INFINITY;
  for (int k : contact_) {
    z_[k] = height_of(r3, k);
    lowest = std::min(lowest, z_[k]);
    in_contact_[k] = 1;
  }
  for (int k : touching_) in_contact_[k] = kTouchingPoint;
  run_.record.note_depth(-lowest);
  remember_axis(rot_.omega);
  trace_update();
  // The search goes on from here with these decisions and the step's candidates.
  step.decision = after;
  step.keep_candidates = true;
  return true;
}

void Contact::trace_update() const {
  if (run_.trace)
    std::fprintf(stderr,
                 "t=%.9g type=%s contact=%zu touching=%zu finishing=%d support=%d line=%d axis=%g,%g,%g "
                 "omega=%g,%g,%g\n",
                 run_.t, to_string(run_.record.type()), contact_.size(), touching_.size(), finishing_,
                 support_vertex_, support_.line, support_.axis.x(), support_.axis.y(), support_.axis.z(),
                 rot_.omega.x(), rot_.omega.y(), rot_.omega.z());
}

// §2.4: a contact element (a hull face all of whose vertices are contacts) hit by the downward ray from the
// centre of mass, or the centre of mass's projection inside the polygon of contact points; either suffices.
// The first implies the second (an element's vertices are contacts, so the ray's foot, the centre of mass's
// projection, lies in their polygon) everywhere but on that polygon's boundary, so the polygon decides,
// as a margin (length) that is positive when the test passes. Fewer than three contacts: −∞. Outside the
// contacts' bounding box: minus the distance to the box, an upper bound of the true (negative) margin that
// spares most calls the 2-D hull (thousands of band points on a fine mesh). Collinear contacts give a
// segment, whose margin is minus the distance to it (never positive): a line of contacts holds nothing.
double Contact::stability_margin(const std::vector<Vec3>& points, const Vec2& g) const {
  if (points.size() < 3) return -INFINITY;
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const Vec3& p : points) {
    x0 = std::min(x0, p.x());
    x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y());
    y1 = std::max(y1, p.y());
  }
  const double dx = std::max({x0 - g.x(), g.x() - x1, 0.0}), dy = std::max({y0 - g.y(), g.y() - y1, 0.0});
  if (dx > 0 || dy > 0) return -std::hypot(dx, dy);
  std::vector<Vec2> plan;
  plan.reserve(points.size());
  for (const Vec3& p : points) plan.emplace_back(p.x(), p.y());
  return polygon_margin(convex_hull_2d(std::move(plan), run_.tol.touch), g);
}

// After the support or the pose changed: the lowest vertex's depth, if any, counts as penetration. The
// paper's integrator refreshes every height (its next step reads them); the adaptive one walks to the
// lowest vertex.
void Contact::note_penetration() {
  if (std::holds_alternative<AdaptiveStepper>(stepper_)) {
    run_.record.note_depth(-lowest_height());
    return;
  }
  heights(run_.q, z_);
  run_.record.note_depth(-*std::min_element(z_.begin(), z_.end()));
}

}  // namespace repose::sim
