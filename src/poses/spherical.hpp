// Small pieces of spherical geometry for the Gauss map: points on great-circle arcs by their chord
// parameter, half-space clips of arcs and convex spherical polygons, and spherical areas.
#pragma once

#include <vector>

#include "repose/geometry/types.hpp"

namespace repose::detail {

// The unit vector along x + t(y − x), t clamped to [0, 1] (the ends exactly).
Vec3 chord_point(const Vec3& x, const Vec3& y, double t);
// Chord parameter in [0, 1] where the plane through the origin with normal n crosses the segment x → y.
double cut(const Vec3& n, const Vec3& x, const Vec3& y);
// Restricts [lo, hi] to the part of segment x → y with n·d ≥ 0 (empty: hi < lo).
void clip_interval(const Vec3& n, const Vec3& x, const Vec3& y, double& lo, double& hi);
// The part of a convex spherical polygon with n·d ≥ 0 (Sutherland–Hodgman; edges are shorter than π).
void clip_polygon(const std::vector<Vec3>& polygon, const Vec3& n, std::vector<Vec3>& out);
// Area (steradian) of a convex spherical polygon.
double spherical_area(const std::vector<Vec3>& polygon);

}  // namespace repose::detail
