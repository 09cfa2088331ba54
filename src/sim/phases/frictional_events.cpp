// The frictional contact phase's event search (frictional_contact.hpp): a vertex reaching the wall, one on it
// sinking below its drift, a point's rule ending (a slip stopping or turning back, a point at rest starting
// to slip, a point lifting out of the band), located on the dense output.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "../body/kinematics.hpp"
#include "../events/events.hpp"
#include "frictional_contact.hpp"

namespace repose::sim {

// The event search samples each step at tol::kEventSamples instants and bisects the first interval in which
// an event holds at its end (the motion is smooth in a step: a vertex dipping below the wall and back within
// an eighth of a step is caught by the next step's projection instead, and counted in the depth).

double FrictionalContact::locate_event(double a, double b) {
  const Run& run = run_;
  const auto& verts = run.particle.hull.vertices;
  // A vertex off the set reaching the wall, or one in the set sinking below it by more than the drift
  // allows (a configuration turned inconsistent within the step: Painlevé's, resolved at the event).
  std::vector<char> on(verts.size(), 0);
  for (int k : active_) on[static_cast<std::size_t>(k)] = 1;
  const double sinking = -tol::kPierceFloor * run.tol.event;
  // Whether any of `indices` is below its level at t; only the height is needed: the rotation's third row.
  const auto any_below = [&](double t, const auto& indices) {
    const BodyState s = integrator_.state_at(t);
    const Vec3 up = s.q.toRotationMatrix().row(2).transpose();
    for (std::size_t k : indices)
      if (s.com.z() + up.dot(verts[k]) < (on[k] ? sinking : 0.0)) return true;
    return false;
  };
  // (a vector, not std::views::iota: clang with libstdc++ 12, the fuzzers' compiler, rejects iota_view)
  std::vector<std::size_t> every_vertex(verts.size());
  std::iota(every_vertex.begin(), every_vertex.end(), std::size_t{0});
  const auto touches = [&](double t) { return any_below(t, every_vertex); };
  // The same test over the vertices that may reach their level within the bracket being bisected (the
  // others stay above it there, by the bound in locate_event's loop): a rolling rim has a handful near the
  // wall among hundreds.
  std::vector<std::size_t> near;
  const auto near_touches = [&](double t) { return any_below(t, near); };
  // A point's rule ending: a sliding point's slip stopping, or turning against its direction at the segment's
  // start; a point at rest starting to slip (issue 48: it kept the rule of a point at rest until the step
  // ended, sticking while it moved); a point on the wall lifting out of the band (issue 48: the set was
  // fixed for the step, and a point that had lifted could take a force above the wall).
  // A sliding point reaching Painlevé's dynamic jam (tolerances.hpp, kJamCompliance): its compliance under
  // its own friction first, cheap, and only where that is small the forces that decide it.
  const auto rule_ends = [&](double t) {
    const BodyState s = integrator_.state_at(t);
    const Mat3 inverse_inertia = world_inverse_inertia(s.q.toRotationMatrix(), run.body.inertia);
    bool near_jam = false;
    for (std::size_t i = 0; i < active_.size(); ++i) {
      const Vec3 arm = s.q * verts[static_cast<std::size_t>(active_[i])];
      if (s.com.z() + arm.z() > run.tol.frictional_band) return true;
      const Vec2 slip = (point_velocity(s.velocity, s.omega, arm)).head<2>();
      if (conditions_[i].rule == PointRule::sliding) {
        if (slip.norm() <= run.tol.speed || slip.dot(conditions_[i].direction) <= 0) return true;
        const Mat3 W = delassus_block(run.body.mass, inverse_inertia, arm);
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
  // The vertices' heights and vertical velocities at an instant: a vertex that dips below the wall and comes
  // back between two samples (its height falling at the first, rising at the second) is found by the minimum
  // of its cubic Hermite interpolant, checked on the dense output.
  const std::size_t nv = verts.size();
  std::vector<double> h0(nv), w0(nv), h1(nv), w1(nv);
  BodyState s0, s1;  // the states at the samples
  const auto sample = [&](double t, std::vector<double>& h, std::vector<double>& w, BodyState& s) {
    s = integrator_.state_at(t);
    const Mat3 R = s.q.toRotationMatrix();
    for (std::size_t k = 0; k < nv; ++k) {
      const Vec3 r = R * verts[k];
      h[k] = s.com.z() + r.z();
      w[k] = s.velocity.z() + s.omega.x() * r.y() - s.omega.y() * r.x();
    }
  };
  const auto dip = [&](double t0, double t1) {
    double first = INFINITY;
    const double span = t1 - t0;
    for (std::size_t k = 0; k < nv; ++k) {
      const double level = on[k] ? sinking : 0.0;
      const double m0 = w0[k] * span, m1 = w1[k] * span;
      if (!(m0 < 0 && m1 > 0) || std::min(h0[k], h1[k]) - level > -m0 + m1) continue;
      // p(s) = c0 + c1·s + c2·s² + c3·s³ on [0, 1]; p' goes from m0 < 0 to m1 > 0: its root, bisected.
      const double c0 = h0[k], c1 = m0, c2 = -3 * h0[k] - 2 * m0 + 3 * h1[k] - m1,
                   c3 = 2 * h0[k] + m0 - 2 * h1[k] + m1;
      double lo = 0, hi = 1;
      for (int i = 0; i < tol::kHermiteBisections; ++i) {
        const double mid = 0.5 * (lo + hi);
        (c1 + mid * (2 * c2 + 3 * c3 * mid) < 0 ? lo : hi) = mid;
      }
      const double sm = 0.5 * (lo + hi);
      if (c0 + sm * (c1 + sm * (c2 + c3 * sm)) < level) first = std::min(first, t0 + sm * span);
    }
    return first;
  };
  EventSearch search;
  search.resolution = (b - a) * kEventResolution;
  double prev = a;
  sample(a, h0, w0, s0);
  for (int j = 1; j <= tol::kEventSamples; ++j) {
    const double t = j == tol::kEventSamples ? b : a + (b - a) * j / tol::kEventSamples;
    sample(t, h1, w1, s1);
    bool touch = touches(t);
    double upper = t;
    // A dip before t, even where something is below the wall at t: the bisection would otherwise find the
    // later crossing and pass over the dip.
    if (const double d = dip(prev, t); d < t && touches(d)) {
      touch = true;
      upper = d;
    }
    const bool stop = rule_ends(t);
    if (touch || stop) {
      double when = INFINITY;
      // A touch at the bracket's lower end (nothing below the wall yet), a stop at its upper end (stopped).
      if (touch) {
        // Over [prev, t] (span Δ) a vertex's height moves by at most Δ·|w| + Δ²·A/2 from either end, w its
        // vertical speed there and A ≤ |a| + |α|·r + |ω|²·r its acceleration; |a| and |α| are taken as the
        // mean rates of change over the bracket, 1/8 of a step of a dense output smooth to the integrator's
        // tolerance, and the bound is doubled: a vertex whose level is farther than that at both ends is
        // not below it anywhere in between, nor in the bisection's sub-brackets (checked against the full
        // test on 340,000 brackets of 300 property tosses: the same brackets to the bit).
        const double span = t - prev, radius = run.hull_radius;
        const double accel = (s1.velocity - s0.velocity).norm() / span +
                             (s1.omega - s0.omega).norm() / span * radius +
                             std::max(s0.omega.squaredNorm(), s1.omega.squaredNorm()) * radius;
        near.clear();
        for (std::size_t k = 0; k < nv; ++k) {
          const double reach = 2 * span * (std::max(std::abs(w0[k]), std::abs(w1[k])) + span * accel);
          if (std::min(h0[k], h1[k]) - (on[k] ? sinking : 0.0) <= reach) near.push_back(k);
        }
        const Located l = locate(prev, upper, search, near_touches, monotone);
        if (l.found()) when = l.lo;
      }
      if (stop) {
        const Located l = locate(prev, t, search, rule_ends, monotone);
        if (l.found()) when = std::min(when, l.hi);
      }
      if (std::isfinite(when)) return std::max(when, std::nextafter(a, INFINITY));
    }
    std::swap(h0, h1);
    std::swap(w0, w1);
    std::swap(s0, s1);
    prev = t;
  }
  return INFINITY;
}

}  // namespace repose::sim
