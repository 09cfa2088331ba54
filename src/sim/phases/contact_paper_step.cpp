// The paper's fixed step (Eqs 10-16) for the contact phase, with every event inside it located by the event
// locator: the state at a trial instant is the paper's step to it, integrated afresh (no dense output).
#include <algorithm>
#include <cmath>

#include "../events/events.hpp"
#include "contact.hpp"

namespace repose::sim {

// Whether any vertex of the step's candidates pierced the wall or entered the band at orientation qq.
Contact::EventFlags Contact::paper_event_at(const Quat& qq) const {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  EventFlags e;
  for (int k : event_candidates_) {
    const double zk = height_of(r3, k);
    e.pierced = e.pierced || pierces(k, zk);
    e.any = e.any || e.pierced || enters_band(k, zk);
  }
  return e;
}

void Contact::paper_step() {
  Run& run = run_;
  const SettleParams& params = run.params;
  Rotation next;
  // The last step is shortened so a run never passes its time limit.
  const double h = std::min({run.tol.dt, run.tol.max_time - run.t, run.limit - run.t});
  int iterations =
      rotate_step(run.body, support_, rot_, h, params.quaternion_tolerance, params.max_iterations, next);
  double taken = h;

  // Eq 2's idea, the bounding test that gates the exact distance query: a vertex can only cause an event
  // inside this step if it ends it, or starts it, within the arc length the step can sweep of the levels.
  next_z_.resize(z_.size());
  heights(next.q, next_z_);
  const double swept = 2 * std::acos(std::min(1.0, std::abs(rot_.q.dot(next.q)))) * reach_radius_;
  const double level = run.surface.candidate_level(run.tol.band);
  event_candidates_.clear();
  bool event = false;
  for (std::size_t k = 0; k < next_z_.size(); ++k) {
    if (std::min(z_[k], next_z_[k]) <= level + swept + run.tol.event)
      event_candidates_.push_back(static_cast<int>(k));
    event = event || pierces(k, next_z_[k]) || enters_band(k, next_z_[k]);
  }

  band_entered_ = false;
  if (event) {
    // The earliest instant at which an event holds, to 2^-48 of the step. The state at a trial instant is
    // the paper's step to it; the bracket's ends are the last trial at which the event held (else the step's
    // end) and the last at which it did not (else its start), so those two are kept.
    struct Trial {
      Rotation state;
      int iterations = 0;
      EventFlags event;
    };
    Trial held{next, iterations, paper_event_at(next.q)}, clear{rot_, 0, {}};
    EventSearch search;
    search.max_halvings = kPaperHalvings;
    search.hi_holds_known = true;
    const Located at = locate(
        0.0, h, search,
        [&](double s) {
          Trial trial;
          trial.iterations = rotate_step(run.body, support_, rot_, s, params.quaternion_tolerance,
                                         params.max_iterations, trial.state);
          trial.event = paper_event_at(trial.state.q);
          (trial.event.any ? held : clear) = trial;
          return trial.event.any;
        },
        monotone);
    // A vertex entering the band: take the instant just after (it is then inside). A vertex reaching the
    // wall: take the instant just before, so it touches from above (within the event tolerance) and never
    // pierces.
    const bool hi_pierced = held.event.pierced;
    band_entered_ = !hi_pierced;
    const Trial& taken_trial = hi_pierced ? clear : held;
    taken = hi_pierced ? at.lo : at.hi;
    next = taken_trial.state;
    iterations = taken_trial.iterations;
  }
  if (iterations >= params.max_iterations) ++run.record.unconverged;
  const Vec3 omega_before = next.omega;
  rot_ = next;
  run.q = rot_.q;
  run.com = com_position(support_, run.q);
  run.t += taken;
  ++run.steps;
  // Without an event the step ends at next.q, whose heights are already known.
  if (!event) z_.swap(next_z_);
  update(omega_before, omega_before.cross(run.com - support_.world), /*heights_known=*/!event);
}

}  // namespace repose::sim
