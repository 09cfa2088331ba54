// The adaptive integrator's contact decisions as events of their own: what the contact update would decide
// at any instant of a step (decision_at), the first instant that changes (a bisection on the dense output),
// and a pass of the paper's stability test shorter than the spacing of the checks (brief_stability_pass).
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "settler.hpp"

namespace repose {

// What the contact update decides from the pose for the current contact and touching sets: the contact type
// (Algorithm 1 on the footprints), whether the touching points hold the centre of mass, whether the paper's
// stability test passes, whether a line support still holds. Between membership events these change
// continuously with the pose (the footprints and the centre of mass move), so each is a root of its own.
// (A point reaching the wall is a touch event of its own, located from below the wall, not here.)
//
// With `with_reach`, also how far the pose can turn before one of them can change (Decision::reach): each is
// the sign of a margin whose rate per radian turned is bounded, because a point at distance r from the
// pivot moves by at most r per radian. The type: sqrt of the fit's residual is the smallest singular value
// of the centred footprints, which moves by at most sqrt(Σ r_k²) (Weyl; centring and the projection on the
// wall do not lengthen a displacement). The hold and the stability test: the distance of the centre of
// mass's footprint to the boundary of a convex polygon moves by at most r_g + max r_k. The line's support:
// line_support. A step whose swept angle is bounded below the reach needs no check inside it.
Settler::Impl::Decision Settler::Impl::decision_at(const Quat& qq, bool with_reach) {
  const Quat q_now = q;
  const Vec3 com_now = com;
  q = qq;
  com = sim::com_position(support, q);
  // Once the stability test has passed, band crossings are not events (on a fine mesh there are hundreds
  // a drop, and only the decisions they change matter): the contact set is the one at this pose.
  const bool own_set = band_crossings_in_decisions();
  if (own_set) {
    // Inside a step every vertex in the band was, at the step's start, within band + touch_tol + arc·r of
    // the wall (arc: the angle the step can sweep; r its distance from the pivot): among the step's event
    // candidates, which begin_adaptive_step collected to that level.
    vertices_below_among(qq, band + touch_tol, event_candidates, decision_set);
    contact.swap(decision_set);
  }
  contact_points.clear();
  footprints.clear();
  for (int k : contact) {
    contact_points.push_back(world_vertex(k));
    footprints.emplace_back(contact_points.back().x(), contact_points.back().y(), 0.0);
  }
  const Vec2 g(com.x(), com.y());
  Decision d;
  sim::LineFit fit;
  d.type = smooth ? ContactType::point : sim::classify_contact(footprints, rss_threshold, &fit);
  double hold_margin = -INFINITY;
  std::size_t hold_corners = 0;
  if (touching.size() >= 3) {
    const std::vector<Vec2> poly = touching_polygon();
    hold_corners = poly.size();
    hold_margin = sim::polygon_margin(poly, g);
  }
  d.hold = hold_corners >= 3 && hold_margin > -touch_tol;  // touching_points_hold(g)
  const double stability = !smooth && !finishing ? stability_margin(contact_points, g) : -INFINITY;
  d.stable = stability > 0;
  const LineSupport line = support.line ? line_support(support_vertex, support.axis) : LineSupport{};
  d.line_holds = support.line && line.holds;
  if (with_reach) {
    const double slack = kReachSlack * length;
    const double r_g = support.body.norm();
    double r_max = 0, r2_sum = 0, r_touch = 0;
    for (int k : contact) {
      const double r = (particle.hull.vertices[k] - support.body).norm();
      r_max = std::max(r_max, r);
      r2_sum += r * r;
    }
    for (int k : touching) r_touch = std::max(r_touch, (particle.hull.vertices[k] - support.body).norm());
    auto reach = [&](double room, double rate) {
      const double r = (room - slack) / rate;
      return r > 0 ? r : 0.0;  // (NaN too: no reach)
    };
    d.reach_of.fill(INFINITY);
    if (!smooth && contact.size() >= 2)
      d.reach_of[0] = reach(std::abs(std::sqrt(fit.rss) - std::sqrt(rss_threshold)), std::sqrt(r2_sum));
    // A polygon of fewer than three corners (collinear within the hull's tolerance) holds nothing until the
    // centre of mass's footprint comes within touch_tol of it.
    if (touching.size() >= 3)
      d.reach_of[1] = reach(hold_corners >= 3 ? std::abs(hold_margin + touch_tol) : -hold_margin - touch_tol,
                            r_g + r_touch);
    if (std::isfinite(stability)) d.reach_of[2] = reach(std::abs(stability), r_g + r_max);
    if (support.line) d.reach_of[3] = line.reach > 0 ? line.reach : 0.0;
  }
  if (own_set) contact.swap(decision_set);
  q = q_now;
  com = com_now;
  return d;
}

// Whether the contact set the decisions are taken on stays the same while the particle turns by at most
// `arc` from the step's start: before the stability test passes it changes only at events; after, a vertex
// joins or leaves it where its height crosses the band's level, and the step's event candidates (their
// heights at the start in z) are every vertex that could reach that level within the step.
bool Settler::Impl::contact_set_holds(double arc) const {
  if (!band_crossings_in_decisions()) return true;
  const double level = band + touch_tol, slack = kReachSlack * length;
  for (int k : event_candidates)
    if (std::abs(z[k] - level) - slack <= arc * (particle.hull.vertices[k] - support.body).norm())
      return false;
  return true;
}

// If the contact decisions at `t_end` differ from those at the step's start `t0`, the step is cut just after
// the first change (bisection on the dense output): the contact update then decides there, as the paper's
// fixed step does at dt → 0.
void Settler::Impl::locate_decision_change(double t0, double t_end, std::span<const double> inner) {
  const Decision start = decision_cached ? cached_decision : decision_at(rot.q, true);
  decision_cached = false;
  // A step too short to turn the particle by the decisions' reach cannot change them: no check inside it,
  // and the end's reach is what is left of the start's.
  const double arc = arc_bound(t_end - t0);
  if (arc < start.reach() && contact_set_holds(arc)) {
    cached_decision = start;
    for (double& r : cached_decision.reach_of) r -= arc;
    end_decision_known = !step_event;
    return;
  }
  // The step's inner sample instants first, so that a decision that changes and changes back within the
  // step (the stability test passing for a moment) is still seen; then its end.
  double lo = t0, hi = t_end;
  bool changed = false;
  for (std::size_t i = kDecisionStride - 1; i < inner.size(); i += kDecisionStride) {
    const double ts = inner[i];
    if (ts >= t_end) break;
    if (decision_at(integrator->orientation_at(ts)) != start) {
      hi = ts;
      changed = true;
      break;
    }
    lo = ts;
  }
  if (!changed) {
    const Decision end = decision_at(integrator->orientation_at(t_end), true);
    end_decision_known = !step_event && end == start;
    const double pass = end == start && !start.stable ? brief_stability_pass(t0, t_end) : -1;
    if (end == start && pass < 0) {
      cached_decision = end;
      return;
    }
    if (pass >= 0) {  // the test passed for a moment between the checks: bisected like any change
      hi = pass;
      lo = t0;
      end_decision_known = false;
    }
  } else {
    end_decision_known = false;
  }
  const double resolution = (t_end - t0) * 0x1p-44;
  for (int i = 0; i < kBisections && hi - lo > resolution; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (decision_at(integrator->orientation_at(mid)) == start)
      lo = mid;
    else
      hi = mid;
  }
  step_end = hi;
  step_event = true;
  step_band_entered = false;
}

// The paper's stability margin (contact_update.cpp) at orientation qq for the current contact set.
double Settler::Impl::stability_margin_at(const Quat& qq) {
  const Quat q_now = q;
  const Vec3 com_now = com;
  q = qq;
  com = sim::com_position(support, q);
  contact_points.clear();
  for (int k : contact) contact_points.push_back(world_vertex(k));
  const double m = stability_margin(contact_points, Vec2(com.x(), com.y()));
  q = q_now;
  com = com_now;
  return m;
}

// An instant in (t0, t1) at which the paper's stability test passes though it failed at the decision checks
// (a pass shorter than their spacing), or −1 if there is none: the stability test becoming true is an event
// of its own (issue 12), so it must not depend on where the checks fall. Before the test has passed the
// contact set changes only at events, so between t0 and t1 the margin moves only with the pose: every
// contact point and the centre of mass keep their distance r ≤ R from the pivot and move by at most r·dθ,
// so the margin is Lipschitz with constant 2·R·|ω|max (rate_bound). An interval whose end margins m_a, m_b
// satisfy m_a + m_b + 2·R·|ω|max·(b − a) ≤ 0 cannot hold a pass; others are halved, left first, down to
// 2^-44 of the step (a pass shorter than that is a tangency within round-off: none).
double Settler::Impl::brief_stability_pass(double t0, double t1) {
  if (smooth || finishing || contact.size() < 3) return -1;
  double radius = support.body.norm();  // the centre of mass's distance from the pivot
  for (int k : contact) radius = std::max(radius, (particle.hull.vertices[k] - support.body).norm());
  const double lipschitz = 2 * radius * rate_bound(t1 - t0);
  const double resolution = (t1 - t0) * 0x1p-44;
  auto margin = [&](double tt) { return stability_margin_at(integrator->orientation_at(tt)); };
  using Interval = StabilityInterval;
  std::vector<Interval>& stack = stability_intervals;
  stack.assign(1, {t0, t1, margin(t0), margin(t1)});
  for (int evaluations = 0; !stack.empty() && evaluations < kStabilityEvaluations; ++evaluations) {
    const Interval i = stack.back();
    stack.pop_back();
    if (i.ma + i.mb + lipschitz * (i.b - i.a) <= 0 || i.b - i.a <= resolution) continue;
    const double mid = 0.5 * (i.a + i.b), mm = margin(mid);
    if (mm > 0) return mid;
    stack.push_back({mid, i.b, mm, i.mb});
    stack.push_back({i.a, mid, i.ma, mm});
  }
  return -1;
}

// The adaptive integrator's events: those of the fixed step, and a contact leaving the ε band (Algorithm
// 1's contact set shrinks: a line or surface contact may become a point).
bool Settler::Impl::adaptive_event_at(const Quat& qq, const std::vector<int>& candidates, bool& pierced,
                                      bool& entered) const {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  bool left = false;
  pierced = entered = false;
  for (int k : candidates) {
    const double zk = height_of(r3, k);
    pierced = pierced || pierces(k, zk);
    entered = entered || enters_band(k, zk);
    left = left || rises(k, zk);
  }
  return pierced || entered || left;
}

// The smallest margin of the candidates to their events at orientation qq (length): negative once one has
// passed below the wall or left the band, zero or negative once one has entered it; continuous in time.
double Settler::Impl::event_margin(const Quat& qq, const std::vector<int>& candidates) const {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  double m = INFINITY;
  for (int k : candidates) {
    const double zk = height_of(r3, k);
    m = std::min({m, zk - pierce_level(k), rise_level(k) - zk});
    if (band_events() && !in_contact[k]) m = std::min(m, zk - band);
  }
  return m;
}

}  // namespace repose
