// The support after an impact with several points on the wall (see impact_support.hpp).
#include "impact_support.hpp"

#include <cmath>

#include "../tolerances.hpp"
#include "../wall/stability.hpp"

namespace repose::sim {

namespace {

Vec3 momentum_about(const SwitchState& impact, const Support& next) {
  return momentum_after_switch(impact.body, impact.q, impact.com, impact.omega, impact.com_velocity, next);
}

std::vector<Vec2> touching_polygon(const std::vector<WallVertex>& touching, double tol) {
  std::vector<Vec2> pts;
  for (const WallVertex& t : touching) pts.emplace_back(t.world.x(), t.world.y());
  return convex_hull_2d(pts, tol);
}

// The touching point whose footprint is nearest `p` (a corner of their polygon).
const WallVertex& nearest_touching(const std::vector<WallVertex>& touching, const Vec2& p) {
  const WallVertex* best = &touching[0];
  double best_d = INFINITY;
  for (const WallVertex& t : touching) {
    const double d = (Vec2(t.world.x(), t.world.y()) - p).norm();
    if (d < best_d) {
      best_d = d;
      best = &t;
    }
  }
  return *best;
}

}  // namespace

SupportChoice point_support(const WallVertex& t) {
  return {{t.world, t.body, false, Vec3::UnitX()}, t.vertex};
}

SupportChoice line_support(const WallVertex& t, Vec3 axis) {
  SupportChoice c = point_support(t);
  c.support.line = true;
  c.support.axis = axis.normalized();
  return c;
}

bool others_separate(const SwitchState& impact, const std::vector<WallVertex>& touching,
                     const Support& next) {
  const Body& body = impact.body;
  const Vec3 w = omega_from_momentum(body, next, impact.q, momentum_about(impact, next));
  const Mat3 inertia = inertia_about_support(body, next, impact.q);
  const Vec3 m = moment(body, next, impact.q, w);  // weight and damping
  // Euler's equation about a fixed point, d(I_O ω)/dt = M, with its gyroscopic term ω × I_O ω (which
  // vanishes for a rotation about a fixed axis).
  const Vec3 alpha = next.line ? Vec3(m.dot(next.axis) / next.axis.dot(inertia * next.axis) * next.axis)
                               : Vec3(inertia.ldlt().solve(m - w.cross(inertia * w)));
  const double v_tol = tol::kSpeed * std::sqrt(body.gravity * impact.length);
  const double a_tol = tol::kAccel * body.gravity;
  for (const WallVertex& t : touching) {
    Vec3 r = t.world - next.world;
    if (next.line) r -= r.dot(next.axis) * next.axis;
    if (r.norm() <= impact.touch_tol) continue;  // on the support
    const double vz = w.cross(r).z();
    const double az = (alpha.cross(r) + w.cross(w.cross(r))).z();
    if (vz < -v_tol || (vz <= v_tol && az < -a_tol)) return false;
    // Rising, but pulled back within a tenth of a step: it would be on the wall again at once (a ping-pong
    // of near-empty steps), so it does not count as separating.
    if (az < -a_tol && 2 * vz / -az < tol::kPullBackFraction * impact.dt) return false;
  }
  return true;
}

SupportChoice choose_from_touching(const SwitchState& impact, const std::vector<WallVertex>& touching,
                                   const Vec2& g) {
  const std::vector<Vec2> poly = touching_polygon(touching, impact.touch_tol);
  const ClosestFeature nearest = closest_feature(poly, g);
  std::vector<ClosestFeature> candidates = {nearest};
  const int n = static_cast<int>(poly.size());
  for (int i = 0; i < (n == 2 ? 1 : n); ++i) candidates.push_back({i, (i + 1) % n});
  for (int i = 0; i < n; ++i) candidates.push_back({i, -1});
  auto make = [&](const ClosestFeature& f) {
    const WallVertex& a = nearest_touching(touching, poly[f.i]);
    if (f.j < 0) return point_support(a);
    // The edge joins two points on the wall: a horizontal hinge, whatever round-off says.
    Vec3 edge = nearest_touching(touching, poly[f.j]).world - a.world;
    edge.z() = 0;
    return line_support(a, edge);
  };
  for (const ClosestFeature& f : candidates) {
    const SupportChoice c = make(f);
    if (others_separate(impact, touching, c.support)) return c;
  }
  // Every support the motion could go on about drives a touching point into the wall: the approaching
  // points are struck together, plastically (the paper's touch, E = 0), and the motion stops. Keeping it
  // instead (the nearest edge with its momentum) drove the third point into the wall at once, step after
  // step, without end (a tossed kitten d3 die, docs/experiments.md).
  SwitchState still = impact;
  still.omega = Vec3::Zero();
  still.com_velocity = Vec3::Zero();
  SupportChoice c = make(nearest.j >= 0 || n < 2 ? nearest : ClosestFeature{nearest.i, (nearest.i + 1) % n});
  for (const ClosestFeature& f : candidates)
    if (others_separate(still, touching, make(f).support)) {
      c = make(f);
      break;
    }
  c.stop = true;
  return c;
}

SupportChoice choose_smooth(const SwitchState& impact, const std::vector<WallVertex>& touching,
                            const WallVertex& current, const Vec2& g) {
  const WallVertex* lowest = &current;
  double deepest = INFINITY;
  for (const WallVertex& t : touching)
    if (t.vertex != current.vertex && t.height < deepest) {
      deepest = t.height;
      lowest = &t;
    }
  const SupportChoice c = point_support(*lowest);
  if (touching.size() >= 2 && !others_separate(impact, touching, c.support))
    return choose_from_touching(impact, touching, g);
  return c;
}

}  // namespace repose::sim
