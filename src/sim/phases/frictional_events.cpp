// The frictional contact phase's event search (frictional_contact.hpp): a vertex reaching the wall, one on it
// sinking below its drift, a point's rule ending (a slip stopping or turning back, a point at rest starting
// to slip, a point lifting out of the band), located on the dense output.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "../body/kinematics.hpp"
#include "../events/wall_crossing.hpp"
#include "../solver/contact_problem.hpp"
#include "frictional_contact.hpp"

namespace repose::sim {

// A vertex reaching the wall is found by the one wall-crossing search (events/wall_crossing.hpp), which
// cannot pass over a vertex that dips below the wall and back between two instants it looked at (the bound
// on its acceleration clears an interval, or it is halved); a rule's end by the step's event samples and
// bisection.

double FrictionalContact::locate_event(double a, double b) {
  const Run& run = run_;
  const auto& verts = run.particle.hull.vertices;
  // A vertex off the set reaching the wall (the wall-crossing search: the points of the set are left out of
  // it by a level of −∞, since the bound on their acceleration, which the wall's forces cancel, would halve
  // the step without end), or one in the set sinking below it by more than the drift allows (a
  // configuration turned inconsistent within the step: Painlevé's, resolved at the event) or lifting out of
  // the band (rule_ends).
  // (Marks of the set's points, cleared after the search: no pass over the hull.)
  if (on_wall_.size() != verts.size()) on_wall_.assign(verts.size(), 0);
  for (int k : active_) on_wall_[static_cast<std::size_t>(k)] = 1;
  const double sinking = -tol::kPierceFloor * run.tol.event;
  // A point's rule ending: a sliding point's slip stopping, or turning against its direction at the segment's
  // start; a point at rest starting to slip (issue 48: it kept the rule of a point at rest until the step
  // ended, sticking while it moved); a point on the wall lifting out of the band (issue 48: the set was
  // fixed for the step, and a point that had lifted could take a force above the wall) or sinking below
  // its drift; a sliding point reaching Painlevé's dynamic jam (tolerances.hpp, kJamCompliance): its
  // compliance under its own friction first, cheap, and only where that is small the forces that decide it.
  const auto rule_ended = [&](const BodyState& s) {
    std::optional<Mat3> inverse_inertia;  // only where a point slides
    bool near_jam = false;
    for (std::size_t i = 0; i < active_.size(); ++i) {
      const Vec3 arm = s.q * verts[static_cast<std::size_t>(active_[i])];
      const double height = s.com.z() + arm.z();
      if (height > run.tol.frictional_band || height < sinking) return true;
      const Vec2 slip = (point_velocity(s.velocity, s.omega, arm)).head<2>();
      if (conditions_[i].rule == PointRule::sliding) {
        if (slip.norm() <= run.tol.speed || slip.dot(conditions_[i].direction) <= 0) return true;
        if (!inverse_inertia)
          inverse_inertia = world_inverse_inertia(s.q.toRotationMatrix(), run.body.inertia);
        const Mat3 W = delassus_block(run.body.mass, *inverse_inertia, arm);
        near_jam = near_jam || sliding_compliance(W, run.params.friction, slip.normalized()) <=
                                   tol::kJamCompliance * W(2, 2);
      } else if (slip.norm() > tol::kSlipHysteresis * run.tol.slip_speed) {
        return true;
      }
    }
    if (!near_jam) return false;
    const ContactForces f = forces_at(s);
    return std::any_of(f.inconsistent.begin(), f.inconsistent.end(), [](char c) { return c != 0; });
  };
  const auto rule_ends = [&](double t) { return rule_ended(integrator_.state_at(t)); };
  // The dense output at the step's event samples: the first at which a rule has ended brackets that event,
  // and the samples' velocities bound the vertices' vertical accelerations over the step.
  const auto times = sample_times(a, b);
  std::array<BodyState, tol::kEventSamples + 1> states;
  for (int i = 0; i <= tol::kEventSamples; ++i) states[i] = integrator_.state_at(times[i]);
  // |z''| ≤ |a| + |α|·r + |ω|²·r at a vertex r from the centre of mass: |a| and |α| taken as the largest mean
  // rates of change between samples (1/8 of a step of a dense output smooth to the integrator's tolerance),
  // |ω| as the largest sampled, the whole bound multiplied by kAccelerationMargin.
  double linear = 0, angular = 0, spin = 0;
  for (int i = 0; i <= tol::kEventSamples; ++i) {
    spin = std::max(spin, states[i].omega.squaredNorm());
    if (i == 0) continue;
    const double span = times[i] - times[i - 1];
    linear = std::max(linear, (states[i].velocity - states[i - 1].velocity).norm() / span);
    angular = std::max(angular, (states[i].omega - states[i - 1].omega).norm() / span);
  }
  // (At least the acceleration that is none, still_acceleration: a raised bound only halves more.)
  const double accel = std::max(tol::kAccelerationMargin * (linear + (angular + spin) * run.hull_radius),
                                run.tol.still_acceleration);
  const auto frame_at = [&](double t) {
    const BodyState s = integrator_.state_at(t);
    return WallFrame{s.q, s.omega, s.com.z(), s.velocity.z()};
  };
  const double touch =
      wall_.first_crossing(a, b, verts, run.near_wall, run.hull_radius, accel, (b - a) * kEventResolution,
                           frame_at, [&](std::size_t k) { return on_wall_[k] ? -INFINITY : 0.0; });
  for (int k : active_) on_wall_[static_cast<std::size_t>(k)] = 0;
  // A rule's end before the touch: bisected in the first sample interval at whose end it holds.
  double when = touch;
  for (int i = 1; i <= tol::kEventSamples && times[i - 1] < touch; ++i) {
    if (!rule_ended(states[i])) continue;
    EventSearch search;
    search.resolution = (b - a) * kEventResolution;
    const Located l = locate(times[i - 1], times[i], search, rule_ends, monotone);
    if (l.found()) when = std::min(when, l.hi);
    break;
  }
  return std::isfinite(when) ? std::max(when, std::nextafter(a, INFINITY)) : INFINITY;
}

}  // namespace repose::sim
