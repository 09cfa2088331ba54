// The paper's fixed step (Eqs 10-16) for a rotation phase, with every event inside it located by bisection.
#include <algorithm>
#include <cmath>

#include "settler.hpp"

namespace repose {

// Heights of the listed vertices after a rotation to `qq`; true if any of them pierced or entered the band.
bool Settler::Impl::event_at(const Quat& qq, const std::vector<int>& candidates, bool& pierced) const {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  bool event = false;
  pierced = false;
  for (int k : candidates) {
    const double zk = height_of(r3, k);
    pierced = pierced || pierces(k, zk);
    event = event || pierced || enters_band(k, zk);
  }
  return event;
}

void Settler::Impl::rotate() {
  if (adaptive) {
    rotate_adaptive();
    return;
  }
  sim::Rotation next;
  // The last step is shortened so a run never passes its time limit.
  const double h = std::min({dt, max_time - t, limit - t});
  int iterations =
      sim::rotate_step(body, support, rot, h, params.quaternion_tolerance, params.max_iterations, next);
  double taken = h;

  // Eq 2's idea, the bounding test that gates the exact distance query: a vertex can only cause an event
  // inside this step if it ends it, or starts it, within the arc length the step can sweep of the levels.
  std::vector<double>& zz = next_z;
  zz.resize(z.size());
  heights(next.q, zz);
  const double swept = 2 * std::acos(std::min(1.0, std::abs(rot.q.dot(next.q)))) * reach_radius;
  const double level = smooth ? 0.0 : band;
  std::vector<int>& candidates = event_candidates;
  candidates.clear();
  bool event = false;
  for (std::size_t k = 0; k < zz.size(); ++k) {
    if (std::min(z[k], zz[k]) <= level + swept + event_tol) candidates.push_back(static_cast<int>(k));
    event = event || pierces(k, zz[k]) || enters_band(k, zz[k]);
  }

  band_entered = false;
  if (event) {
    // Bisect for the earliest instant at which an event holds (to 2^-48 of the step).
    double lo = 0, hi = h;
    sim::Rotation lo_state = rot, hi_state = next;
    int lo_iterations = 0;
    bool hi_pierced = true, pierced = false;
    event_at(next.q, candidates, hi_pierced);
    for (int i = 0; i < kBisections; ++i) {
      const double mid = 0.5 * (lo + hi);
      sim::Rotation trial;
      const int it = sim::rotate_step(body, support, rot, mid, params.quaternion_tolerance,
                                      params.max_iterations, trial);
      if (event_at(trial.q, candidates, pierced)) {
        hi = mid;
        hi_state = trial;
        hi_pierced = pierced;
        iterations = it;
      } else {
        lo = mid;
        lo_state = trial;
        lo_iterations = it;
      }
    }
    // A vertex entering the band: take the instant just after (it is then inside). A vertex reaching the
    // wall: take the instant just before, so it touches from above (within event_tol) and never pierces.
    band_entered = !hi_pierced;
    next = hi_pierced ? lo_state : hi_state;
    taken = hi_pierced ? lo : hi;
    if (hi_pierced) iterations = lo_iterations;
  }
  if (iterations >= params.max_iterations) ++unconverged;
  const Vec3 omega_before = next.omega;
  rot = next;
  q = rot.q;
  com = sim::com_position(support, q);
  t += taken;
  ++steps;
  // Without an event the step ends at next.q, whose heights are already known.
  if (!event) z.swap(next_z);
  update_contacts(omega_before, omega_before.cross(com - support.world), /*heights_known=*/!event);
}
}  // namespace repose
