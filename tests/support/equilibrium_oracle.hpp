// Independent checks of a rest pose, written in the test from the mesh vertices alone: no call into the
// library's hull, stability margins or contact logic, so a bug there cannot hide itself.
//
// A rest is a static equilibrium when the vertices on the wall (within 1e-9·L) span a polygon that holds the
// centre of mass's projection strictly inside, no vertex is below the wall, and the pose is the exact rest
// pose of that face: its plane (fitted here through the supporting vertices) is the wall, to 1e-9.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <repose/geometry/types.hpp>
#include <string>
#include <vector>

namespace repose::oracle {

struct Point2 {
  double x = 0, y = 0;
};

inline double cross(const Point2& o, const Point2& a, const Point2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

/// Andrew's monotone chain, counter-clockwise, collinear points dropped.
inline std::vector<Point2> convex_hull(std::vector<Point2> p) {
  std::sort(p.begin(), p.end(),
            [](const Point2& a, const Point2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (p.size() < 3) return p;
  std::vector<Point2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

/// Smallest signed distance from `g` to the edges of the CCW polygon `poly` (positive: inside).
inline double inside_margin(const std::vector<Point2>& poly, const Point2& g) {
  if (poly.size() < 3) return -INFINITY;
  double margin = INFINITY;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2& a = poly[i];
    const Point2& b = poly[(i + 1) % poly.size()];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    margin = std::min(margin, cross(a, b, g) / len);
  }
  return margin;
}

struct RestCheck {
  int supporting = 0;            ///< vertices within 1e-9·L of the wall
  double lowest = 0;             ///< lowest vertex height / L
  double margin = -INFINITY;     ///< centre of mass inside the support polygon (length; > 0 inside)
  double plane_tilt = INFINITY;  ///< angle (rad) between the supporting vertices' plane and the wall
  std::string problem;           ///< empty if the pose is an exact static equilibrium
};

/// Checks a pose (body → world rotation `q`, centre of mass `com`) of a body whose vertices (body frame,
/// centre of mass at the origin) are `vertices`, L = `length`.
inline RestCheck check_rest(const std::vector<Vec3>& vertices, const Quat& q, const Vec3& com,
                            double length) {
  RestCheck c;
  const double touch = 1e-9 * length;
  const Mat3 R = q.normalized().toRotationMatrix();
  std::vector<Vec3> on_wall;
  double lowest = INFINITY;
  for (const Vec3& v : vertices) {
    const Vec3 w = com + R * v;
    lowest = std::min(lowest, w.z());
    if (std::abs(w.z()) <= touch) on_wall.push_back(w);
  }
  c.lowest = lowest / length;
  c.supporting = static_cast<int>(on_wall.size());
  std::vector<Point2> footprint;
  for (const Vec3& w : on_wall) footprint.push_back({w.x(), w.y()});
  const std::vector<Point2> poly = convex_hull(footprint);
  c.margin = inside_margin(poly, {com.x(), com.y()});
  // The supporting plane: the normal of the largest triangle of the support polygon's corners.
  double best = 0;
  for (std::size_t i = 0; i < on_wall.size(); ++i)
    for (std::size_t j = i + 1; j < on_wall.size(); ++j)
      for (std::size_t k = j + 1; k < on_wall.size() && k < i + 64; ++k) {
        const Vec3 n = (on_wall[j] - on_wall[i]).cross(on_wall[k] - on_wall[i]);
        if (n.norm() > best) {
          best = n.norm();
          c.plane_tilt = std::acos(std::min(1.0, std::abs(n.z()) / n.norm()));
        }
      }
  if (lowest < -touch)
    c.problem = "a vertex is " + std::to_string(-lowest / length) + " L below the wall";
  else if (poly.size() < 3)
    c.problem = "only " + std::to_string(c.supporting) + " vertices on the wall, not a support polygon";
  else if (!(c.margin > 0))
    c.problem =
        "the centre of mass is " + std::to_string(-c.margin / length) + " L outside the support polygon";
  else if (c.plane_tilt > 1e-9)
    c.problem = "the supporting face is tilted " + std::to_string(c.plane_tilt) + " rad from the wall";
  return c;
}

}  // namespace repose::oracle

namespace repose::oracle {

/// Whether a solid with its centre of mass at the origin stands on the planar convex face `corners` (3-D
/// points in order around the face, outward normal `normal`): the origin's projection on the face plane lies
/// strictly inside the polygon. Returns the signed distance from the projection to the nearest edge
/// (positive inside), computed from the corners alone.
inline double face_margin(const std::vector<Vec3>& corners, const Vec3& normal) {
  const Vec3 n = normal.normalized();
  const Vec3 p = n * n.dot(corners[0]);  // the origin's projection on the face plane
  double margin = INFINITY;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Vec3& a = corners[i];
    const Vec3& b = corners[(i + 1) % corners.size()];
    // Inward direction of edge a→b in the face plane (corners counter-clockwise seen from outside).
    const Vec3 inward = n.cross(b - a).normalized();
    margin = std::min(margin, (p - a).dot(inward));
  }
  return margin;
}

/// The smallest distance from the origin (the centre of mass) to the plane of a triangle of a closed convex
/// mesh: the centre-of-mass height of its lowest rest.
inline double lowest_rest_height(const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles) {
  double lowest = INFINITY;
  for (const auto& t : triangles) {
    const Vec3 a = vertices[t[0]], b = vertices[t[1]], c = vertices[t[2]];
    lowest = std::min(lowest, std::abs((b - a).cross(c - a).normalized().dot(a)));
  }
  return lowest;
}

}  // namespace repose::oracle
