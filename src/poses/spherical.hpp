// Small pieces of spherical geometry for the Gauss map: points on great-circle arcs by their chord
// parameter, half-space clips of arcs and convex spherical polygons, and spherical areas. Templates over the
// scalar (double, or an automatic-differentiation type: the design's exact gradients,
// docs/inverse-design.md); the double instantiations are the landscape's own, compiled once in spherical.cpp.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "repose/geometry/types.hpp"

namespace repose::detail {

template <class T>
using Vec3T = Eigen::Matrix<T, 3, 1>;

// The unit vector along x + t(y − x), t clamped to [0, 1] (the ends exactly).
template <class T>
Vec3T<T> chord_point(const Vec3T<T>& x, const Vec3T<T>& y, const T& t) {
  if (t <= 0) return x;
  if (t >= 1) return y;
  return (x + t * (y - x)).normalized();
}

// Chord parameter in [0, 1] where the plane through the origin with normal n crosses the segment x → y.
template <class T>
T cut(const Vec3T<T>& n, const Vec3T<T>& x, const Vec3T<T>& y) {
  const T sx = n.dot(x);
  const T sy = n.dot(y);
  if (sx == sy) return T(0.5);  // the segment lies in the plane (or is a point)
  return std::clamp(T(sx / (sx - sy)), T(0.0), T(1.0));
}

// Restricts [lo, hi] to the part of segment x → y with n·d ≥ 0 (n·d is linear in the chord parameter).
template <class T>
void clip_interval(const Vec3T<T>& n, const Vec3T<T>& x, const Vec3T<T>& y, T& lo, T& hi) {
  const T sx = n.dot(x);
  const T sy = n.dot(y);
  if (sx >= 0 && sy >= 0) return;
  if (sx < 0 && sy < 0) {
    hi = lo - 1;
    return;
  }
  const T t = sx / (sx - sy);
  if (sx < 0) {
    lo = std::max(lo, t);
  } else {
    hi = std::min(hi, t);
  }
}

// The part of a convex spherical polygon with n·d ≥ 0 (Sutherland–Hodgman; edges are shorter than π).
template <class T>
void clip_polygon(const std::vector<Vec3T<T>>& polygon, const Vec3T<T>& n, std::vector<Vec3T<T>>& out) {
  out.clear();
  const std::size_t k = polygon.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3T<T>& p = polygon[i];
    const Vec3T<T>& q = polygon[(i + 1) % k];
    const T sp = n.dot(p);
    const T sq = n.dot(q);
    if (sp >= 0) out.push_back(p);
    if ((sp >= 0) != (sq >= 0)) out.push_back((p + sp / (sp - sq) * (q - p)).normalized());
  }
}

// Area (steradian) of a convex spherical polygon: a fan of triangles, each by Van Oosterom & Strackee (1983),
// tan(E/2) = |a·(b×c)| / (1 + a·b + b·c + c·a), which stays accurate for thin triangles.
template <class T>
T spherical_area(const std::vector<Vec3T<T>>& polygon) {
  using std::abs;
  using std::atan2;
  T area(0);
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    const Vec3T<T>& a = polygon[0];
    const Vec3T<T>& b = polygon[i];
    const Vec3T<T>& c = polygon[i + 1];
    area += T(2) * atan2(abs(a.dot(b.cross(c))), T(1) + a.dot(b) + b.dot(c) + c.dot(a));
  }
  return area;
}

// The landscape's double versions (their arguments may be Eigen expressions, which a template does not
// deduce).
inline Vec3 chord_point(const Vec3& x, const Vec3& y, double t) { return chord_point<double>(x, y, t); }
inline double cut(const Vec3& n, const Vec3& x, const Vec3& y) { return cut<double>(n, x, y); }
inline void clip_interval(const Vec3& n, const Vec3& x, const Vec3& y, double& lo, double& hi) {
  clip_interval<double>(n, x, y, lo, hi);
}
inline void clip_polygon(const std::vector<Vec3>& polygon, const Vec3& n, std::vector<Vec3>& out) {
  clip_polygon<double>(polygon, n, out);
}
inline double spherical_area(const std::vector<Vec3>& polygon) { return spherical_area<double>(polygon); }

extern template Vec3 chord_point<double>(const Vec3&, const Vec3&, const double&);
extern template double cut<double>(const Vec3&, const Vec3&, const Vec3&);
extern template void clip_interval<double>(const Vec3&, const Vec3&, const Vec3&, double&, double&);
extern template void clip_polygon<double>(const std::vector<Vec3>&, const Vec3&, std::vector<Vec3>&);
extern template double spherical_area<double>(const std::vector<Vec3>&);

}  // namespace repose::detail
