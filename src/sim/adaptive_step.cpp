// The adaptive integrator's rotation steps: events located on the dense output, and the vertex sets found by
// walks over the hull's edge graph instead of scans (docs/method.md, "No overlap, ever").
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <bit>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>

#include "settler.hpp"

namespace repose {

// The hull vertices at most `level` above the wall at orientation `qq` about the current support, in `out`
// (in index order if `sorted`: the order of a contact list matters to its fit's round-off and to ties): a
// walk from the lowest vertex over the hull's edge graph (a linear function's sublevel sets on a convex
// polytope are connected), so the cost is the set and its border. The walk runs 1e-12·L beyond `level` and
// the exact test (the same arithmetic as heights()) picks the members.
void Settler::Impl::vertices_below(const Quat& qq, double level, std::vector<int>& out, bool sorted) {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  const Vec3 down = -r3;
  lowest_vertex = particle.hull.support_vertex_from(down, lowest_vertex);
  const double base = support.world.z() - r3.dot(support.body);  // height = base + r3·p
  walk_out.clear();
  particle.hull.vertices_at_least(down, -(level + event_tol - base), lowest_vertex, walk_out, walk_visited);
  out.clear();
  for (int k : walk_out)
    if (height_of(r3, k) <= level) out.push_back(k);
  if (sorted) sort_vertex_ids(out);
}

// The same set, sorted, when it is known to lie within `among` (a superset): the members are picked from it
// by the same test, with no walk. The walk to the lowest vertex is still made (later walks start there).
void Settler::Impl::vertices_below_among(const Quat& qq, double level, const std::vector<int>& among,
                                         std::vector<int>& out) {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  lowest_vertex = particle.hull.support_vertex_from(-r3, lowest_vertex);
  out.clear();
  for (int k : among)
    if (height_of(r3, k) <= level) out.push_back(k);
  sort_vertex_ids(out);
}

// Whether the band picked from the step's candidates is the one a walk finds (the sanitizer build checks
// every such pick); the walk's scratch is left as it was.
bool Settler::Impl::band_matches_walk(double level, const std::vector<int>& picked) {
  const std::vector<int> reachable = walk_out;
  std::vector<int> walked;
  vertices_below(q, level, walked, true);
  walk_out = reachable;
  return walked == picked;
}

// Distinct hull vertex indices into increasing order. A band of hundreds is written into a bitset of the
// hull's vertices and read back in order: linear in the set plus its span/64 words, where a comparison sort
// costs ~n·log n (a tenth of a 10,000-vertex grain's settle went to std::sort).
void Settler::Impl::sort_vertex_ids(std::vector<int>& ids) {
  if (ids.size() < 64) {
    std::sort(ids.begin(), ids.end());
    return;
  }
  int lo = ids.front(), hi = ids.front();
  for (int k : ids) {
    id_bits[static_cast<std::size_t>(k) >> 6] |= std::uint64_t{1} << (k & 63);
    lo = std::min(lo, k);
    hi = std::max(hi, k);
  }
  ids.clear();
  for (std::size_t w = static_cast<std::size_t>(lo) >> 6; w <= static_cast<std::size_t>(hi) >> 6; ++w) {
    for (std::uint64_t bits = id_bits[w]; bits != 0; bits &= bits - 1)
      ids.push_back(static_cast<int>(64 * w) + std::countr_zero(bits));
    id_bits[w] = 0;
  }
}

// The height of the lowest hull vertex at orientation q (a walk downhill from the last lowest vertex).
double Settler::Impl::lowest_height() {
  const Vec3 r3 = q.toRotationMatrix().row(2).transpose();
  lowest_vertex = particle.hull.support_vertex_from(-r3, lowest_vertex);
  return height_of(r3, lowest_vertex);
}

// A bound of the angle the particle can turn in time h from now about the current support, from energy:
// kinetic energy K grows at most by the potential energy the centre of mass loses, m·g·r_c per radian turned
// (r_c: its distance from the pivot; damping only removes energy, impacts happen only at events), and
// |ω| ≤ sqrt(2K / I_min) (I_min: the smallest moment of inertia about the support, or about a line's axis).
// So dθ/dt ≤ sqrt(a + b·θ) with a = 2·K₀/I_min, b = 2·m·g·r_c/I_min, whence θ(h) ≤ sqrt(a)·h + b·h²/4.
// K₀ carries a margin of 10·tolerance·m·g·L for the integrator's energy error (measured ≤ 5.2·tolerance).
// The smallest moment of inertia about the current support (for a line, about its axis).
double Settler::Impl::smallest_moment() const {
  const Mat3 inertia = sim::support_inertia(body, support).inertia;  // body frame
  if (support.line) {
    const Vec3 e = q.conjugate() * support.axis;
    return e.dot(inertia * e);
  }
  Eigen::SelfAdjointEigenSolver<Mat3> eigen;
  eigen.computeDirect(inertia, Eigen::EigenvaluesOnly);
  return eigen.eigenvalues()(0);
}

std::array<double, 2> Settler::Impl::rate_coefficients() const {
  const double k0 = kinetic_energy() + 10 * params.tolerance * body.mass * params.gravity * length;
  return {2 * k0 / min_moment, 2 * body.mass * params.gravity * support.body.norm() / min_moment};
}

double Settler::Impl::arc_bound(double h) const {
  const auto [a, b] = rate_coefficients();
  return std::sqrt(a) * h + 0.25 * b * h * h;
}

// A bound of |ω| over the next time h (the same energy argument): sqrt(a + b·θ(h)).
double Settler::Impl::rate_bound(double h) const {
  const auto [a, b] = rate_coefficients();
  return std::sqrt(a + b * arc_bound(h));
}

// One adaptive step, or the part of it before its first event, then the contact update at its end. The
// step and its first event are found once, over the whole step, so advance_to() can stop inside it (the
// state there is only interpolated, with no contact decision) without changing the run.
void Settler::Impl::rotate_adaptive() {
  if (restart) {
    // After an event the motion goes on at the pace the error control had reached, so it restarts from the
    // proposed step; from rest (the first contact, a tip off a balance) it tries kFirstStep. Either, if too
    // long, is rejected and shortened by the error control (measured: 1e-3·τ instead costs the cube 9 % more
    // steps and the same result within the tolerance).
    const double first = restart_step > 0 ? restart_step : kFirstStep * std::sqrt(length / params.gravity);
    integrator->start(support, rot, t, std::min(dt, first));
    min_moment = smallest_moment();
    restart = false;
    in_step = false;
    resume = false;
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
  // After an event the rest of the integrator's step is still the motion, unless the update below changes
  // the support (which restarts the integrator): the next step resumes there.
  resume = step_event;
  restart_step = integrator->proposed_step();
  rot = integrator->state_at(step_end);
  q = rot.q;
  com = sim::com_position(support, q);
  t = step_end;
  ++steps;
  // The decisions found at this step's end hold at the next step's start if the update changes nothing they
  // depend on (the same contact and touching points, support and phase): then they are not recomputed.
  const bool keep = end_decision_known;
  // A step without an event whose decisions did not change leaves the update nothing to decide while a
  // single point touches: the contact and touching sets change only at events (after the stability test the
  // contact set enters the decisions instead), the support the rules call for is the one they called for
  // (choose_support), and neither a rest (the touching points do not hold the centre of mass) nor an edge
  // balance (two touching points) can begin.
  if (keep && !smooth && touching.size() <= 1 && !cached_decision.hold) {
    quiet_update();
    decision_cached = true;
    return;
  }
  decision_contact.assign(contact.begin(), contact.end());
  decision_touching.assign(touching.begin(), touching.end());
  const sim::Support support_before = support;
  const int vertex_before = support_vertex;
  const bool finishing_before = finishing;
  // This step's event candidates reach the band's level (not a smooth particle's, collected to the wall
  // only), for the support they were collected about.
  band_in_candidates = !smooth;
  update_contacts(rot.omega, rot.omega.cross(com - support.world));
  // A support chosen from several touching points by the impact law is chosen again at once with the motion
  // it leaves: the choice the paper's fixed step makes one step later, here at dt → 0. (An impact can switch
  // to a line whose motion then lets one of its points lift.)
  for (int again = 0;
       again < kRedecisions && !smooth && restart && status == Status::running && touching.size() >= 2;
       ++again) {
    restart = false;
    update_contacts(rot.omega, rot.omega.cross(com - support.world));
    if (!restart) {
      restart = true;
      break;
    }
  }
  decision_cached = keep && !restart && contact == decision_contact && touching == decision_touching &&
                    support_vertex == vertex_before && support.line == support_before.line &&
                    support.axis == support_before.axis && support.world == support_before.world &&
                    finishing == finishing_before;
}

// Takes one integrator step from t, or resumes the last one after an event that changed no support, and
// finds its first event (step_end: the event, or the step's end).
void Settler::Impl::begin_adaptive_step() {
  if (!resume || integrator->time() <= t) integrator->step();
  resume = false;
  in_step = true;
  step_start = t;
  const double t0 = t, t1 = integrator->time();
  // The rotation angle the step can sweep, a bound from energy (arc_bound), bounds which vertices can cause
  // an event: a vertex at distance r from the pivot moves by at most arc·r (the support itself never does).
  const double arc = arc_bound(t1 - t0);
  const double level = smooth ? 0.0 : band + touch_tol;
  // Candidates: the vertices within reach of an event level from where they start, by a walk; their start
  // heights (the baseline of the pierce test) are refreshed. Of those, the ones that can reach one of their
  // own event levels are checked; most steps keep none and look no further.
  std::vector<int>& candidates = event_candidates;
  vertices_below(rot.q, level + arc * reach_radius + event_tol, candidates, false);
  const Vec3 r3 = rot.q.toRotationMatrix().row(2).transpose();
  std::vector<int>& reachable = walk_out;
  reachable.clear();
  for (int k : candidates) {
    const Vec3 d = particle.hull.vertices[k] - support.body;
    z[k] = support.world.z() + r3.dot(d);
    const double reach = arc * d.norm() + event_tol;
    if (z[k] - reach < event_level(k) || z[k] + reach > rise_level(k)) reachable.push_back(k);
  }
  // The dense output at evenly spaced instants: the first at which an event holds brackets it, so a vertex
  // that dips below the wall and back up inside one step is still caught.
  std::array<double, kEventSamples + 1> times;
  for (int i = 0; i <= kEventSamples; ++i)
    times[i] = i == kEventSamples ? t1 : t0 + (t1 - t0) * i / kEventSamples;
  bool pierced = false, entered = false;
  int first = -1;
  if (!reachable.empty())
    for (int i = 1; i <= kEventSamples && first < 0; ++i)
      if (adaptive_event_at(integrator->orientation_at(times[i]), reachable, pierced, entered)) first = i;
  step_end = t1;
  step_event = first > 0;
  step_band_entered = false;
  if (!step_event) {
    locate_decision_change(t0, t1, std::span(times).subspan(1, kEventSamples - 1));
    return;
  }
  const auto [lo, hi] = locate_event(times[first - 1], times[first], pierced, entered);
  // As in the fixed step: just after a band event, just before a vertex reaches the wall. Only an entry
  // counts as "a point entered the band" for the choice of support (a point that leaves it does not), and,
  // as in the fixed step, not once the stability test has passed.
  step_band_entered = !pierced && entered && !finishing;
  step_end = pierced ? lo : hi;
  locate_decision_change(t0, lo, std::span(times).subspan(1, first - 1));
}

// The first event in [lo, hi] (none at lo, one at hi) bracketed to 2^-44 of the step, over the vertices that
// can reach an event level in the step: TOMS 748 (Alefeld, Potra and Shi; Boost.Math) on the smallest event
// margin, which is continuous in time, with bisection of the event test as the fallback for a margin that
// is exactly zero. `pierced` and `entered` are set to the event at the returned upper end.
std::pair<double, double> Settler::Impl::locate_event(double lo, double hi, bool& pierced, bool& entered) {
  const std::vector<int>& near = walk_out;        // the step's reachable vertices
  const double resolution = (hi - lo) * 0x1p-41;  // the bracket is 1/8 of a step: 2^-44 of the step
  auto margin = [&](double tt) { return event_margin(integrator->orientation_at(tt), near); };
  const double m_lo = margin(lo), m_hi = margin(hi);
  bool hi_pierced = pierced, hi_entered = entered;
  if (m_lo > 0 && m_hi < 0) {
    boost::uintmax_t iterations = kBisections;
    const auto r = boost::math::tools::toms748_solve(
        margin, lo, hi, m_lo, m_hi, [&](double a, double b) { return b - a <= resolution; }, iterations);
    // The bracket is then snapped to the grid of cells `resolution` wide from lo, the cells bisection would
    // end in: the result depends on the event test alone, not on the round-off of the margins (which differ
    // with the particle's scale), so a run stays the same at any scale.
    const double cell = std::floor((r.first - lo) / resolution);
    double a = lo + cell * resolution, b = std::min(hi, a + resolution);
    bool p = false, e = false;
    for (int shift = 0; shift < 4 && a > lo && adaptive_event_at(integrator->orientation_at(a), near, p, e);
         ++shift) {
      b = a;
      a = std::max(lo, a - resolution);
    }
    for (int shift = 0; shift < 4 && b < hi && !adaptive_event_at(integrator->orientation_at(b), near, p, e);
         ++shift) {
      a = b;
      b = std::min(hi, b + resolution);
    }
    if (!adaptive_event_at(integrator->orientation_at(a), near, p, e) &&
        adaptive_event_at(integrator->orientation_at(b), near, pierced, entered))
      return {a, b};
  }
  for (int i = 0; i < kBisections && hi - lo > resolution; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (adaptive_event_at(integrator->orientation_at(mid), near, pierced, entered)) {
      hi = mid;
      hi_pierced = pierced;
      hi_entered = entered;
    } else {
      lo = mid;
    }
  }
  pierced = hi_pierced;
  entered = hi_entered;
  return {lo, hi};
}

}  // namespace repose
