// The adaptive integrator's steps in the contact phase: events located on the dense output, and the vertex
// sets found by walks over the hull's edge graph instead of scans (docs/method.md, "No overlap, ever").
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <span>
#include <tuple>
#include <utility>

#include "../events/events.hpp"
#include "../events/wall_crossing.hpp"
#include "contact.hpp"

namespace repose::sim {

// A bound of the angle the particle can turn in time h from now about the current support, from energy:
// kinetic energy K grows at most by the potential energy the centre of mass loses, m·g·r_c per radian turned
// (r_c: its distance from the pivot; damping only removes energy, impacts happen only at events), and
// |ω| ≤ sqrt(2K / I_min) (I_min: the smallest moment of inertia about the support, or about a line's axis).
// So dθ/dt ≤ sqrt(a + b·θ) with a = 2·K₀/I_min, b = 2·m·g·r_c/I_min, whence θ(h) ≤ sqrt(a)·h + b·h²/4.
// K₀ carries a margin for the integrator's energy error (Tolerances::energy_margin).
double Contact::smallest_moment() const {
  const Mat3 inertia = support_inertia(run_.body, support_).inertia;  // body frame
  if (support_.line) {
    const Vec3 e = run_.q.conjugate() * support_.axis;
    return e.dot(inertia * e);
  }
  Eigen::SelfAdjointEigenSolver<Mat3> eigen;
  eigen.computeDirect(inertia, Eigen::EigenvaluesOnly);
  return eigen.eigenvalues()(0);
}

std::array<double, 2> Contact::rate_coefficients() const {
  const double k0 = kinetic_energy() + run_.tol.energy_margin;
  const Body& body = run_.body;
  const double min_moment = std::get<AdaptiveStepper>(stepper_).min_moment;
  return {2 * k0 / min_moment, 2 * body.mass * run_.params.gravity * support_.body.norm() / min_moment};
}

double Contact::arc_bound(double h) const {
  const auto [a, b] = rate_coefficients();
  return std::sqrt(a) * h + 0.25 * b * h * h;
}

// A bound of |ω| over the next time h (the same energy argument): sqrt(a + b·θ(h)).
double Contact::rate_bound(double h) const {
  const auto [a, b] = rate_coefficients();
  return std::sqrt(a + b * arc_bound(h));
}

// One adaptive step, or the part of it before its first event, then the contact update at its end. The
// step and its first event are found once, over the whole step, so advance_to() can stop inside it (the
// state there is only interpolated, with no contact decision) without changing the run.
void Contact::adaptive_step(AdaptiveStepper& step) {
  using Next = AdaptiveStepper::Next;
  Run& run = run_;
  if (step.next == Next::restart) {
    // After an event the motion goes on at the pace the error control had reached, so it restarts from the
    // proposed step; from rest (the first contact, a tip off a balance) it tries the first step. Either, if
    // too long, is rejected and shortened by the error control.
    const double first = step.restart_step > 0 ? step.restart_step : run.tol.first_step;
    step.integrator.start(support_, rot_, run.t, std::min(run.tol.dt, first));
    step.min_moment = smallest_moment();
    step.next = Next::new_step;
  }
  // A crossing of the ε band that changes no decision is no step (issue 49): the contact set changes and the
  // search goes on in the same integrator step, up to kQuietCrossings in one call.
  for (int crossings = 0;; ++crossings) {
    if (step.next != Next::inside) begin_adaptive_step(step);
    const double end = std::min({step.end, run.tol.max_time, run.limit});
    if (end < step.end) {  // stopped inside the step by advance_to() or the time limit
      rot_ = step.integrator.state_at(end);
      run.q = rot_.q;
      run.com = com_position(support_, run.q);
      run.t = end;
      return;
    }
    band_entered_ = step.ends == AdaptiveStepper::End::band_entry;
    // After an event the rest of the integrator's step is still the motion, unless the update below changes
    // the support (which restarts the integrator): the next step resumes there.
    step.next = step.ends == AdaptiveStepper::End::step ? Next::new_step : Next::resume;
    step.restart_step = step.integrator.proposed_step();
    rot_ = step.integrator.state_at(step.end);
    run.q = rot_.q;
    run.com = com_position(support_, run.q);
    run.t = step.end;
    if (!step.crossing || crossings + 1 >= tol::kQuietCrossings || !quiet_crossing(step)) break;
  }
  ++run.steps;
  // The decisions found at this step's end hold at the next step's start if the update changes nothing they
  // depend on (the same contact and touching points, support and phase): then they are not recomputed.
  const std::optional<Decision> known = std::exchange(step.decision, std::nullopt);
  // A step without an event whose decisions did not change leaves the update nothing to decide while a
  // single point touches: the contact and touching sets change only at events (after the stability test the
  // contact set enters the decisions instead), the support the rules call for is the one they called for,
  // and neither a rest nor an edge balance (two touching points) can begin.
  if (known && run.surface.has_contact_types() && touching_.size() <= 1 && !known->hold) {
    quiet_update();
    step.decision = known;
    return;
  }
  decision_contact_.assign(contact_.begin(), contact_.end());
  decision_touching_.assign(touching_.begin(), touching_.end());
  const Support support_before = support_;
  const int vertex_before = support_vertex_;
  const bool finishing_before = finishing_;
  // This step's event candidates reach the band's level (not a smooth particle's, collected to the wall
  // only), for the support they were collected about.
  const auto band_source = run.surface.has_band_events() ? BandSource::step_candidates : BandSource::walk;
  Outcome out = update(rot_.omega, rot_.omega.cross(run.com - support_.world), false, band_source);
  if (out == Outcome::rest) return;
  // A support chosen from several touching points by the impact law is chosen again at once with the motion
  // it leaves: the choice the paper's fixed step makes one step later, here at dt → 0. (An impact can switch
  // to a line whose motion then lets one of its points lift.)
  for (int again = 0; again < tol::kRedecisions && run.surface.has_contact_types() &&
                      out == Outcome::new_support && touching_.size() >= 2;
       ++again) {
    out = update(rot_.omega, rot_.omega.cross(run.com - support_.world));
    if (out == Outcome::rest) return;
  }
  if (known && step.next != Next::restart && contact_ == decision_contact_ &&
      touching_ == decision_touching_ && support_vertex_ == vertex_before &&
      support_.line == support_before.line && support_.axis == support_before.axis &&
      support_.world == support_before.world && finishing_ == finishing_before)
    step.decision = known;
}

// Takes one integrator step from t, or resumes the last one after an event that changed no support, and
// finds its first event (step.end: the event, or the step's end).
void Contact::begin_adaptive_step(AdaptiveStepper& step) {
  Run& run = run_;
  if (step.next != AdaptiveStepper::Next::resume || step.integrator.time() <= run.t) step.integrator.step();
  step.next = AdaptiveStepper::Next::inside;
  const double t0 = run.t, t1 = step.integrator.time();
  // The rotation angle the step can sweep, a bound from energy (arc_bound), bounds which vertices can cause
  // an event: a vertex at distance r from the pivot moves by at most arc·r (the support itself never does).
  const double arc = arc_bound(t1 - t0);
  const double level = run.surface.candidate_level(run.tol.band + run.tol.touch);
  // Candidates: the vertices within reach of an event level from where they start, by a walk; their start
  // heights (the baseline of the pierce test) are refreshed. Of those, the ones that can reach one of their
  // own event levels are checked; most steps keep none and look no further.
  const double reach_level = level + arc * reach_radius_ + run.tol.event;
  if (std::exchange(step.keep_candidates, false))
    assert(candidates_cover(rot_.q, reach_level));
  else
    vertices_below(rot_.q, reach_level, event_candidates_, true);  // sorted once for the picks from them
  const Vec3 r3 = rot_.q.toRotationMatrix().row(2).transpose();
  StepVertices& packed = step_vertices_;
  packed.clear();
  for (int k : event_candidates_) {
    const Vec3 d = run.particle.hull.vertices[static_cast<std::size_t>(k)] - support_.body;
    z_[k] = support_.world.z() + r3.dot(d);
    const double distance = d.norm();
    const double reach = arc * distance + run.tol.event;
    if (z_[k] - reach < event_level(k) || z_[k] + reach > rise_level(k)) {
      const auto kk = static_cast<std::size_t>(k);
      packed.offset.push_back(d);
      packed.distance.push_back(distance);
      packed.pierce.push_back(pierce_level(kk));
      packed.rise.push_back(rise_level(kk));
      packed.enter.push_back(band_events() && !in_contact_[kk] ? run.tol.band : -INFINITY);
    }
  }
  // The dense output at evenly spaced instants: the first at which an event holds brackets it.
  const auto times = sample_times(t0, t1);  // the wall-crossing search's grid (events/wall_crossing.hpp)
  int first = -1;
  EventFlags at_first;
  if (!packed.offset.empty())
    for (int i = 1; i <= tol::kEventSamples && first < 0; ++i)
      if ((at_first = adaptive_event_at(step.integrator.orientation_at(times[i]), packed)).any) first = i;
  step.end = t1;
  step.ends = first > 0 ? AdaptiveStepper::End::event : AdaptiveStepper::End::step;
  step.crossing = false;
  if (first <= 0) {
    locate_decision_change(step, t0, t1, std::span(times).subspan(1, tol::kEventSamples - 1));
    return;
  }
  const double before_event = locate_step_event(step, times[first - 1], times[first], at_first);
  locate_decision_change(step, t0, before_event, std::span(times).subspan(1, first - 1));
}

}  // namespace repose::sim
