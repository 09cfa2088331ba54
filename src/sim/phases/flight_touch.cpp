// The touch that ends a spinning flight: the first instant at which a hull vertex reaches the wall, as a root
// function of the event locator (events.hpp).
//
// The search cannot step over a touch: over an interval [s0, s1] a vertex's height z has |z''| ≤ A = g +
// 2·R·|L|²/I_min² (the centre of mass's fall plus the body's centripetal and torque-free angular
// accelerations, |ω| ≤ |L|/I_min), so from z and z' at both ends it stays above the wall for
// (z'(s0) + sqrt(z'(s0)² + 2·A·z(s0)))/A after s0 and the mirror time before s1; an interval those two
// cover is clear.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "../events/events.hpp"
#include "flight.hpp"

namespace repose::sim {

// The lower end of a bracket kEventResolution of the step wide, so nothing is ever below the wall; +∞ if no
// vertex reaches the wall in (a, b].
double Flight::locate_touch(double a, double b) {
  const auto& verts = run_.particle.hull.vertices;
  if (inertia_min_ == 0)
    inertia_min_ = Eigen::SelfAdjointEigenSolver<Mat3>(run_.body.inertia, Eigen::EigenvaluesOnly)
                       .eigenvalues()
                       .minCoeff();
  const Mat3 R0 = run_.q.toRotationMatrix();
  const double spin_momentum = (R0 * run_.body.inertia * R0.transpose() * omega_).norm();
  const double accel = run_.params.gravity +
                       2 * run_.hull_radius * spin_momentum * spin_momentum / (inertia_min_ * inertia_min_);
  // A vertex's height and vertical speed on top of the centre of mass's.
  const auto vertex = [&](const Rotation& st, std::pair<double, double> c, std::size_t k) {
    const Vec3 r = st.q * verts[k];
    return std::pair{c.first + r.z(), c.second + st.omega.cross(r).z()};
  };
  // Whether a vertex at heights zl, zr ≥ 0 (round-off clamped) and speeds vl, vr at tl, tr stays above the
  // wall in between, by the bound A.
  const auto vertex_clear = [&](double tl, double zl, double vl, double tr, double zr, double vr) {
    zl = std::max(zl, 0.0);
    zr = std::max(zr, 0.0);
    const double after = (vl + std::sqrt(vl * vl + 2 * accel * zl)) / accel;
    const double before = (-vr + std::sqrt(vr * vr + 2 * accel * zr)) / accel;
    return after + before >= tr - tl;
  };
  // The vertices that may reach the wall in (a, b]: every other one stays above it over the whole step by the
  // bound, hence over each part of it, so the search looks at these only (a body rolling on its rim has a
  // handful near the wall among hundreds).
  candidates_.clear();
  {
    const Rotation sa = rotation_->state_at(a), sb = rotation_->state_at(b);
    const auto ca = centre_at(a), cb = centre_at(b);
    for (std::size_t k = 0; k < verts.size(); ++k) {
      const auto [za, va] = vertex(sa, ca, k);
      const auto [zb, vb] = vertex(sb, cb, k);
      if (zb < 0 || !vertex_clear(a, za, va, b, zb, vb)) candidates_.push_back(k);
    }
  }
  if (candidates_.empty()) return INFINITY;
  // The candidates' heights and vertical speeds at an instant: recomputed from the instant when needed, not
  // kept with the intervals still to examine. The last few are cached, since the search examines an
  // interval right after halving its parent, whose ends it shares.
  const std::size_t n = candidates_.size();
  samples_.resize(tol::kFlightCachedSamples * 2 * n);
  sample_time_.fill(NAN);  // a sample describes this flight step only
  // Slots are written in turn, never the one holding the other end of the interval being tested.
  std::size_t cursor = 0;
  // The slot of the sample at instant s: heights at [0, n), vertical speeds at [n, 2n).
  const auto sample = [&](double s, std::size_t keep) {
    for (std::size_t i = 0; i < tol::kFlightCachedSamples; ++i)
      if (sample_time_[i] == s) return i;
    std::size_t slot = cursor++ % tol::kFlightCachedSamples;
    if (slot == keep) slot = cursor++ % tol::kFlightCachedSamples;
    double* out = &samples_[slot * 2 * n];
    const Rotation st = rotation_->state_at(s);
    const auto c = centre_at(s);
    for (std::size_t i = 0; i < n; ++i) std::tie(out[i], out[n + i]) = vertex(st, c, candidates_[i]);
    sample_time_[slot] = s;
    return slot;
  };
  const auto below = [&](double s) {
    const double* z = &samples_[sample(s, tol::kFlightCachedSamples) * 2 * n];
    return *std::min_element(z, z + n) < 0;
  };
  const auto clear = [&](double tl, double tr) {
    const std::size_t left = sample(tl, tol::kFlightCachedSamples);
    const double* l = &samples_[left * 2 * n];
    const double* r = &samples_[sample(tr, left) * 2 * n];
    for (std::size_t k = 0; k < n; ++k)
      if (!vertex_clear(tl, l[k], l[n + k], tr, r[k], r[n + k])) return false;
    return true;
  };
  EventSearch search;
  search.resolution = (b - a) * kEventResolution;
  const Located touch = locate(a, b, search, below, clear);
  // A bracket: on or above the wall at lo, below it at hi. A search cut short (a tangency within round-off)
  // takes the start of the interval it would have examined next as the touch.
  const bool ends = touch.kind == Located::Kind::bracket || touch.kind == Located::Kind::exhausted;
  return ends ? touch.lo : INFINITY;
}

}  // namespace repose::sim
