// Internal: the one wall-crossing search of a body moving freely (a flight, the frictional contact phase):
// the first instant at which a hull vertex reaches its level at the wall, located by locate() (events.hpp)
// on the motion's dense output.
//
// The candidate bound: over an interval [tl, tr] a vertex's height z has |z''| ≤ A (the phase gives A: the
// centre of mass's acceleration plus the angular and centripetal accelerations of the vertex), so from z and
// z' at both ends it stays above its level for (z'(tl) + sqrt(z'(tl)² + 2·A·z(tl)))/A after tl and the
// mirror time before tr; an interval those two cover is clear for it. The vertices the bound does not clear
// over the whole step are the candidates (a body rolling on its rim has a handful near the wall among
// hundreds); the search halves only intervals the bound cannot clear, so it cannot step over a touch, nor
// over a vertex that dips below its level and back between two instants it looked at.
//
// The bound's test looks only at the vertices that can reach the wall within the step (issue 49: a cost per
// step independent of the hull's size): with every level ≤ 0, a vertex higher at tl than
// reach = 2·((|v_z| + |ω|·R)·h + ½·A·h²) (R the hull's radius, h the step) cannot come down to its level
// before tr, and the bound's own test clears it (its time to reach the level from tl alone exceeds h); the
// factor 2 keeps that so through round-off. Those vertices are found by a walk of the hull's edge graph from
// the lowest (wall/near_wall.hpp), in index order: the candidates are the ones a scan gives.
//
// The paper's phase (contact_adaptive_step.cpp) turns about a fixed support instead: its candidates come from
// an energy bound on the angle a step can sweep, and its events (entering and leaving the ε band as well as
// the wall) from the same locate() on the same evenly spaced samples (sample_times below).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <tuple>
#include <utility>
#include <vector>

#include "../tolerances.hpp"
#include "../wall/near_wall.hpp"
#include "events.hpp"
#include "repose/geometry/types.hpp"

namespace repose::sim {

/// What the search needs of a body at an instant: its orientation and angular velocity, and its centre of
/// mass's height above the wall and vertical speed.
struct WallFrame {
  Quat q = Quat::Identity();  ///< body → world
  Vec3 omega = Vec3::Zero();  ///< world frame
  double height = 0;
  double speed = 0;
};

/// The instants an adaptive step [t0, t1] is searched at for events: tol::kEventSamples evenly spaced after
/// t0, the last t1 exactly.
inline std::array<double, tol::kEventSamples + 1> sample_times(double t0, double t1) {
  std::array<double, tol::kEventSamples + 1> times;
  for (int i = 0; i <= tol::kEventSamples; ++i)
    times[i] = i == tol::kEventSamples ? t1 : t0 + (t1 - t0) * i / tol::kEventSamples;
  return times;
}

/// Whether a vertex at heights zl, zr above its level (round-off clamped at 0) with vertical speeds vl, vr at
/// tl, tr stays above it in between, by |z''| ≤ accel.
inline bool stays_above(double accel, double tl, double zl, double vl, double tr, double zr, double vr) {
  zl = std::max(zl, 0.0);
  zr = std::max(zr, 0.0);
  const double after = (vl + std::sqrt(vl * vl + 2 * accel * zl)) / accel;
  const double before = (-vr + std::sqrt(vr * vr + 2 * accel * zr)) / accel;
  return after + before >= tr - tl;
}

class WallCrossing {
 public:
  /// The lower end of a bracket `resolution` wide in which a vertex of `vertices` (body frame, from the
  /// centre of mass) first goes below its level `level(k)` (0: the wall; −∞ leaves the vertex out) in (a, b],
  /// so nothing is below its level at the time returned; +∞ if none does. `frame_at(t)` is the body's
  /// WallFrame at any t in [a, b], `accel` the bound A on every vertex's |z''| over [a, b]. `vertices` are
  /// the hull's, whose edge graph `near` walks and whose radius is `radius`; every level is ≤ 0.
  template <class FrameAt, class Level>
  double first_crossing(double a, double b, const std::vector<Vec3>& vertices, NearWall& near, double radius,
                        double accel, double resolution, FrameAt&& frame_at, Level&& level) {
    // A vertex's height above its level and vertical speed.
    const auto vertex = [&](const WallFrame& f, std::size_t k) {
      const Vec3 r = f.q * vertices[k];
      return std::pair{f.height + r.z() - level(k), f.speed + f.omega.cross(r).z()};
    };
    // The candidates: every other vertex stays above its level over the whole step by the bound, hence over
    // each part of it, so the search looks at these only.
    candidates_.clear();
    {
      const WallFrame fa = frame_at(a), fb = frame_at(b);
      const double h = b - a;
      const double reach = 2 * ((std::abs(fa.speed) + fa.omega.norm() * radius) * h + 0.5 * accel * h * h);
      const auto& near_wall = near.vertices_below(fa.q, fa.height, reach, 0.0, [](int) { return true; });
      for (int vertex_index : near_wall) {
        const auto k = static_cast<std::size_t>(vertex_index);
        if (level(k) == -INFINITY) continue;
        const auto [za, va] = vertex(fa, k);
        const auto [zb, vb] = vertex(fb, k);
        if (zb < 0 || !stays_above(accel, a, za, va, b, zb, vb)) candidates_.push_back(k);
      }
    }
    if (candidates_.empty()) return INFINITY;
    // The candidates' heights and vertical speeds at an instant: recomputed from the instant when needed, not
    // kept with the intervals still to examine. The last few are cached, since the search examines an
    // interval right after halving its parent, whose ends it shares.
    const std::size_t n = candidates_.size();
    samples_.resize(tol::kFlightCachedSamples * 2 * n);
    sample_time_.fill(NAN);  // a sample describes this step only
    // Slots are written in turn, never the one holding the other end of the interval being tested.
    std::size_t cursor = 0;
    // The slot of the sample at instant s: heights at [0, n), vertical speeds at [n, 2n).
    const auto sample = [&](double s, std::size_t keep) {
      for (std::size_t i = 0; i < tol::kFlightCachedSamples; ++i)
        if (sample_time_[i] == s) return i;
      std::size_t slot = cursor++ % tol::kFlightCachedSamples;
      if (slot == keep) slot = cursor++ % tol::kFlightCachedSamples;
      double* out = &samples_[slot * 2 * n];
      const WallFrame f = frame_at(s);
      for (std::size_t i = 0; i < n; ++i) std::tie(out[i], out[n + i]) = vertex(f, candidates_[i]);
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
        if (!stays_above(accel, tl, l[k], l[n + k], tr, r[k], r[n + k])) return false;
      return true;
    };
    EventSearch search;
    search.resolution = resolution;
    const Located touch = locate(a, b, search, below, clear);
    // A bracket: on or above the level at lo, below it at hi. A search cut short (a tangency within
    // round-off) takes the start of the interval it would have examined next.
    const bool ends = touch.kind == Located::Kind::bracket || touch.kind == Located::Kind::exhausted;
    return ends ? touch.lo : INFINITY;
  }

  /// The candidates of the last search (hull vertex indices): for tests.
  const std::vector<std::size_t>& candidates() const { return candidates_; }

 private:
  // Working memory, kept from search to search: no allocation once it has grown.
  std::vector<std::size_t> candidates_;
  std::vector<double> samples_;
  std::array<double, tol::kFlightCachedSamples> sample_time_{};
};

}  // namespace repose::sim
