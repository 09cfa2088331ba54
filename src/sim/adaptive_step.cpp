// The adaptive integrator's rotation steps: events located on the dense output, and the vertex sets found by
// walks over the hull's edge graph instead of scans (docs/method.md, "No overlap, ever").
#include <algorithm>
#include <array>
#include <cmath>

#include "settler.hpp"

namespace repose {

namespace {
// An upper bound of the rotation angle 2·acos(|a·b|) between two unit quaternions, without the acos: with
// d = |a·b| in [0, 1], acos(d) / sqrt(2·(1 − d)) rises from 1 at d = 1 to (π/2)/√2 < 1.1108 at d = 0.
double angle_bound(const Quat& a, const Quat& b) {
  const double d = std::min(1.0, std::abs(a.dot(b)));
  return 2 * 1.1108 * std::sqrt(2 * (1 - d));
}
}  // namespace

// The hull vertices at most `level` above the wall at orientation `qq` about the current support, appended
// to `out` (in index order if `sorted`: the order of a contact list matters to its fit's round-off and
// to ties): a walk from the lowest vertex over the hull's edge graph (a linear function's sublevel sets on a
// convex polytope are connected), so the cost is the set and its border. The walk runs 1e-12·L beyond
// `level` and the exact test (the same arithmetic as heights()) picks the members.
void Settler::Impl::vertices_below(const Quat& qq, double level, std::vector<int>& out, bool sorted) {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  const Vec3 down = -r3;
  lowest_vertex = particle.hull.support_vertex_from(down, lowest_vertex);
  const double base = support.world.z() - r3.dot(support.body);  // height = base + r3·p
  walk_out.clear();
  particle.hull.vertices_at_least(down, -(level + event_tol - base), lowest_vertex, walk_out, walk_visited);
  const std::size_t first = out.size();
  for (int k : walk_out)
    if (support.world.z() + r3.dot(particle.hull.vertices[k] - support.body) <= level) out.push_back(k);
  if (sorted) std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
}

// The height of the lowest hull vertex at orientation q (a walk downhill from the last lowest vertex).
double Settler::Impl::lowest_height() {
  const Vec3 r3 = q.toRotationMatrix().row(2).transpose();
  lowest_vertex = particle.hull.support_vertex_from(-r3, lowest_vertex);
  return support.world.z() + r3.dot(particle.hull.vertices[lowest_vertex] - support.body);
}

// One adaptive step, or the part of it before its first event, then the contact update at its end. The
// step and its first event are found once, over the whole step, so advance_to() can stop inside it (the
// state there is only interpolated, with no contact decision) without changing the run.
void Settler::Impl::rotate_adaptive() {
  if (restart) {
    integrator->start(support, rot, t, std::min(dt, 1e-3 * std::sqrt(length / params.gravity)));
    restart = false;
    in_step = false;
  }
  if (!in_step) begin_adaptive_step();
  const double end = std::min({step_end, max_time, limit});
  if (end < step_end) {  // stopped inside the step by advance_to() or the time limit
    rot = integrator->state_at(end);
    q = rot.q;
    com = sim::com_position(support, q);
    t = end;
    return;
  }
  in_step = false;
  band_entered = step_band_entered;
  if (step_event) restart = true;
  rot = integrator->state_at(step_end);
  stalled_steps = step_end - step_start < 1e-9 * dt ? stalled_steps + 1 : 0;
  q = rot.q;
  com = sim::com_position(support, q);
  t = step_end;
  ++steps;
  // The decisions found at this step's end hold at the next step's start if the update changes nothing they
  // depend on (the same contact and touching points, support and phase): then they are not recomputed.
  const bool keep = end_decision_known;
  decision_contact.assign(contact.begin(), contact.end());
  decision_touching.assign(touching.begin(), touching.end());
  const sim::Support support_before = support;
  const int vertex_before = support_vertex;
  const bool finishing_before = finishing;
  update_contacts(rot.omega, rot.omega.cross(com - support.world));
  decision_cached = keep && !restart && contact == decision_contact && touching == decision_touching &&
                    support_vertex == vertex_before && support.line == support_before.line &&
                    support.axis == support_before.axis && support.world == support_before.world &&
                    finishing == finishing_before;
}

// Takes one integrator step from t and finds its first event (step_end: the event, or the step's end).
void Settler::Impl::begin_adaptive_step() {
  integrator->step();
  in_step = true;
  step_start = t;
  const double t0 = t, t1 = integrator->time();
  // The dense output at evenly spaced instants: the swept arc bounds which vertices can cause an event, and
  // the first instant at which one holds brackets it.
  std::array<Quat, kEventSamples + 1> at;
  std::array<double, kEventSamples + 1> times;
  double arc = 0;
  for (int i = 0; i <= kEventSamples; ++i) {
    times[i] = i == kEventSamples ? t1 : t0 + (t1 - t0) * i / kEventSamples;
    at[i] = i == 0 ? rot.q : integrator->orientation_at(times[i]);
    if (i > 0) arc += angle_bound(at[i - 1], at[i]);
  }
  // The chord sum under-estimates the arc by O(h²) of it: a factor 2 covers that with room.
  const double swept = 2 * arc * reach_radius;
  const double level = smooth ? 0.0 : band + touch_tol;
  // Candidates: the vertices within reach of an event at the start or at the end of the step, by two walks;
  // their start heights (the baseline of the pierce test) are refreshed.
  std::vector<int>& candidates = event_candidates;
  candidates.clear();
  walk_union.clear();
  vertices_below(at[0], level + swept + event_tol, walk_union, false);
  vertices_below(at[kEventSamples], level + swept + event_tol, walk_union, false);
  for (int k : walk_union)
    if (!walk_member[k]) {
      walk_member[k] = 1;
      candidates.push_back(k);
    }
  for (int k : candidates) walk_member[k] = 0;
  const Vec3 r3 = at[0].toRotationMatrix().row(2).transpose();
  for (int k : candidates) z[k] = support.world.z() + r3.dot(particle.hull.vertices[k] - support.body);

  bool pierced = false, entered = false;
  int first = -1;
  for (int i = 1; i <= kEventSamples && first < 0; ++i)
    if (adaptive_event_at(at[i], candidates, pierced, entered)) first = i;
  step_end = t1;
  step_event = first > 0;
  step_band_entered = false;
  if (!step_event) {
    locate_decision_change(t0, t1);
    return;
  }
  // Bisect the bracketing interval on the dense output (to 2^-48 of it), over the candidates within reach
  // of an event inside that interval alone.
  const double sub_swept = 2 * angle_bound(at[first - 1], at[first]) * reach_radius;
  const Vec3 r3_lo = at[first - 1].toRotationMatrix().row(2).transpose();
  const Vec3 r3_hi = at[first].toRotationMatrix().row(2).transpose();
  std::vector<int>& near = walk_out;
  near.clear();
  for (int k : candidates) {
    const Vec3 d = particle.hull.vertices[k] - support.body;
    const double z_lo = support.world.z() + r3_lo.dot(d), z_hi = support.world.z() + r3_hi.dot(d);
    if (std::min(z_lo, z_hi) <= level + sub_swept + event_tol) near.push_back(k);
  }
  double lo = times[first - 1], hi = times[first];
  bool hi_pierced = pierced, hi_entered = entered;
  for (int i = 0; i < kBisections; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (adaptive_event_at(integrator->orientation_at(mid), near, pierced, entered)) {
      hi = mid;
      hi_pierced = pierced;
      hi_entered = entered;
    } else {
      lo = mid;
    }
  }
  // As in the fixed step: just after a band event, just before a vertex reaches the wall. Only an entry
  // counts as "a point entered the band" for the choice of support (a point that leaves it does not).
  step_band_entered = !hi_pierced && hi_entered;
  step_end = hi_pierced ? lo : hi;
  locate_decision_change(t0, lo);
}

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
  d.stable = !smooth && !finishing && paper_stability_test(contact_points, g);
  d.line_holds = support.line && line_is_supported(support_vertex, support.axis);
  q = q_now;
  com = com_now;
  return d;
}

// If the contact decisions at `t_end` differ from those at the step's start `t0`, the step is cut just after
// the first change (bisection on the dense output): the contact update then decides there, as the paper's
// fixed step does at dt → 0.
void Settler::Impl::locate_decision_change(double t0, double t_end) {
  const Decision start = decision_cached ? cached_decision : decision_at(rot.q);
  decision_cached = false;
  const Decision end = decision_at(integrator->orientation_at(t_end));
  end_decision_known = !step_event && end == start;
  if (end == start) {
    cached_decision = end;
    return;
  }
  double lo = t0, hi = t_end;
  for (int i = 0; i < kBisections; ++i) {
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

// The adaptive integrator's events: those of the fixed step, and a contact leaving the ε band (Algorithm
// 1's contact set shrinks: a line or surface contact may become a point).
bool Settler::Impl::adaptive_event_at(const Quat& qq, const std::vector<int>& candidates, bool& pierced,
                                      bool& entered) const {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  bool left = false;
  pierced = entered = false;
  for (int k : candidates) {
    const double zk = support.world.z() + r3.dot(particle.hull.vertices[k] - support.body);
    pierced = pierced || pierces(k, zk);
    entered = entered || enters_band(k, zk);
    left = left || leaves_band(k, zk);
  }
  return pierced || entered || left;
}
}  // namespace repose
