// The centroid of a convex hull's solid, in any scalar (the tape's and the optimiser's).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "repose/geometry/hull.hpp"

namespace repose::detail {

// Each face's fan of tetrahedra with the first vertex as apex: Σ V_t (apex + a + b + c)/4 / Σ V_t.
template <class T>
Eigen::Matrix<T, 3, 1> solid_centroid(const std::vector<Eigen::Matrix<T, 3, 1>>& x, const ConvexHull& hull) {
  using V = Eigen::Matrix<T, 3, 1>;
  const V& o = x.front();
  T volume(0.0);
  V moment = V::Zero();
  for (const HullFace& f : hull.faces) {
    const V& a = x[static_cast<std::size_t>(f.loop[0])];
    for (std::size_t k = 1; k + 1 < f.loop.size(); ++k) {
      const V& b = x[static_cast<std::size_t>(f.loop[k])];
      const V& c = x[static_cast<std::size_t>(f.loop[k + 1])];
      const T v = (a - o).dot(V((b - o).cross(c - o)));
      volume += v;
      moment += v * V(o + a + b + c);
    }
  }
  return moment / (T(4.0) * volume);
}

}  // namespace repose::detail
