// The adaptive integrator's contact decisions as events of their own: what the contact update would decide
// at any instant of a step (decision_at), the first instant that changes, and a pass of the paper's
// stability test shorter than the spacing of the checks (brief_stability_pass); both located by the event
// locator on the dense output.
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "../events/events.hpp"
#include "../wall/stability.hpp"
#include "contact.hpp"

namespace repose::sim {

// Between membership events the decisions change continuously with the pose (the footprints and the centre
// of mass move), so each is a root of its own. (A point reaching the wall is a touch event of its own.)
//
// With `with_reach`, also how far the pose can turn before one of them can change: each is the sign of a
// margin whose rate per radian turned is bounded, because a point at distance r from the pivot moves by at
// most r per radian. The type: sqrt of the fit's residual is the smallest singular value of the centred
// footprints, which moves by at most sqrt(Σ r_k²) (Weyl; centring and the projection on the wall do not
// lengthen a displacement). The hold and the stability test: the distance of the centre of mass's footprint
// to the boundary of a convex polygon moves by at most r_g + max r_k. The line's support: line_support. A
// step whose swept angle is bounded below the reach needs no check inside it.
Contact::Decision Contact::decision_at(const Quat& qq, bool with_reach, std::span<const int> candidates) {
  const Run& run = run_;
  const Pose pose = pose_at(qq);
  // Once the stability test has passed, band crossings are not events (on a fine mesh there are hundreds a
  // drop, and only the decisions they change matter): the contact set is the one at this pose, among the
  // candidates.
  const bool own_set = decisions_use_own_set();
  if (own_set) vertices_below_among(qq, run.tol.band + run.tol.touch, candidates, decision_set_);
  const std::vector<int>& set = own_set ? decision_set_ : contact_;
  contact_points_.clear();
  footprints_.clear();
  for (int k : set) {
    contact_points_.push_back(world_vertex(qq, k));
    footprints_.emplace_back(contact_points_.back().x(), contact_points_.back().y(), 0.0);
  }
  const Vec2 g(pose.com.x(), pose.com.y());
  Decision d;
  LineFit fit;
  d.type = run.surface.contact_type(footprints_, run.tol.rss_threshold, &fit);
  double hold_margin = -INFINITY;
  std::size_t hold_corners = 0;
  if (touching_.size() >= 3) {
    const std::vector<Vec2> poly = touching_polygon(qq);
    hold_corners = poly.size();
    hold_margin = polygon_margin(poly, g);
  }
  d.hold = hold_corners >= 3 && hold_margin > -run.tol.touch;  // touching_points_hold(g)
  const double stability =
      run.surface.has_stability_test() && !finishing_ ? stability_margin(contact_points_, g) : -INFINITY;
  d.stable = stability > 0;
  const LineSupport line = support_.line
                               ? line_support(pose, set, contact_points_, support_vertex_, support_.axis)
                               : LineSupport{};
  d.line_holds = support_.line && line.holds;
  if (with_reach) {
    const double slack = run.tol.reach_slack;
    const double r_g = support_.body.norm();
    double r_max = 0, r2_sum = 0, r_touch = 0;
    const auto& verts = run.particle.hull.vertices;
    for (int k : set) {
      const double r = (verts[static_cast<std::size_t>(k)] - support_.body).norm();
      r_max = std::max(r_max, r);
      r2_sum += r * r;
    }
    for (int k : touching_)
      r_touch = std::max(r_touch, (verts[static_cast<std::size_t>(k)] - support_.body).norm());
    auto reach = [&](double room, double rate) {
      const double r = (room - slack) / rate;
      return r > 0 ? r : 0.0;  // (NaN too: no reach)
    };
    d.reach_of.fill(INFINITY);
    if (run.surface.has_contact_types() && set.size() >= 2)
      d.reach_of[0] =
          reach(std::abs(std::sqrt(fit.rss) - std::sqrt(run.tol.rss_threshold)), std::sqrt(r2_sum));
    // A polygon of fewer than three corners (collinear within the hull's tolerance) holds nothing until the
    // centre of mass's footprint comes within the touching tolerance of it.
    if (touching_.size() >= 3)
      d.reach_of[1] =
          reach(hold_corners >= 3 ? std::abs(hold_margin + run.tol.touch) : -hold_margin - run.tol.touch,
                r_g + r_touch);
    if (std::isfinite(stability)) d.reach_of[2] = reach(std::abs(stability), r_g + r_max);
    if (support_.line) d.reach_of[3] = line.reach > 0 ? line.reach : 0.0;
  }
  return d;
}

// Whether the contact set the decisions are taken on stays the same while the particle turns by at most
// `arc` from the step's start: before the stability test passes it changes only at events; after, a vertex
// joins or leaves it where its height crosses the band's level, and the step's event candidates (their
// heights at the start in z) are every vertex that could reach that level within the step.
bool Contact::contact_set_holds(double arc) const {
  if (!decisions_use_own_set()) return true;
  const double level = run_.tol.band + run_.tol.touch, slack = run_.tol.reach_slack;
  for (int k : event_candidates_)
    if (std::abs(z_[k] - level) - slack <=
        arc * (run_.particle.hull.vertices[static_cast<std::size_t>(k)] - support_.body).norm())
      return false;
  return true;
}

// If the contact decisions at `t_end` differ from those at the step's start `t0`, the step is cut just after
// the first change: the contact update then decides there, as the paper's fixed step does at dt → 0.
void Contact::locate_decision_change(AdaptiveStepper& step, double t0, double t_end,
                                     std::span<const double> inner) {
  const Decision start = step.decision ? *step.decision : decision_at(rot_.q, true, event_candidates_);
  step.before = start;
  // The decisions at the step's end are known (step.decision) only if it ends without an event.
  step.decision.reset();
  const bool to_step_end = step.ends == AdaptiveStepper::End::step;
  // A step too short to turn the particle by the decisions' reach cannot change them: no check inside it,
  // and the end's reach is what is left of the start's.
  const double arc = arc_bound(t_end - t0);
  if (arc < start.reach() && contact_set_holds(arc)) {
    if (to_step_end) {
      step.decision = start;
      for (double& r : step.decision->reach_of) r -= arc;
    }
    return;
  }
  const auto differs = [&](double s) {
    return !(decision_at(step.integrator.orientation_at(s), false, event_candidates_) == start);
  };
  // The step's inner sample instants first, so that a decision that changes and changes back within the
  // step (the stability test passing for a moment) is still seen; then its end.
  double lo = t0, hi = t_end;
  bool changed = false;
  for (std::size_t i = tol::kDecisionStride - 1; i < inner.size(); i += tol::kDecisionStride) {
    const double ts = inner[i];
    if (ts >= t_end) break;
    if (differs(ts)) {
      hi = ts;
      changed = true;
      break;
    }
    lo = ts;
  }
  if (!changed) {
    const Decision end = decision_at(step.integrator.orientation_at(t_end), true, event_candidates_);
    const double pass = end == start && !start.stable ? brief_stability_pass(step, t0, t_end) : -1;
    if (end == start && pass < 0) {
      if (to_step_end) step.decision = end;
      return;
    }
    if (pass >= 0) {  // the test passed for a moment between the checks: located like any change
      hi = pass;
      lo = t0;
    }
  }
  EventSearch search;
  search.resolution = (t_end - t0) * kEventResolution;
  search.max_halvings = kMaxHalvings;
  search.hi_holds_known = true;
  step.end = locate(lo, hi, search, differs, monotone).hi;
  step.ends = AdaptiveStepper::End::event;
  step.crossing = false;
}

// The paper's stability margin (contact_update.cpp) at orientation qq for the current contact set.
double Contact::stability_margin_at(const Quat& qq) {
  const Pose pose = pose_at(qq);
  contact_points_.clear();
  for (int k : contact_) contact_points_.push_back(world_vertex(qq, k));
  return stability_margin(contact_points_, Vec2(pose.com.x(), pose.com.y()));
}

// An instant in (t0, t1) at which the paper's stability test passes though it failed at the decision checks
// (a pass shorter than their spacing), or −1 if there is none: the stability test becoming true is an event
// of its own (issue 12), so it must not depend on where the checks fall. Before the test has passed the
// contact set changes only at events, so between t0 and t1 the margin moves only with the pose: every
// contact point and the centre of mass keep their distance r ≤ R from the pivot and move by at most r·dθ,
// so the margin is Lipschitz with constant 2·R·|ω|max (rate_bound). An interval whose end margins m_a, m_b
// satisfy m_a + m_b + 2·R·|ω|max·(b − a) ≤ 0 cannot hold a pass; others are halved, left first, down to
// the event resolution (a pass shorter than that is a tangency within round-off: none).
double Contact::brief_stability_pass(const AdaptiveStepper& step, double t0, double t1) {
  if (!run_.surface.has_stability_test() || finishing_ || contact_.size() < 3) return -1;
  const auto& verts = run_.particle.hull.vertices;
  double radius = support_.body.norm();  // the centre of mass's distance from the pivot
  for (int k : contact_)
    radius = std::max(radius, (verts[static_cast<std::size_t>(k)] - support_.body).norm());
  const double lipschitz = 2 * radius * rate_bound(t1 - t0);
  // The margins found so far in this search, by time (an interval's ends were found when it was made).
  margin_samples_.clear();
  const auto margin = [&](double s) {
    for (auto it = margin_samples_.rbegin(); it != margin_samples_.rend(); ++it)
      if (it->first == s) return it->second;
    const double m = stability_margin_at(step.integrator.orientation_at(s));
    margin_samples_.emplace_back(s, m);
    return m;
  };
  EventSearch search;
  search.resolution = (t1 - t0) * kEventResolution;
  search.any_instant = true;
  const Located pass = locate(
      t0, t1, search, [&](double s) { return margin(s) > 0; },
      [&](double a, double b) { return margin(a) + margin(b) + lipschitz * (b - a) <= 0; });
  return pass.kind == Located::Kind::instant ? pass.lo : -1;
}

}  // namespace repose::sim
