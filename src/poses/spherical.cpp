#include "spherical.hpp"

#include <algorithm>
#include <cmath>

namespace repose::detail {

Vec3 chord_point(const Vec3& x, const Vec3& y, double t) {
  if (t <= 0) return x;
  if (t >= 1) return y;
  return (x + t * (y - x)).normalized();
}

// Chord parameter in [0, 1] where the plane through the origin with normal n crosses the segment x → y.
double cut(const Vec3& n, const Vec3& x, const Vec3& y) {
  const double sx = n.dot(x);
  const double sy = n.dot(y);
  if (sx == sy) return 0.5;  // the segment lies in the plane (or is a point)
  return std::clamp(sx / (sx - sy), 0.0, 1.0);
}

// Restricts [lo, hi] to the part of segment x → y with n·d ≥ 0 (n·d is linear in the chord parameter).
void clip_interval(const Vec3& n, const Vec3& x, const Vec3& y, double& lo, double& hi) {
  const double sx = n.dot(x);
  const double sy = n.dot(y);
  if (sx >= 0 && sy >= 0) return;
  if (sx < 0 && sy < 0) {
    hi = lo - 1;
    return;
  }
  const double t = sx / (sx - sy);
  if (sx < 0) {
    lo = std::max(lo, t);
  } else {
    hi = std::min(hi, t);
  }
}

// The part of a convex spherical polygon with n·d ≥ 0 (Sutherland–Hodgman; edges are shorter than π).
void clip_polygon(const std::vector<Vec3>& polygon, const Vec3& n, std::vector<Vec3>& out) {
  out.clear();
  const std::size_t k = polygon.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& p = polygon[i];
    const Vec3& q = polygon[(i + 1) % k];
    const double sp = n.dot(p);
    const double sq = n.dot(q);
    if (sp >= 0) out.push_back(p);
    if ((sp >= 0) != (sq >= 0)) out.push_back((p + sp / (sp - sq) * (q - p)).normalized());
  }
}

// Area (steradian) of a convex spherical polygon: a fan of triangles, each by Van Oosterom & Strackee (1983),
// tan(E/2) = |a·(b×c)| / (1 + a·b + b·c + c·a), which stays accurate for thin triangles.
double spherical_area(const std::vector<Vec3>& polygon) {
  double area = 0;
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    const Vec3& a = polygon[0];
    const Vec3& b = polygon[i];
    const Vec3& c = polygon[i + 1];
    area += 2 * std::atan2(std::abs(a.dot(b.cross(c))), 1 + a.dot(b) + b.dot(c) + c.dot(a));
  }
  return area;
}

}  // namespace repose::detail
