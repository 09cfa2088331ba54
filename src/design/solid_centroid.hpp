// The centroid of a convex hull's solid, in any scalar (the tape's and the optimiser's).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "repose/geometry/hull.hpp"

namespace repose::detail {

// Calls visit(a, b, c, 6V) for each tetrahedron of the solid's fan: each face's triangles (a, b, c) with the
// first vertex of `x` as apex, 6V their signed volume (positive for outward loops).
template <class T, class Visit>
void for_each_fan_tetrahedron(const std::vector<Eigen::Matrix<T, 3, 1>>& x, const ConvexHull& hull,
                              Visit&& visit) {
  using V = Eigen::Matrix<T, 3, 1>;
  const V& o = x.front();
  for (const HullFace& f : hull.faces) {
    const V& a = x[static_cast<std::size_t>(f.loop[0])];
    for (std::size_t k = 1; k + 1 < f.loop.size(); ++k) {
      const V& b = x[static_cast<std::size_t>(f.loop[k])];
      const V& c = x[static_cast<std::size_t>(f.loop[k + 1])];
      visit(a, b, c, T((a - o).dot(V((b - o).cross(c - o)))));
    }
  }
}

// Σ V_t (apex + a + b + c)/4 / Σ V_t over the fan.
template <class T>
Eigen::Matrix<T, 3, 1> solid_centroid(const std::vector<Eigen::Matrix<T, 3, 1>>& x, const ConvexHull& hull) {
  using V = Eigen::Matrix<T, 3, 1>;
  const V& o = x.front();
  T volume(0.0);
  V moment = V::Zero();
  for_each_fan_tetrahedron<T>(x, hull, [&](const V& a, const V& b, const V& c, const T& v) {
    volume += v;
    moment += v * V(o + a + b + c);
  });
  return moment / (T(4.0) * volume);
}

// The solid's volume: Σ V_t over the fan.
template <class T>
T solid_volume(const std::vector<Eigen::Matrix<T, 3, 1>>& x, const ConvexHull& hull) {
  using V = Eigen::Matrix<T, 3, 1>;
  T six(0.0);
  for_each_fan_tetrahedron<T>(x, hull, [&](const V&, const V&, const V&, const T& v) { six += v; });
  return six / T(6.0);
}

}  // namespace repose::detail
