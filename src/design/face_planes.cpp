// Face planes (face_planes.hpp).
#include "face_planes.hpp"

#include <Eigen/LU>
#include <cmath>

#include "repose/error.hpp"

namespace repose::detail {

std::vector<Vec3> face_planes(const ConvexHull& hull) {
  std::vector<Vec3> out;
  out.reserve(hull.faces.size());
  for (const HullFace& f : hull.faces) out.push_back(f.normal / f.offset);
  return out;
}

std::optional<std::vector<Vec3>> plane_vertices(const std::vector<Vec3>& planes) {
  for (const Vec3& p : planes)
    if (!p.allFinite()) return std::nullopt;
  ConvexHull dual;
  try {
    dual = compute_convex_hull(planes);
  } catch (const Error&) {
    return std::nullopt;  // the planes' points are flat: the polytope is unbounded
  }
  std::vector<Vec3> out;
  out.reserve(dual.faces.size());
  for (const HullFace& facet : dual.faces) {
    // The origin must be strictly inside the dual hull, or the polytope is unbounded in some direction.
    if (!(facet.offset > 1e-12 * facet.normal.norm())) return std::nullopt;
    out.push_back(facet.normal / facet.offset);
  }
  return out;
}

std::vector<int> plane_indices(const ConvexHull& hull, const std::vector<Vec3>& planes) {
  std::vector<int> out(hull.faces.size(), -1);
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    double best = 1 - 1e-6;
    for (std::size_t i = 0; i < planes.size(); ++i) {
      const double c = hull.faces[f].normal.dot(planes[i].normalized());
      if (c > best) best = c, out[f] = static_cast<int>(i);
    }
  }
  return out;
}

Eigen::MatrixXd plane_columns(const Eigen::MatrixXd& vertex_columns, const ConvexHull& hull,
                              const Vec3& origin, const std::vector<Vec3>& planes) {
  Eigen::MatrixXd out =
      Eigen::MatrixXd::Zero(vertex_columns.rows(), 3 * static_cast<Eigen::Index>(planes.size()));
  const std::vector<int> plane_of = plane_indices(hull, planes);
  std::vector<std::vector<int>> faces_at(hull.vertices.size());
  for (std::size_t f = 0; f < hull.faces.size(); ++f)
    for (const int v : hull.faces[f].loop)
      if (plane_of[f] >= 0) faces_at[static_cast<std::size_t>(v)].push_back(plane_of[f]);
  for (std::size_t j = 0; j < hull.vertices.size(); ++j) {
    const std::vector<int>& at = faces_at[j];
    // The three planes with the largest |det| of their normals.
    double best = 0;
    int pick[3] = {-1, -1, -1};
    for (std::size_t a = 0; a < at.size(); ++a)
      for (std::size_t b = a + 1; b < at.size(); ++b)
        for (std::size_t c = b + 1; c < at.size(); ++c) {
          const auto ua = planes[static_cast<std::size_t>(at[a])].normalized();
          const auto ub = planes[static_cast<std::size_t>(at[b])].normalized();
          const auto uc = planes[static_cast<std::size_t>(at[c])].normalized();
          const double det = std::abs(ua.dot(ub.cross(uc)));
          if (det > best) best = det, pick[0] = at[a], pick[1] = at[b], pick[2] = at[c];
        }
    if (pick[0] < 0) continue;  // fewer than three planes known: the vertex does not move with them
    Mat3 a;
    for (int r = 0; r < 3; ++r) a.row(r) = planes[static_cast<std::size_t>(pick[r])].transpose();
    const Mat3 inverse = a.inverse();
    const Vec3 v = hull.vertices[j] - origin;  // A v = 1
    const auto col = 3 * static_cast<Eigen::Index>(j);
    for (int r = 0; r < 3; ++r) {
      // ∂v/∂p_r = −A⁻¹ e_r vᵀ.
      const Mat3 dv = -inverse.col(r) * v.transpose();
      out.middleCols<3>(3 * pick[r]) += vertex_columns.middleCols<3>(col) * dv;
    }
  }
  return out;
}

}  // namespace repose::detail
