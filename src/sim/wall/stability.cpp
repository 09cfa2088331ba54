#include "stability.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

#include "../tolerances.hpp"

namespace repose::sim {

bool ray_hits_triangle(const Vec3& origin, const Vec3& dir, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a;
  const Vec3 e2 = c - a;
  const Vec3 p = dir.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) <= tol::kParallel) return false;  // ray parallel to the triangle's plane
  const double inv = 1.0 / det;
  const Vec3 s = origin - a;
  const double u = s.dot(p) * inv;
  const Vec3 q = s.cross(e1);
  const double v = dir.dot(q) * inv;
  const double t = e2.dot(q) * inv;
  const double edge = tol::kRayEdge;
  return u >= -edge && v >= -edge && u + v <= 1 + edge && t > 0;
}

namespace {
double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}
}  // namespace

namespace {
// Akl and Toussaint's heuristic: the points deep inside the quadrilateral of the extreme points in x and y
// (more than tol::kHullInteriorDepth·tol inside every edge) are neither on the hull nor within `tol` of a
// point on it, so the monotone chain below gives the same hull without them. On a fine mesh's band (thousands
// of points) it leaves the points near the boundary, and the sort is of those.
void drop_deep_interior(std::vector<Vec2>& pts, double tol) {
  if (pts.size() < tol::kHullFilterFrom) return;
  std::array<Vec2, 4> corner{pts[0], pts[0], pts[0], pts[0]};  // leftmost, lowest, rightmost, highest
  for (const Vec2& p : pts) {
    if (p.x() < corner[0].x()) corner[0] = p;
    if (p.y() < corner[1].y()) corner[1] = p;
    if (p.x() > corner[2].x()) corner[2] = p;
    if (p.y() > corner[3].y()) corner[3] = p;
  }
  const double depth = tol::kHullInteriorDepth * tol;
  std::array<Vec2, 4> normal;  // inward unit normals of the edges corner[i] → corner[i + 1] (zero: none)
  std::array<double, 4> offset{};
  int edges = 0;
  for (int i = 0; i < 4; ++i) {
    const Vec2 e = corner[static_cast<std::size_t>((i + 1) % 4)] - corner[static_cast<std::size_t>(i)];
    const double length = e.norm();
    normal[static_cast<std::size_t>(i)] = length > 0 ? Vec2(-e.y() / length, e.x() / length) : Vec2::Zero();
    offset[static_cast<std::size_t>(i)] =
        normal[static_cast<std::size_t>(i)].dot(corner[static_cast<std::size_t>(i)]);
    edges += length > 0;
  }
  if (edges < 3) return;
  const auto deep = [&](const Vec2& p) {
    for (std::size_t i = 0; i < 4; ++i)
      if (normal[i] != Vec2::Zero() && !(normal[i].dot(p) - offset[i] > depth)) return false;
    return true;
  };
  pts.erase(std::remove_if(pts.begin(), pts.end(), deep), pts.end());
}

// Andrew's monotone chain (convex_hull_2d).

std::vector<Vec2> monotone_chain(std::vector<Vec2> pts, double tol) {
  std::sort(pts.begin(), pts.end(),
            [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  std::vector<Vec2> unique;
  for (const Vec2& p : pts)
    if (unique.empty() || (p - unique.back()).norm() > tol) unique.push_back(p);
  if (unique.size() < 3) return unique;
  // Collinearity tolerance: an area of tol times the extent of the set.
  const double extent = (unique.back() - unique.front()).norm();
  const double area_tol = tol * std::max(extent, tol);
  std::vector<Vec2> hull(2 * unique.size());
  std::size_t k = 0;
  for (const Vec2& p : unique) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], p) <= area_tol) --k;
    hull[k++] = p;
  }
  for (std::size_t i = unique.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross2(hull[k - 2], hull[k - 1], unique[i]) <= area_tol) --k;
    hull[k++] = unique[i];
  }
  hull.resize(k - 1);
  if (hull.size() < 3) {  // all collinear: keep the two extreme points
    return {unique.front(), unique.back()};
  }
  return hull;
}
}  // namespace

std::vector<Vec2> convex_hull_2d(std::vector<Vec2> pts, double tol) {
#ifndef NDEBUG
  const std::vector<Vec2> all = pts;
#endif
  drop_deep_interior(pts, tol);
  std::vector<Vec2> hull = monotone_chain(std::move(pts), tol);
  assert(hull == monotone_chain(all, tol));  // the sanitizer build checks every filtered hull
  return hull;
}

namespace {
double segment_distance(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}
}  // namespace

double polygon_margin(const std::vector<Vec2>& hull, const Vec2& p) {
  if (hull.empty()) return -std::numeric_limits<double>::infinity();
  if (hull.size() == 1) return -(p - hull[0]).norm();
  if (hull.size() == 2) return -segment_distance(hull[0], hull[1], p);
  double inside = std::numeric_limits<double>::infinity();
  bool outside = false;
  double outside_dist = std::numeric_limits<double>::infinity();
  const Vec2* a = &hull.back();  // each edge a → b, the closing one first
  for (const Vec2& b : hull) {
    const Vec2 e = b - *a;
    const double signed_dist = (e.x() * (p.y() - a->y()) - e.y() * (p.x() - a->x())) / e.norm();
    if (signed_dist < 0) outside = true;
    inside = std::min(inside, signed_dist);
    outside_dist = std::min(outside_dist, segment_distance(*a, b, p));
    a = &b;
  }
  return outside ? -outside_dist : inside;
}

ClosestFeature closest_feature(const std::vector<Vec2>& hull, const Vec2& p) {
  ClosestFeature best;
  double best_dist = std::numeric_limits<double>::infinity();
  const std::size_t n = hull.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double d = (p - hull[i]).norm();
    if (d < best_dist) {
      best_dist = d;
      best = {static_cast<int>(i), -1};
    }
  }
  if (n < 2) return best;
  const std::size_t edges = n == 2 ? 1 : n;
  for (std::size_t i = 0; i < edges; ++i) {
    const Vec2& a = hull[i];
    const Vec2& b = hull[(i + 1) % n];
    const Vec2 ab = b - a;
    const double s = (p - a).dot(ab) / ab.squaredNorm();
    if (s <= 0 || s >= 1) continue;
    const double d = (p - (a + s * ab)).norm();
    if (d < best_dist) {
      best_dist = d;
      best = {static_cast<int>(i), static_cast<int>((i + 1) % n)};
    }
  }
  return best;
}

}  // namespace repose::sim
