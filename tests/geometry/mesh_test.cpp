#include "repose/geometry/mesh.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "repose/error.hpp"

namespace repose {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// Unit cube [0,1]^3, vertex i at (bit 0, bit 1, bit 2) of i, triangles counter-clockwise from outside.
TriangleMesh unit_cube() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

// Every triangle with its own three vertex records, as STL stores them.
TriangleMesh soup(const TriangleMesh& m) {
  TriangleMesh out;
  for (const Triangle& t : m.triangles) {
    const auto base = static_cast<std::int32_t>(out.vertices.size());
    for (const std::int32_t i : t) out.vertices.push_back(m.vertices[i]);
    out.triangles.push_back({base, base + 1, base + 2});
  }
  return out;
}

TriangleMesh transformed(TriangleMesh m, double scale, const Vec3& offset) {
  for (Vec3& v : m.vertices) v = scale * v + offset;
  return m;
}

// The message of the repose::Error that validate_mesh throws ("" if it does not throw).
// A latitude-longitude sphere of radius 1: nu meridians, nv − 1 rings between the poles, outward winding.
TriangleMesh lat_long_sphere(int nu, int nv) {
  const double pi = std::acos(-1.0);
  TriangleMesh sphere;
  sphere.vertices.emplace_back(0, 0, 1);
  for (int k = 1; k < nv; ++k)
    for (int i = 0; i < nu; ++i) {
      const double theta = pi * k / nv, phi = 2 * pi * i / nu;
      sphere.vertices.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                   std::cos(theta));
    }
  sphere.vertices.emplace_back(0, 0, -1);
  const std::int32_t south = nu * (nv - 1) + 1;
  auto ring = [&](int k, int i) { return 1 + (k - 1) * nu + i % nu; };
  for (int i = 0; i < nu; ++i) {
    sphere.triangles.push_back({0, ring(1, i), ring(1, i + 1)});
    sphere.triangles.push_back({south, ring(nv - 1, i + 1), ring(nv - 1, i)});
    for (int k = 1; k < nv - 1; ++k) {
      sphere.triangles.push_back({ring(k, i), ring(k + 1, i), ring(k + 1, i + 1)});
      sphere.triangles.push_back({ring(k, i), ring(k + 1, i + 1), ring(k, i + 1)});
    }
  }
  return sphere;
}

std::string validation_error(TriangleMesh m, const std::string& name = "part.stl") {
  try {
    validate_mesh(m, name);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(MeshValidate, ValidCubeNeedsNoRepair) {
  TriangleMesh m = unit_cube();
  const MeshReport r = validate_mesh(m, "cube");
  EXPECT_EQ(r.input_vertices, 8);
  EXPECT_EQ(r.input_triangles, 12);
  EXPECT_EQ(r.welded_vertices, 0);
  EXPECT_EQ(r.degenerate_triangles, 0);
  EXPECT_EQ(r.unused_vertices, 0);
  EXPECT_FALSE(r.flipped);
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_EQ(m.vertices, unit_cube().vertices);
  EXPECT_EQ(m.triangles, unit_cube().triangles);
  EXPECT_DOUBLE_EQ(signed_volume(m), 1.0);
}

TEST(MeshValidate, EmptyMeshIsRejected) {
  EXPECT_EQ(validation_error(TriangleMesh{}), "part.stl: empty mesh (no triangles)");
  TriangleMesh no_triangles = unit_cube();
  no_triangles.triangles.clear();
  EXPECT_EQ(validation_error(no_triangles), "part.stl: empty mesh (no triangles)");
  TriangleMesh no_vertices = unit_cube();
  no_vertices.vertices.clear();
  EXPECT_EQ(validation_error(no_vertices), "part.stl: empty mesh (no triangles)");
}

TEST(MeshValidate, IndexOutOfRangeIsRejected) {
  TriangleMesh m = unit_cube();
  m.triangles[3][1] = 8;
  EXPECT_EQ(validation_error(m), "part.stl: in triangle 3, vertex index 8 does not exist (8 vertices)");
  m.triangles[3][1] = -1;
  EXPECT_EQ(validation_error(m), "part.stl: in triangle 3, vertex index -1 does not exist (8 vertices)");
}

TEST(MeshValidate, NonFiniteCoordinateIsRejected) {
  TriangleMesh m = unit_cube();
  m.vertices[2].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(validation_error(m), "part.stl: vertex 2 has a non-finite coordinate");
  m = unit_cube();
  m.vertices[5].z() = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(validation_error(m), "part.stl: vertex 5 has a non-finite coordinate");
}

// Found by fuzz_shape_spec: a 1e300 cube overflowed the bounding-box diagonal to inf, and the weld grid's
// cell index became undefined behaviour. Sizes whose mass properties would overflow are rejected.
TEST(MeshValidate, SizeOutOfRangeIsRejected) {
  EXPECT_EQ(validation_error(transformed(unit_cube(), 1e300, Vec3::Zero())),
            "part.stl: size out of range (bounding-box diagonal inf; must be in [1e-50, 1e50])");
  EXPECT_EQ(validation_error(transformed(unit_cube(), 1e-60, Vec3::Zero())),
            "part.stl: size out of range (bounding-box diagonal 1.73e-60; must be in [1e-50, 1e50])");
  EXPECT_EQ(validation_error(transformed(unit_cube(), 1e40, Vec3::Zero())), "");
  EXPECT_EQ(validation_error(transformed(unit_cube(), 1e51, Vec3::Zero())),
            "part.stl: size out of range (bounding-box diagonal 1.73e+51; must be in [1e-50, 1e50])");
  EXPECT_EQ(validation_error(transformed(unit_cube(), 1e-40, Vec3::Zero())), "");
}

TEST(MeshValidate, WeldsDuplicateVertices) {
  TriangleMesh m = soup(unit_cube());
  const MeshReport r = validate_mesh(m, "soup");
  EXPECT_EQ(r.input_vertices, 36);
  EXPECT_EQ(r.welded_vertices, 28);
  EXPECT_EQ(r.unused_vertices, 0);
  EXPECT_THAT(r.warnings, ElementsAre("welded 28 duplicate vertices"));
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_DOUBLE_EQ(signed_volume(m), 1.0);
}

TEST(MeshValidate, WeldToleranceIsRelativeToSize) {
  // Copies 1e-12·D apart are the same vertex; 1e-6·D apart they are not, so the surface stays open.
  for (const double scale : {1.0, 5e-5, 1e4}) {
    TriangleMesh near = transformed(soup(unit_cube()), scale, Vec3::Zero());
    TriangleMesh far = near;
    for (std::size_t i = 0; i < near.vertices.size(); i += 3) {
      near.vertices[i].x() += 1e-12 * scale;
      far.vertices[i].x() += 1e-6 * scale;
    }
    EXPECT_EQ(validate_mesh(near, "near").welded_vertices, 28) << scale;
    EXPECT_THAT(validation_error(far), HasSubstr("open surface")) << scale;
  }
}

TEST(MeshValidate, JitteredCopiesWeldAcrossGridCells) {
  // A latitude-longitude sphere as a soup, every vertex record moved by its own pseudo-random offset of at
  // most 0.25·tol in each coordinate (tol = 1e-10·D, the weld distance; D = the bounding-box diagonal, 2√3):
  // copies of one vertex are then within 0.5·√3·tol ≈ 0.87·tol of each other and must weld, whichever side
  // of a weld-grid cell boundary (cells 4·tol wide) each falls on; distinct vertices are ≥ 0.07 apart. Any
  // copy left unwelded would leave the surface open.
  const int nu = 40, nv = 20;
  const TriangleMesh sphere = lat_long_sphere(nu, nv);
  TriangleMesh m = soup(sphere);
  const double tol = 1e-10 * 2 * std::sqrt(3.0);
  std::uint64_t state = 12345;
  auto uniform = [&] {  // a 64-bit LCG (Knuth's MMIX constants), top 53 bits: [0, 1)
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1p-53;
  };
  for (Vec3& p : m.vertices)
    for (int c = 0; c < 3; ++c) p[c] += 0.25 * tol * (2 * uniform() - 1);
  const MeshReport r = validate_mesh(m, "jittered sphere");
  EXPECT_EQ(m.vertices.size(), sphere.vertices.size());
  EXPECT_EQ(r.welded_vertices, static_cast<int>(3 * sphere.triangles.size() - sphere.vertices.size()));
}

TEST(MeshValidate, RemovesDegenerateTrianglesAndUnusedVertices) {
  TriangleMesh m = unit_cube();
  m.vertices.emplace_back(0, 0, 0);    // 8: duplicate of vertex 0
  m.vertices.emplace_back(2, 2, 2);    // 9..11: collinear
  m.vertices.emplace_back(3, 3, 3);    //
  m.vertices.emplace_back(4, 4, 4);    //
  m.vertices.emplace_back(-5, 7, 9);   // 12: referenced by nothing
  m.triangles.push_back({0, 0, 1});    // repeated index
  m.triangles.push_back({8, 1, 0});    // repeated index after welding
  m.triangles.push_back({9, 10, 11});  // zero area
  const MeshReport r = validate_mesh(m, "cube");
  EXPECT_EQ(r.input_vertices, 13);
  EXPECT_EQ(r.input_triangles, 15);
  EXPECT_EQ(r.welded_vertices, 1);
  EXPECT_EQ(r.degenerate_triangles, 3);
  EXPECT_EQ(r.unused_vertices, 4);
  EXPECT_THAT(r.warnings,
              ElementsAre("welded 1 duplicate vertex", "removed 3 degenerate triangles (zero area)",
                          "removed 4 unused vertices"));
  // What remains is the cube, in its original order.
  EXPECT_EQ(m.vertices, unit_cube().vertices);
  EXPECT_EQ(m.triangles, unit_cube().triangles);
}

// The area threshold of a degenerate triangle is 1e-14·D² (mesh.hpp; D = √3 for the unit cube): a stray
// sliver inside the cube of area 0.75× that (base 0.6, height 2.5·1e-14·D²/0.6 = 7.5e-14) is removed, one of
// 1.5× is a real triangle, which leaves the surface open.
TEST(MeshValidate, TheDegenerateAreaThresholdIsOneE14TimesTheDiagonalSquared) {
  const double threshold = 1e-14 * 3.0;  // D² = 3
  for (const double fraction : {0.75, 1.5}) {
    TriangleMesh m = unit_cube();
    const double h = 2 * fraction * threshold / 0.6;  // area ½·0.6·h
    m.vertices.emplace_back(0.2, 0.2, 0.5);
    m.vertices.emplace_back(0.8, 0.2, 0.5);
    m.vertices.emplace_back(0.5, 0.2 + h, 0.5);
    m.triangles.push_back({8, 9, 10});
    if (fraction < 1) {
      const MeshReport r = validate_mesh(m, "cube");
      EXPECT_EQ(r.degenerate_triangles, 1);
      EXPECT_EQ(m.triangles, unit_cube().triangles);
    } else {
      EXPECT_THAT(validation_error(m), HasSubstr("open surface"));
    }
  }
}

TEST(MeshValidate, AllTrianglesDegenerateIsRejected) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  m.triangles = {{0, 1, 2}, {0, 2, 1}};
  EXPECT_EQ(validation_error(m), "part.stl: all 2 triangles are degenerate (zero area)");
  m.vertices = {Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)};
  EXPECT_THAT(validation_error(m), HasSubstr("part.stl: zero volume"));
}

TEST(MeshValidate, OpenSurfaceIsRejected) {
  TriangleMesh m = unit_cube();
  m.triangles.erase(m.triangles.begin(), m.triangles.begin() + 2);  // the z = 0 face
  EXPECT_EQ(validation_error(m),
            "part.stl: open surface: 4 boundary edges (the mesh must be a closed solid)");
}

TEST(MeshValidate, FailureLeavesMeshUnchanged) {
  TriangleMesh m = soup(unit_cube());
  m.triangles.pop_back();
  const TriangleMesh before = m;
  EXPECT_THROW(validate_mesh(m, "open"), Error);
  EXPECT_EQ(m.vertices, before.vertices);
  EXPECT_EQ(m.triangles, before.triangles);
}

TEST(MeshValidate, NonManifoldEdgeIsRejected) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  EXPECT_EQ(validation_error(m), "part.stl: non-manifold surface: 1 edges shared by more than two triangles");
}

TEST(MeshValidate, InconsistentWindingIsRejected) {
  TriangleMesh m = unit_cube();
  std::swap(m.triangles[5][0], m.triangles[5][1]);
  EXPECT_EQ(validation_error(m),
            "part.stl: inconsistent winding: 3 edges whose two triangles face opposite ways");
}

TEST(MeshValidate, FlatClosedSurfaceHasZeroVolume) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  m.triangles = {{0, 1, 2}, {0, 2, 1}};
  EXPECT_EQ(validation_error(m), "part.stl: zero volume");
}

TEST(MeshValidate, InvertedSurfaceIsFlipped) {
  TriangleMesh m = unit_cube();
  for (Triangle& t : m.triangles) std::swap(t[0], t[2]);
  EXPECT_DOUBLE_EQ(signed_volume(m), -1.0);
  const MeshReport r = validate_mesh(m, "cube");
  EXPECT_TRUE(r.flipped);
  EXPECT_THAT(r.warnings, ElementsAre("inverted winding (negative volume): all triangles flipped"));
  EXPECT_DOUBLE_EQ(signed_volume(m), 1.0);
}

TEST(MeshValidate, TinyParticleFarFromOriginLoads) {
  // A 50 µm cube in metres, 1 m from the origin: every tolerance scales with the particle.
  const double size = 5e-5;
  TriangleMesh m = transformed(soup(unit_cube()), size, Vec3(1.0, -1.0, 0.5));
  const MeshReport r = validate_mesh(m, "tiny");
  EXPECT_EQ(r.welded_vertices, 28);
  EXPECT_EQ(r.degenerate_triangles, 0);
  EXPECT_FALSE(r.flipped);
  // Coordinates of ~1 m have an ulp of 2.2e-16 m = 4.4e-12·size: measured 1.9e-12 relative; 2e-11 is 10×.
  EXPECT_NEAR(signed_volume(m), size * size * size, 2e-11 * size * size * size);
}

TEST(MeshValidate, LargeSoupIsWeldedQuickly) {
  // A latitude-longitude sphere as a soup of 2·nu·(nv-1) triangles (about 120k vertex records): quadratic
  // welding would take minutes.
  const int nu = 200, nv = 100;
  const TriangleMesh sphere = lat_long_sphere(nu, nv);
  const double pi = std::acos(-1.0);
  TriangleMesh m = soup(sphere);
  const MeshReport r = validate_mesh(m, "sphere");
  EXPECT_EQ(m.vertices.size(), sphere.vertices.size());
  EXPECT_EQ(r.welded_vertices, static_cast<int>(3 * sphere.triangles.size() - sphere.vertices.size()));
  EXPECT_EQ(r.degenerate_triangles, 0);
  EXPECT_FALSE(r.flipped);
  // Exact volume of this polyhedron: cut at the ring heights, each slab is a frustum of a regular nu-gon
  // pyramid (circumradius linear in z), area A0·r² with A0 = nu/2·sin(2π/nu). Round-off over 40,000
  // triangles: measured 4e-16 relative, 1e-12 is a round-off margin. It is 1.7e-3 below 4π/3.
  const double a0 = nu / 2.0 * std::sin(2 * pi / nu);
  double exact = 0;
  for (int k = 0; k < nv; ++k) {
    const double t0 = pi * k / nv, t1 = pi * (k + 1) / nv;
    const double r0 = std::sin(t0), r1 = std::sin(t1);
    exact += a0 * (std::cos(t0) - std::cos(t1)) * (r0 * r0 + r0 * r1 + r1 * r1) / 3;
  }
  EXPECT_NEAR(signed_volume(m), exact, 1e-12 * exact);
  EXPECT_LT(exact, 4.0 / 3.0 * pi);
}

TEST(MeshSignedVolume, SignFollowsWinding) {
  EXPECT_DOUBLE_EQ(signed_volume(transformed(unit_cube(), 2.0, Vec3(10, 20, 30))), 8.0);
  EXPECT_EQ(signed_volume(TriangleMesh{}), 0.0);
}

}  // namespace
}  // namespace repose
