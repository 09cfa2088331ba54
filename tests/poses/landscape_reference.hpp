// Shared by the rest-landscape tests: round-off tolerance, the support function, stability by the test's own
// arithmetic, closed-form spherical areas and an independent numerical integration of the gradient flow.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace repose::landscape_test {

inline constexpr double kTol = 1e-12;
inline constexpr double kPi = std::numbers::pi;

inline double total(const RestLandscape& land) {
  double sum = 0;
  for (double p : land.basin_probability) sum += p;
  return sum;
}

inline double support(const Particle& particle, const Vec3& d) {
  double h = -std::numeric_limits<double>::infinity();
  for (const Vec3& v : particle.hull.vertices) h = std::max(h, v.dot(d));
  return h;
}

// Static stability of hull face f judged by the test (equilibrium_oracle.hpp), not by the library's margins.
inline bool is_stable(const Particle& particle, int f) {
  if (f < 0) return false;
  const HullFace& face = particle.hull.faces[static_cast<std::size_t>(f)];
  std::vector<Vec3> corners;
  for (int k : face.loop) corners.push_back(particle.hull.vertices[k]);
  return oracle::face_margin(corners, face.normal) > 0;
}

inline int face_with_normal(const Particle& particle, const Vec3& n) {
  int best = -1;
  double best_dot = -2;
  for (std::size_t f = 0; f < particle.hull.faces.size(); ++f) {
    const double dot = particle.hull.faces[f].normal.dot(n);
    if (dot > best_dot) {
      best_dot = dot;
      best = static_cast<int>(f);
    }
  }
  return best;
}

// Area of a convex spherical polygon by the angle excess (Girard), independent of the library's formula.
inline double girard_area(const std::vector<Vec3>& corners) {
  const std::size_t k = corners.size();
  double angles = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& b = corners[i];
    const Vec3& a = corners[(i + k - 1) % k];
    const Vec3& c = corners[(i + 1) % k];
    const Vec3 ta = a - a.dot(b) * b;
    const Vec3 tc = c - c.dot(b) * b;
    angles += std::atan2(ta.cross(tc).norm(), ta.dot(tc));
  }
  return angles - static_cast<double>(k - 2) * kPi;
}

// ---- an independent reference: the gradient flow of h integrated numerically ------------------------------

// Minimum-norm point of the convex hull of 2-D points (zero if the hull contains the origin).
inline Vec2 min_norm_point(const std::vector<Vec2>& points) {
  std::vector<double> angles;
  for (const Vec2& p : points) {
    if (p.norm() == 0) return Vec2::Zero();
    angles.push_back(std::atan2(p.y(), p.x()));
  }
  std::sort(angles.begin(), angles.end());
  double gap = angles.front() + 2 * kPi - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) gap = std::max(gap, angles[i] - angles[i - 1]);
  if (gap < kPi) return Vec2::Zero();  // no half-plane holds all points: the origin is inside
  Vec2 best = points.front();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].norm() < best.norm()) best = points[i];
    for (std::size_t j = i + 1; j < points.size(); ++j) {
      const Vec2 ab = points[j] - points[i];
      const double t = std::clamp(-points[i].dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      const Vec2 q = points[i] + t * ab;
      if (q.norm() < best.norm()) best = q;
    }
  }
  return best;
}

// Steepest descent of h(d) = max_v v·d on the sphere, using nothing but the hull's vertex list (no Gauss-map
// topology, lunes or tipping rules). Each step follows the great circle from d against the minimum-norm
// subgradient of the vertices within 1e-9·L of the top (which slides along creases instead of zig-zagging
// across them). A step is at most `max_step` (rad) and is cut where the first other vertex rises to the top
// (event location, as in the settling engine), so no crease is overshot. Returns the face whose normal is
// nearest where the subgradient contains zero, or −1 if the flow does not stop.
inline int numeric_rest_face(const Particle& particle, Vec3 d, double max_step) {
  const std::vector<Vec3>& vertices = particle.hull.vertices;
  std::vector<Vec2> active;
  for (int it = 0; it < 100000; ++it) {
    const double h = support(particle, d);
    const Vec3 e1 = d.unitOrthogonal();
    const Vec3 e2 = d.cross(e1);
    active.clear();
    for (const Vec3& v : vertices) {
      if (v.dot(d) >= h - 1e-9 * particle.length) active.emplace_back(v.dot(e1), v.dot(e2));
    }
    const Vec2 g = min_norm_point(active);
    if (g.norm() < 1e-12 * particle.length) return face_with_normal(particle, d);
    const Vec3 u = -(g.x() * e1 + g.y() * e2) / g.norm();
    // Along d(s) = cos s·d + sin s·u the top is the active vertex descending slowest; another vertex w with
    // (w − top)·d = A ≤ 0 and (w − top)·u = B > 0 reaches it at s = atan2(−A, B).
    const Vec3* top = nullptr;
    for (const Vec3& v : vertices) {
      if (v.dot(d) >= h - 1e-9 * particle.length && (top == nullptr || v.dot(u) > top->dot(u))) top = &v;
    }
    double step = max_step;
    for (const Vec3& w : vertices) {
      const double a = (w - *top).dot(d);
      const double b = (w - *top).dot(u);
      if (a < -1e-9 * particle.length && b > 0) step = std::min(step, std::atan2(-a, b));
    }
    d = (std::cos(step) * d + std::sin(step) * u).normalized();
  }
  return -1;
}

inline Vec3 random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  while (true) {
    const Vec3 d(normal(rng), normal(rng), normal(rng));
    if (d.norm() > 1e-6) return d.normalized();
  }
}

}  // namespace repose::landscape_test
