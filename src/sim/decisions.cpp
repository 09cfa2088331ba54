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
Settler::Impl::Decision Settler::Impl::decision_at(const Quat& qq) {
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
  d.type = smooth ? ContactType::point : sim::classify_contact(footprints, rss_threshold);
  d.hold = (!smooth || touching.size() >= 3) && touching_points_hold(g);
  d.stable = !smooth && !finishing && stability_margin(contact_points, g) > 0;
  d.line_holds = support.line && line_is_supported(support_vertex, support.axis);
  if (own_set) contact.swap(decision_set);
  q = q_now;
  com = com_now;
  return d;
}

// If the contact decisions at `t_end` differ from those at the step's start `t0`, the step is cut just after
// the first change (bisection on the dense output): the contact update then decides there, as the paper's
// fixed step does at dt → 0.
void Settler::Impl::locate_decision_change(double t0, double t_end, std::span<const double> inner) {
  const Decision start = decision_cached ? cached_decision : decision_at(rot.q);
  decision_cached = false;
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
    const Decision end = decision_at(integrator->orientation_at(t_end));
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
