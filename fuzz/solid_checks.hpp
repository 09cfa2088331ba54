// Invariants of an accepted solid, checked by the harnesses themselves (a few lines each, no library call),
// so that a mesh validate_mesh wrongly accepts is caught even when nothing crashes.
#pragma once

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

#include "repose/geometry/types.hpp"

namespace repose_fuzz {

inline void require(bool ok) {
  if (!ok) __builtin_trap();
}

// A closed, consistently wound 2-manifold surface: every directed edge (a, b) of a triangle occurs exactly
// once, and its reverse (b, a) occurs exactly once too (each edge has exactly two triangles, traversed in
// opposite senses). Indices in range, triangles with three distinct vertices.
inline bool closed_and_consistently_wound(const repose::TriangleMesh& mesh) {
  const auto n = static_cast<std::int64_t>(mesh.vertices.size());
  std::map<std::pair<std::int32_t, std::int32_t>, int> directed;
  for (const repose::Triangle& t : mesh.triangles) {
    for (const std::int32_t i : t)
      if (i < 0 || i >= n) return false;
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return false;
    for (int k = 0; k < 3; ++k)
      if (++directed[{t[k], t[(k + 1) % 3]}] != 1) return false;
  }
  for (const auto& [edge, count] : directed)
    if (!directed.count({edge.second, edge.first})) return false;
  return !mesh.triangles.empty();
}

// Volume by the divergence theorem (sum of signed tetrahedra), about the bounding-box centre to keep the
// terms small; also returns the surface area, the bounding-box diagonal and the largest |coordinate|, from
// which the round-off bound on a volume is computed.
struct SolidSums {
  double volume = 0, area = 0, diagonal = 0, max_coordinate = 0;
};

inline SolidSums solid_sums(const repose::TriangleMesh& mesh) {
  repose::Vec3 lo = mesh.vertices.front(), hi = lo;
  SolidSums s;
  for (const repose::Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
    s.max_coordinate = std::max(s.max_coordinate, v.cwiseAbs().maxCoeff());
  }
  const repose::Vec3 c = 0.5 * (lo + hi);
  s.diagonal = (hi - lo).norm();
  for (const repose::Triangle& t : mesh.triangles) {
    const repose::Vec3 a = mesh.vertices[t[0]] - c, b = mesh.vertices[t[1]] - c, d = mesh.vertices[t[2]] - c;
    s.volume += a.dot(b.cross(d)) / 6;
    s.area += 0.5 * (b - a).cross(d - a).norm();
  }
  return s;
}

// How far two volume computations of the same closed surface may differ by round-off alone: recursive
// summation of n tetrahedra, each |det| ≤ 2·(its area)·D about any point of the bounding box, errs by at most
// ~(n + 4)·ε·Σ|det|/6 ≤ (n + 4)·ε·A·D/3 (Higham, Accuracy and Stability, §4.2); translating the vertices (to
// the bounding-box centre here, to the centre of mass in the library) moves each by up to ε·max|x|, which
// changes the volume by at most A·ε·max|x|. Twice the sum of both, for both computations.
inline double volume_round_off(const repose::TriangleMesh& mesh, const SolidSums& s) {
  const double n = static_cast<double>(mesh.triangles.size());
  return 2 * DBL_EPSILON * s.area * ((n + 4) * s.diagonal / 3 + 2 * s.max_coordinate);
}

}  // namespace repose_fuzz
