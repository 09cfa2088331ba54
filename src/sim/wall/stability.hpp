// Internal: the geometric tests of section 2.4 (stability) in the wall plane.
#pragma once

#include <vector>

#include "repose/geometry/types.hpp"

namespace repose::sim {

/// Möller–Trumbore: does the ray origin + s·dir (s > 0) hit triangle (a, b, c)? Edges count as hits within a
/// relative barycentric tolerance of 1e-12, so a centre of mass exactly above an edge is "on" the face.
bool ray_hits_triangle(const Vec3& origin, const Vec3& dir, const Vec3& a, const Vec3& b, const Vec3& c);

/// Convex hull of 2-D points, counter-clockwise, without collinear points (Andrew's monotone chain).
/// Points closer than `tol` are merged.
std::vector<Vec2> convex_hull_2d(std::vector<Vec2> points, double tol);

/// Signed distance from `p` to the boundary of the convex polygon `hull` (CCW): positive inside. For a hull
/// of one or two points (a point or a segment) the result is minus the distance to it.
double polygon_margin(const std::vector<Vec2>& hull, const Vec2& p);

/// The feature of a convex polygon (or segment, or point) closest to an outside point `p`: the edge (i, i+1)
/// if p projects inside it, else vertex i (then j = −1).
struct ClosestFeature {
  int i = 0;
  int j = -1;
};
ClosestFeature closest_feature(const std::vector<Vec2>& hull, const Vec2& p);

}  // namespace repose::sim
