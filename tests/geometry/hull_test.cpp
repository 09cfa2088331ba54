// Tests of compute_convex_hull.
//
// Tolerances: hull faces are built from input coordinates of size O(L) (L = 1 here), so plane offsets, areas
// and centroids carry round-off of a few ulps of L. Measured: ≤ 6.7e-16 on normals, areas, offsets and
// centroids, ≤ 4.4e-15 between the two volume integrals. kTol = 1e-12 (·L or relative) is a round-off margin,
// not an error estimate: every value checked is an exact closed form, and a real error (a missing vertex, a
// wrong face) changes results by O(L).
#include "repose/geometry/hull.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "repose/error.hpp"
#include "repose/geometry/mass.hpp"
#include "repose/geometry/shapes.hpp"

namespace repose {
namespace {

constexpr double kTol = 1e-12;

double hull_volume_by_fans(const ConvexHull& hull) {
  // Triangulate every face polygon as a fan and integrate exactly (independent of face centroids/offsets).
  TriangleMesh mesh;
  mesh.vertices = hull.vertices;
  for (const HullFace& face : hull.faces) {
    for (std::size_t k = 1; k + 1 < face.loop.size(); ++k) {
      mesh.triangles.push_back({face.loop[0], face.loop[k], face.loop[k + 1]});
    }
  }
  return compute_mass_properties(mesh, 1.0).volume;
}

// Properties every hull must have, whatever the input. `tol` is the absolute length tolerance (the particles
// here have L ~ 1, so it also serves, times L², for volumes).
void check_hull(const ConvexHull& hull, const std::vector<Vec3>& points, double tol = kTol) {
  ASSERT_EQ(hull.vertices.size(), hull.source_index.size());
  for (std::size_t i = 0; i < hull.vertices.size(); ++i) {
    ASSERT_GE(hull.source_index[i], 0);
    ASSERT_LT(static_cast<std::size_t>(hull.source_index[i]), points.size());
    EXPECT_EQ(hull.vertices[i], points[static_cast<std::size_t>(hull.source_index[i])]);
  }
  double divergence_volume = 0;
  for (const HullFace& face : hull.faces) {
    ASSERT_GE(face.loop.size(), 3u);
    EXPECT_NEAR(face.normal.norm(), 1.0, kTol);
    EXPECT_GT(face.area, 0);
    // Vertices on the face plane; loop counter-clockwise seen from outside (each corner turns left).
    const std::size_t n = face.loop.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3& a = hull.vertices[static_cast<std::size_t>(face.loop[k])];
      const Vec3& b = hull.vertices[static_cast<std::size_t>(face.loop[(k + 1) % n])];
      const Vec3& c = hull.vertices[static_cast<std::size_t>(face.loop[(k + 2) % n])];
      EXPECT_NEAR(face.normal.dot(a), face.offset, tol);
      EXPECT_GT(face.normal.dot((b - a).cross(c - b)), 0) << "corner " << k << " of a face is not CCW";
    }
    EXPECT_NEAR(face.normal.dot(face.centroid), face.offset, tol);
    // Every input point is on the inner side of every face.
    for (const Vec3& p : points) EXPECT_LE(face.normal.dot(p), face.offset + tol);
    divergence_volume += face.area * face.normal.dot(face.centroid) / 3.0;
  }
  EXPECT_NEAR(divergence_volume, hull_volume_by_fans(hull), tol);
}

TEST(ConvexHull, Cube) {
  const TriangleMesh mesh = make_shape("box:x=2,y=2,z=2");
  const ConvexHull hull = compute_convex_hull(mesh.vertices);
  check_hull(hull, mesh.vertices);
  EXPECT_EQ(hull.vertices.size(), 8u);
  ASSERT_EQ(hull.faces.size(), 6u);
  int axes_seen = 0;
  for (const HullFace& face : hull.faces) {
    EXPECT_EQ(face.loop.size(), 4u);
    EXPECT_NEAR(face.area, 4.0, kTol);
    EXPECT_NEAR(face.offset, 1.0, kTol);
    EXPECT_NEAR(face.normal.cwiseAbs().maxCoeff(), 1.0, kTol);  // ±x, ±y or ±z
    Eigen::Index axis = 0;
    face.normal.cwiseAbs().maxCoeff(&axis);
    axes_seen |= 1 << (2 * axis + (face.normal[axis] > 0 ? 1 : 0));
    EXPECT_LT((face.centroid - face.normal).norm(), kTol);
  }
  EXPECT_EQ(axes_seen, 0b111111);
  EXPECT_NEAR(hull_volume_by_fans(hull), 8.0, kTol);
}

TEST(ConvexHull, PrismCapsAreMergedIntoSingleFaces) {
  const int n = 16;
  const double r = 0.8, h = 1.1;
  const TriangleMesh mesh = make_shape("cylinder:r=0.8,h=1.1,n=16");
  const ConvexHull hull = compute_convex_hull(mesh.vertices);
  check_hull(hull, mesh.vertices);
  EXPECT_EQ(hull.vertices.size(), 32u);  // the cap centres are not hull vertices
  ASSERT_EQ(hull.faces.size(), 18u);
  const double cap_area = n / 2.0 * r * r * std::sin(2 * std::numbers::pi / n);
  const double side_area = 2 * r * std::sin(std::numbers::pi / n) * h;
  int caps = 0;
  for (const HullFace& face : hull.faces) {
    if (std::abs(face.normal.z()) > 0.5) {
      ++caps;
      EXPECT_EQ(face.loop.size(), 16u);
      EXPECT_NEAR(face.area, cap_area, kTol);
      EXPECT_NEAR(std::abs(face.normal.z()), 1.0, kTol);
      EXPECT_NEAR(face.offset, h / 2, kTol);
    } else {
      EXPECT_EQ(face.loop.size(), 4u);
      EXPECT_NEAR(face.area, side_area, kTol);
    }
  }
  EXPECT_EQ(caps, 2);
  EXPECT_NEAR(hull_volume_by_fans(hull), compute_mass_properties(mesh, 1.0).volume, kTol);
}

TEST(ConvexHull, Tetrahedron) {
  const TriangleMesh mesh = make_shape("tetrahedron:edge=1");
  const ConvexHull hull = compute_convex_hull(mesh.vertices);
  check_hull(hull, mesh.vertices);
  EXPECT_EQ(hull.vertices.size(), 4u);
  EXPECT_EQ(hull.faces.size(), 4u);
  for (const HullFace& face : hull.faces) EXPECT_NEAR(face.area, std::sqrt(3.0) / 4, kTol);
  EXPECT_NEAR(hull_volume_by_fans(hull), 1 / (6 * std::sqrt(2.0)), kTol);
}

TEST(ConvexHull, EllipsoidKeepsEveryVertex) {
  // All vertices of a strictly convex surface are extreme points.
  const TriangleMesh mesh = make_shape("ellipsoid:a=1,b=0.6,c=0.3,n=10");
  const ConvexHull hull = compute_convex_hull(mesh.vertices);
  check_hull(hull, mesh.vertices);
  EXPECT_EQ(hull.vertices.size(), mesh.vertices.size());
  EXPECT_NEAR(hull_volume_by_fans(hull), compute_mass_properties(mesh, 1.0).volume, kTol);
}

TEST(ConvexHull, IrregularParticleFarFromOrigin) {
  TriangleMesh mesh = make_shape("irregular:seed=5");
  const ConvexHull near_hull = compute_convex_hull(mesh.vertices);
  check_hull(near_hull, mesh.vertices);
  EXPECT_LT(near_hull.vertices.size(), mesh.vertices.size());  // non-convex: some vertices are inside
  for (Vec3& p : mesh.vertices) p += Vec3(3e3, -2e3, 1e3);
  const ConvexHull far_hull = compute_convex_hull(mesh.vertices);
  // Coordinates of ~3.6e3 have an ulp of 4.5e-13: measured 9.1e-13 on plane offsets (2 ulps), 5.9e-14 on the
  // volume; 1e-11·L is 11× the worst.
  check_hull(far_hull, mesh.vertices, 1e-11);
  EXPECT_EQ(far_hull.source_index, near_hull.source_index);
}

TEST(ConvexHull, SupportVertex) {
  const TriangleMesh mesh = make_shape("irregular:seed=9");
  const ConvexHull hull = compute_convex_hull(mesh.vertices);
  const Mat3 rot = Eigen::AngleAxisd(1.1, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (int k = 0; k < 50; ++k) {
    const Vec3 dir =
        rot * Vec3(std::cos(0.37 * k), std::sin(0.37 * k) * std::cos(0.11 * k), std::sin(0.11 * k));
    const int s = hull.support_vertex(dir);
    ASSERT_GE(s, 0);
    double best = -INFINITY;
    for (const Vec3& p : mesh.vertices) best = std::max(best, dir.dot(p));
    EXPECT_EQ(dir.dot(hull.vertices[static_cast<std::size_t>(s)]), best);
  }
  EXPECT_EQ(ConvexHull{}.support_vertex(Vec3::UnitZ()), -1);
}

// max − min of direction·v over the hull's vertices.
double hull_extent(const ConvexHull& hull, const Vec3& dir) {
  double lo = INFINITY, hi = -INFINITY;
  for (const Vec3& p : hull.vertices) {
    lo = std::min(lo, dir.dot(p));
    hi = std::max(hi, dir.dot(p));
  }
  return hi - lo;
}

// The edge graph against Euler's formula V − E + F = 2 (a convex polytope with planar faces), and the
// walking queries against a scan of every vertex: the furthest vertex's value exactly (a plateau may give
// another vertex of the same value), the superlevel set exactly (as a set), from every kind of start.
TEST(ConvexHull, EdgeGraphWalksAgreeWithAScan) {
  for (const char* shape : {"box:x=1,y=2,z=3", "tetrahedron:edge=1", "cylinder:r=0.5,h=1,n=64",
                            "ellipsoid:a=1,b=0.7,c=0.5", "irregular:seed=9"}) {
    SCOPED_TRACE(shape);
    const ConvexHull hull = compute_convex_hull(make_shape(shape).vertices);
    const std::size_t nv = hull.vertices.size();
    ASSERT_EQ(hull.neighbor_offsets.size(), nv + 1);
    EXPECT_EQ(static_cast<std::size_t>(hull.neighbor_offsets.back()), hull.neighbor_list.size());
    std::size_t ends = 0;
    for (std::size_t v = 0; v < nv; ++v) {
      const auto around = hull.neighbors(static_cast<int>(v));
      ends += around.size();
      EXPECT_GE(around.size(), 3u);  // a polytope's vertex has at least three edges
      for (int n : around) {         // symmetric
        const auto back = hull.neighbors(n);
        EXPECT_EQ(std::count(back.begin(), back.end(), static_cast<int>(v)), 1);
      }
    }
    ASSERT_EQ(ends % 2, 0u);
    EXPECT_EQ(static_cast<long>(nv) - static_cast<long>(ends / 2) + static_cast<long>(hull.faces.size()), 2);

    std::vector<char> visited(nv, 0);
    for (int k = 0; k < 40; ++k) {
      const Vec3 dir(std::cos(0.37 * k) * std::cos(0.23 * k), std::sin(0.37 * k) * std::cos(0.23 * k),
                     std::sin(0.23 * k));
      double best = -INFINITY;
      for (const Vec3& p : hull.vertices) best = std::max(best, dir.dot(p));
      const int start = static_cast<int>((7919u * static_cast<unsigned>(k)) % nv);
      const int top = hull.support_vertex_from(dir, start);
      EXPECT_EQ(dir.dot(hull.vertices[static_cast<std::size_t>(top)]), best);
      // Levels from the top down to below the bottom: the walk's set is the scan's set.
      for (double fraction : {0.0, 0.01, 0.2, 0.7, 2.5}) {
        const double level = best - fraction * hull_extent(hull, dir);
        std::vector<int> walked;
        hull.vertices_at_least(dir, level, top, walked, visited);
        std::vector<int> scanned;
        for (std::size_t v = 0; v < nv; ++v)
          if (dir.dot(hull.vertices[v]) >= level) scanned.push_back(static_cast<int>(v));
        std::sort(walked.begin(), walked.end());
        EXPECT_EQ(walked, scanned) << "direction " << k << ", fraction " << fraction;
      }
      EXPECT_EQ(std::count(visited.begin(), visited.end(), 1), 0);  // scratch left clean
    }
  }
}

TEST(ConvexHull, FaceCentroidsAreAreaCentroids) {
  // A prism over the trapezoid (0,0), (3,0), (2,1), (0,1), height 1. The caps' area centroid, by hand:
  // area 2.5, ∫x dA = ∫₀¹ (3 − y)²/2 dy = 19/6, ∫y dA = ∫₀¹ y(3 − y) dy = 7/6, so (19/15, 7/15); not the
  // vertex mean (1.25, 0.5). Exact up to round-off (1e-14).
  std::vector<Vec3> points;
  for (double z : {0.0, 1.0})
    for (const auto& [x, y] : std::vector<std::pair<double, double>>{{0, 0}, {3, 0}, {2, 1}, {0, 1}})
      points.emplace_back(x, y, z);
  const ConvexHull hull = compute_convex_hull(points);
  int caps = 0;
  for (const HullFace& face : hull.faces) {
    if (std::abs(face.normal.z()) < 0.5) continue;
    ++caps;
    EXPECT_NEAR(face.area, 2.5, 1e-14);
    EXPECT_LT((face.centroid - Vec3(19.0 / 15, 7.0 / 15, face.normal.z() > 0 ? 1 : 0)).norm(), 1e-14);
  }
  EXPECT_EQ(caps, 2);
}

TEST(ConvexHull, RejectsDegenerateInput) {
  const auto expect_error = [](const std::vector<Vec3>& points, const std::string& what,
                               const std::string& expected = "") {
    try {
      compute_convex_hull(points);
      ADD_FAILURE() << "no error for " << what;
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("convex hull: ", 0), 0u) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_NE(message.find(expected), std::string::npos) << message;
    }
  };
  expect_error({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, "three points", "at least 4 points");
  expect_error({}, "no points");
  std::vector<Vec3> planar;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) planar.emplace_back(i, j, 0.5 * i - 0.25 * j);
  }
  // qhull's own diagnostic (its first line, with its QH code) follows, so a user can look it up.
  expect_error(planar, "coplanar points", "degenerate input (all points coplanar or collinear): QH");
  expect_error({Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(3, 3, 3), Vec3(4, 4, 4)},
               "collinear points", "degenerate input (all points coplanar or collinear): QH");
  expect_error(std::vector<Vec3>(6, Vec3(1, 2, 3)), "identical points", "degenerate");
  expect_error({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, NAN)}, "NaN");
}

TEST(ConvexHull, DuplicatePointsMapToOneSource) {
  std::vector<Vec3> points = make_shape("box:x=1,y=1,z=1").vertices;
  const std::vector<Vec3> copy = points;
  points.insert(points.end(), copy.begin(), copy.end());
  points.emplace_back(0, 0, 0);  // interior
  const ConvexHull hull = compute_convex_hull(points);
  check_hull(hull, points);
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.faces.size(), 6u);
}

}  // namespace
}  // namespace repose
