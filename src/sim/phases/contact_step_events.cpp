// The adaptive step's first event: a vertex reaching the wall, entering or leaving the ε band, located on the
// dense output over the vertices that can decide it, a set that shrinks with the search's bracket.
#include <cassert>
#include <cmath>
#include <tuple>
#include <utility>

#include "../events/events.hpp"
#include "contact.hpp"

namespace repose::sim {

// The first event in [lo, hi] (none at lo, one at hi), over the vertices that can reach an event level in
// the step, on the smallest event margin (continuous in time). As in the fixed step: the step ends just
// after a band event, just before a vertex reaches the wall. Only an entry counts as "a point entered the
// band" for the choice of support (a point that leaves it does not), and not once the stability test has
// passed. Returns the bracket's lower end, the last instant known to be before the event.
double Contact::locate_step_event(AdaptiveStepper& step, double lo, double hi, const EventFlags& at_hi) {
  EventSearch search;
  search.resolution = (hi - lo) * (kEventResolution * tol::kEventSamples);  // the bracket is 1/8 of the step
  search.max_halvings = kMaxHalvings;
  search.hi_holds_known = true;
  // Only the vertices that can decide the search take part in it: |ω| ≤ rate_bound over the step, so in
  // an interval of length τ a vertex at distance d from the pivot moves by at most rate·τ·d.
  const double rate = tol::kBracketTurnMargin * rate_bound(step.integrator.time() - run_.t);
  select_event_vertices(step_vertices_, step.integrator.orientation_at(lo), rate * (hi - lo),
                        bracket_vertices_);
  // The root finder narrows its bracket [a, b] (the margin positive at a, negative at b) and evaluates only
  // inside it, so the vertices that can decide the margin there are selected again, from those of the wider
  // interval, each time it has shrunk 8-fold: a co-planar ring crossing the band together is a kink of the
  // smallest margin at every vertex, and the search's last halvings need one or two of them. The narrow set
  // is exact on [narrow_lo, narrow_hi] (as the bracket's on [lo, hi]): an instant outside it is evaluated on
  // the bracket's set, so the margins and the event tests are the same to the bit whatever the root finder
  // does.
  const StepVertices* narrow = &bracket_vertices_;
  double narrow_lo = lo, narrow_hi = hi, a = lo, b = hi;
  const auto vertices_at = [&](double s) -> const StepVertices& {
    return s >= narrow_lo && s <= narrow_hi ? *narrow : bracket_vertices_;
  };
  const auto narrow_to_bracket = [&] {
    if (narrow->offset.size() <= 2 || 8 * (b - a) > narrow_hi - narrow_lo) return;
    StepVertices& next = narrow == &narrow_vertices_[0] ? narrow_vertices_[1] : narrow_vertices_[0];
    select_event_vertices(*narrow, step.integrator.orientation_at(a), rate * (b - a), next);
    narrow = &next;
    narrow_lo = a;
    narrow_hi = b;
  };
  // The events at the bracket's upper end: at hi, or at the last instant tested at which one held.
  double held_at = hi;
  EventFlags held = at_hi;
  const Located at = locate(
      lo, hi, search,
      [&](double s) {
        const EventFlags e = adaptive_event_at(step.integrator.orientation_at(s), vertices_at(s));
        assert(e.any == adaptive_event_at(step.integrator.orientation_at(s), step_vertices_).any);
        if (e.any) std::tie(held_at, held) = std::pair{s, e};
        return e.any;
      },
      monotone,
      [&](double s) {
        const double m = event_margin(step.integrator.orientation_at(s), vertices_at(s));
        assert(m == event_margin(step.integrator.orientation_at(s), step_vertices_));
        if (s > a && s < b) {
          if (m > 0) a = s;
          if (m < 0) b = s;
          narrow_to_bracket();
        }
        return m;
      });
  const EventFlags flags =
      held_at == at.hi ? held : adaptive_event_at(step.integrator.orientation_at(at.hi), vertices_at(at.hi));
  if (!flags.pierced && flags.entered && !finishing_) step.ends = AdaptiveStepper::End::band_entry;
  step.crossing = !flags.pierced && band_events();
  step.end = flags.pierced ? at.lo : at.hi;
  return at.lo;
}

// The selection (step_vertices.hpp) from orientation q_lo about the current support.
void Contact::select_event_vertices(const StepVertices& from, const Quat& q_lo, double turn,
                                    StepVertices& out) {
  sim::select_event_vertices(from, q_lo.toRotationMatrix().row(2).transpose(), support_.world.z(), turn,
                             run_.tol.event, margin_scratch_, out);
}

void select_event_vertices(const StepVertices& from, const Vec3& r3, double base, double turn, double slack,
                           std::vector<double>& scratch, StepVertices& out) {
  scratch.resize(from.offset.size());
  double bound = INFINITY;  // of the smallest margin anywhere in the interval
  for (std::size_t i = 0; i < from.offset.size(); ++i) {
    const double zk = base + r3.dot(from.offset[i]);
    double m = std::min(zk - from.pierce[i], from.rise[i] - zk);
    if (from.enter[i] > -INFINITY) m = std::min(m, zk - from.enter[i]);
    const double reach = turn * from.distance[i];
    scratch[i] = m - reach;
    bound = std::min(bound, m + reach);
  }
  const double keep = std::max(bound, 0.0) + slack;
  out.clear();
  for (std::size_t i = 0; i < from.offset.size(); ++i) {
    if (!(scratch[i] <= keep)) continue;
    out.offset.push_back(from.offset[i]);
    out.distance.push_back(from.distance[i]);
    out.pierce.push_back(from.pierce[i]);
    out.rise.push_back(from.rise[i]);
    out.enter.push_back(from.enter[i]);
  }
}

// The adaptive integrator's events: those of the fixed step, and a contact leaving the ε band (Algorithm
// 1's contact set shrinks: a line or surface contact may become a point), over the vertices `v` (the step's
// reachable ones, or those of a bracket).
Contact::EventFlags Contact::adaptive_event_at(const Quat& qq, const StepVertices& v) const {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  const double base = support_.world.z();  // height_of(r3, k), from the packed offsets
  bool left = false;
  EventFlags e;
  for (std::size_t i = 0; i < v.offset.size(); ++i) {
    const double zk = base + r3.dot(v.offset[i]);
    e.pierced = e.pierced || zk < v.pierce[i];
    e.entered = e.entered || zk <= v.enter[i];
    left = left || zk > v.rise[i];
  }
  e.any = e.pierced || e.entered || left;
  return e;
}

// The smallest margin of the reachable vertices to their events at orientation qq (length): negative once
// one has passed below the wall or left the band, zero or negative once one has entered it.
double Contact::event_margin(const Quat& qq, const StepVertices& v) const {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  const double base = support_.world.z();
  double m = INFINITY;
  for (std::size_t i = 0; i < v.offset.size(); ++i) {
    const double zk = base + r3.dot(v.offset[i]);
    m = std::min({m, zk - v.pierce[i], v.rise[i] - zk});
    if (v.enter[i] > -INFINITY) m = std::min(m, zk - v.enter[i]);
  }
  return m;
}

}  // namespace repose::sim
