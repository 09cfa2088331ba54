// Tests of the built-in shapes and their spec strings.
//
// Tolerances: vertex coordinates are computed with a handful of operations on O(1) numbers, so positions and
// lengths are exact to a few ulps; 1e-12 (relative to the shape size) is a round-off margin that still
// catches any wrong formula. Measured: ≤ 5e-16 on positions and lengths, ≤ 9.4e-15 relative between two
// volume sums over the 25,000-triangle ellipsoid, ≤ 2.7e-15·size on centres of mass.
#include "repose/geometry/shapes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "repose/error.hpp"
#include "repose/geometry/hull.hpp"
#include "repose/geometry/mass.hpp"
#include "repose/geometry/mesh.hpp"

namespace repose {
namespace {

constexpr double kShapeTol = 1e-12;

double signed_volume_of(const TriangleMesh& mesh) {
  double six_v = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    six_v += a.dot(b.cross(c));
  }
  return six_v / 6;
}

// Closed, consistently oriented 2-manifold: every directed edge occurs exactly once and its reverse exactly
// once; indices in range; no degenerate triangle; no duplicate vertex; every vertex used.
void expect_closed_and_outward(const TriangleMesh& mesh, const std::string& spec) {
  SCOPED_TRACE(spec);
  std::map<std::pair<int, int>, int> directed;
  std::vector<int> used(mesh.vertices.size(), 0);
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(t[static_cast<std::size_t>(k)], 0);
      ASSERT_LT(static_cast<std::size_t>(t[static_cast<std::size_t>(k)]), mesh.vertices.size());
      ++used[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
      ++directed[{t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]}];
    }
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    EXPECT_GT((b - a).cross(c - a).norm(), 0);
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second;
    const auto reverse = directed.find({edge.second, edge.first});
    EXPECT_TRUE(reverse != directed.end() && reverse->second == 1)
        << "edge " << edge.first << "-" << edge.second << " has no matching reverse edge";
  }
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](int u) { return u > 0; }));
  std::vector<Vec3> sorted = mesh.vertices;
  std::sort(sorted.begin(), sorted.end(), [](const Vec3& p, const Vec3& q) {
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  });
  EXPECT_TRUE(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) << "duplicate vertex";
  const double volume = signed_volume_of(mesh);
  EXPECT_GT(volume, 0);
  // Euler characteristic of a sphere: V - E + F = 2.
  EXPECT_EQ(static_cast<long>(mesh.vertices.size()) - static_cast<long>(directed.size() / 2) +
                static_cast<long>(mesh.triangles.size()),
            2);
}

// For a shape that is star-shaped about its centre (all but irregular, which is star-shaped about a point
// near it): every triangle has positive signed volume seen from the origin.
void expect_every_triangle_outward(const TriangleMesh& mesh, const std::string& spec) {
  SCOPED_TRACE(spec);
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    EXPECT_GT(a.dot(b.cross(c)), 0);
  }
}

TEST(Shapes, AllShapesAreClosedOutwardAndCentred) {
  for (const std::string spec :
       {"box:x=1,y=2,z=3", "cylinder:r=0.67,h=0.67", "cylinder:r=1,h=0.1,n=3", "cylinder:r=2,h=5,n=1000",
        "ellipsoid:a=1,b=0.6,c=0.3", "ellipsoid:a=1,b=1,c=1,n=1", "ellipsoid:a=3,b=2,c=1,n=37",
        "tetrahedron:edge=2.5", "irregular:seed=1", "irregular:seed=2,size=3,n=1", "irregular:seed=3,n=12"}) {
    const TriangleMesh mesh = make_shape(spec);
    expect_closed_and_outward(mesh, spec);
    if (spec.rfind("irregular", 0) != 0) expect_every_triangle_outward(mesh, spec);
    // The library's own validation accepts every shape as it is: nothing welded, dropped or flipped.
    TriangleMesh validated = mesh;
    const MeshReport report = validate_mesh(validated, spec);
    EXPECT_EQ(report.welded_vertices, 0) << spec;
    EXPECT_EQ(report.degenerate_triangles, 0) << spec;
    EXPECT_EQ(report.unused_vertices, 0) << spec;
    EXPECT_FALSE(report.flipped) << spec;
    EXPECT_TRUE(report.warnings.empty()) << spec;
    EXPECT_EQ(validated.vertices, mesh.vertices) << spec;
    EXPECT_EQ(validated.triangles, mesh.triangles) << spec;
    EXPECT_NEAR(signed_volume(mesh), signed_volume_of(mesh), kShapeTol * signed_volume_of(mesh)) << spec;
    const MassProperties mp = compute_mass_properties(mesh, 1.0);
    const double size = bounding_box(mesh.vertices).size().maxCoeff();
    EXPECT_LT(mp.center_of_mass.norm(), kShapeTol * size) << spec;
    EXPECT_NEAR(mp.volume, signed_volume_of(mesh), kShapeTol * mp.volume) << spec;
  }
}

TEST(Shapes, Box) {
  const TriangleMesh mesh = make_shape("box:x=1,y=2,z=3");
  EXPECT_EQ(mesh.vertices.size(), 8u);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  const Aabb box = bounding_box(mesh.vertices);
  EXPECT_EQ(box.min, Vec3(-0.5, -1, -1.5));
  EXPECT_EQ(box.max, Vec3(0.5, 1, 1.5));
  EXPECT_NEAR(signed_volume_of(mesh), 6.0, kShapeTol);
}

TEST(Shapes, Cylinder) {
  const TriangleMesh mesh = make_shape("cylinder:r=0.5,h=2");
  EXPECT_EQ(mesh.vertices.size(), 2u * 64 + 2);
  EXPECT_EQ(mesh.triangles.size(), 4u * 64);
  EXPECT_EQ(mesh.vertices[0], Vec3(0.5, 0, -1));  // rim vertex 0 on +x
  for (const Vec3& p : mesh.vertices) {
    const double rho = std::hypot(p.x(), p.y());
    EXPECT_TRUE(rho < kShapeTol || std::abs(rho - 0.5) < kShapeTol);
    EXPECT_EQ(std::abs(p.z()), 1.0);
  }
  EXPECT_EQ(make_shape("cylinder:r=1,h=1,n=7").triangles.size(), 28u);
}

TEST(Shapes, Ellipsoid) {
  const TriangleMesh mesh = make_shape("ellipsoid:a=2,b=1,c=0.5");
  EXPECT_EQ(mesh.triangles.size(), 2000u);         // 20·F² with F = 10
  EXPECT_EQ(mesh.vertices.size(), 10u * 100 + 2);  // 10·F² + 2
  for (const Vec3& p : mesh.vertices) {
    EXPECT_NEAR(std::pow(p.x() / 2, 2) + std::pow(p.y() / 1, 2) + std::pow(p.z() / 0.5, 2), 1.0, kShapeTol);
  }
  const Aabb box = bounding_box(mesh.vertices);
  EXPECT_LT((box.max + box.min).norm(), kShapeTol);
  EXPECT_EQ(make_shape("ellipsoid:a=1,b=1,c=1,n=1").vertices.size(), 12u);  // the icosahedron itself
}

TEST(Shapes, Tetrahedron) {
  const double edge = 1.7;
  const TriangleMesh mesh = make_shape("tetrahedron:edge=1.7");
  ASSERT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.triangles.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = i + 1; j < 4; ++j) {
      EXPECT_NEAR((mesh.vertices[i] - mesh.vertices[j]).norm(), edge, kShapeTol);
    }
  }
  const double bottom = -edge * std::sqrt(2.0 / 3.0) / 4;
  const double radius = edge / std::sqrt(3.0);
  const double azimuth[3] = {90, 210, 330};
  for (std::size_t i = 0; i < 3; ++i) {
    const double a = azimuth[i] * std::numbers::pi / 180;
    EXPECT_LT((mesh.vertices[i] - Vec3(radius * std::cos(a), radius * std::sin(a), bottom)).norm(),
              kShapeTol);
  }
  EXPECT_LT((mesh.vertices[3] - Vec3(0, 0, 3 * edge * std::sqrt(2.0 / 3.0) / 4)).norm(), kShapeTol);
}

std::uint64_t fnv1a(const TriangleMesh& mesh) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  const auto add = [&](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ULL;
  };
  for (const Vec3& p : mesh.vertices) add(p.data(), 3 * sizeof(double));
  for (const Triangle& t : mesh.triangles) add(t.data(), sizeof(Triangle));
  return hash;
}

TEST(Shapes, IrregularIsReproducible) {
  const TriangleMesh a = make_shape("irregular:seed=42");
  const TriangleMesh b = make_shape("irregular:seed=42");
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  ASSERT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(std::memcmp(a.vertices.data(), b.vertices.data(), a.vertices.size() * sizeof(Vec3)), 0);
  const TriangleMesh c = make_shape("irregular:seed=43");
  EXPECT_NE(fnv1a(a), fnv1a(c));
  EXPECT_NE(fnv1a(make_shape("irregular:seed=0")), fnv1a(make_shape("irregular:seed=18446744073709551615")));
  // Golden value: the same seed must give the same bytes on every platform and in every release. If this
  // changes, the generator changed and every recorded irregular particle changes with it.
  EXPECT_EQ(fnv1a(a), 0x4235d02ff2fdc8fdULL);
}

TEST(Shapes, IrregularIsNonConvexElongatedAndSized) {
  for (int seed = 1; seed <= 10; ++seed) {
    const double size = 0.5 * seed;
    const std::string spec = "irregular:seed=" + std::to_string(seed) + ",size=" + std::to_string(size);
    SCOPED_TRACE(spec);
    const TriangleMesh mesh = make_shape(spec);
    EXPECT_EQ(mesh.triangles.size(), 320u);  // default F = 4
    const Vec3 extent = bounding_box(mesh.vertices).size();
    EXPECT_NEAR(extent.maxCoeff(), size, kShapeTol * size);
    const MassProperties mp = compute_mass_properties(mesh, 1.0);
    EXPECT_LT(mp.center_of_mass.norm(), kShapeTol * size);
    // Elongated: the principal moments differ markedly (a shape property, not a tolerance; measured ≥ 1.67).
    EXPECT_GT(mp.principal_moments[2] / mp.principal_moments[0], 1.3);
    // Non-convex: the hull encloses noticeably more than the particle (measured ≥ 1.21).
    const ConvexHull hull = compute_convex_hull(mesh.vertices);
    TriangleMesh hull_mesh;
    hull_mesh.vertices = hull.vertices;
    for (const HullFace& face : hull.faces) {
      for (std::size_t k = 1; k + 1 < face.loop.size(); ++k) {
        hull_mesh.triangles.push_back({face.loop[0], face.loop[k], face.loop[k + 1]});
      }
    }
    const double ratio = signed_volume_of(hull_mesh) / mp.volume;
    EXPECT_GT(ratio, 1.03);
    std::cout << spec << ": hull/particle volume = " << ratio
              << ", I3/I1 = " << mp.principal_moments[2] / mp.principal_moments[0] << "\n";
  }
}

TEST(Shapes, IsShapeSpec) {
  EXPECT_TRUE(is_shape_spec("box:x=1,y=1,z=1"));
  EXPECT_TRUE(is_shape_spec("sphere:r=1"));  // unknown, but a spec: make_shape reports it
  EXPECT_TRUE(is_shape_spec("irregular:seed=1"));
  EXPECT_FALSE(is_shape_spec("cube.stl"));
  EXPECT_FALSE(is_shape_spec("C:\\meshes\\cube.stl"));  // one letter: a drive
  EXPECT_TRUE(is_shape_spec("ab:x=1"));                 // two are the shortest name
  EXPECT_FALSE(is_shape_spec("data/a:b.stl"));
  EXPECT_FALSE(is_shape_spec(""));
  EXPECT_FALSE(is_shape_spec(":x=1"));
}

TEST(Shapes, SpecErrors) {
  const std::pair<std::string, std::string> cases[] = {
      {"cylinder:r=1", "shape 'cylinder:r=1': missing parameter 'h'"},
      {"sphere:r=1",
       "shape 'sphere:r=1': unknown shape 'sphere' (known: box, cylinder, ellipsoid, "
       "tetrahedron, irregular)"},
      {"box:x=1,y=1,z=1,q=2", "shape 'box:x=1,y=1,z=1,q=2': unknown parameter 'q'"},
      {"cylinder:r=-1,h=1",
       "shape 'cylinder:r=-1,h=1': parameter 'r' must be a finite positive number, got '-1'"},
      {"cylinder:r=0,h=1", "parameter 'r' must be a finite positive number, got '0'"},
      {"cylinder:r=nan,h=1", "parameter 'r' must be a finite positive number, got 'nan'"},
      {"cylinder:r=inf,h=1", "parameter 'r' must be a finite positive number, got 'inf'"},
      {"cylinder:r=1e999,h=1", "parameter 'r' must be a finite positive number, got '1e999'"},
      {"cylinder:r=1x,h=1", "parameter 'r' must be a finite positive number, got '1x'"},
      {"cylinder:r=,h=1", "parameter 'r' must be a finite positive number, got ''"},
      {"cylinder:r=1,h=1,n=2", "parameter 'n' must be an integer in 3..4096, got '2'"},
      {"cylinder:r=1,h=1,n=4097", "parameter 'n' must be an integer in 3..4096, got '4097'"},
      {"cylinder:r=1,h=1,n=4.5", "parameter 'n' must be an integer"},
      {"ellipsoid:a=1,b=1,c=1,n=0", "parameter 'n' must be an integer in 1..200, got '0'"},
      {"ellipsoid:a=1,b=1,c=1,n=201", "parameter 'n' must be an integer in 1..200"},
      {"irregular:seed=-1", "parameter 'seed' must be an integer in 0..18446744073709551615, got '-1'"},
      {"irregular:seed=18446744073709551616", "parameter 'seed' must be an integer"},
      {"irregular:seed=1.5", "parameter 'seed' must be an integer"},
      {"irregular:size=1", "missing parameter 'seed'"},
      {"box:x=1,y=1,x=2,z=1", "duplicate parameter 'x'"},
      {"box:x=1,,y=1,z=1", "empty parameter"},
      {"box:x", "expected key=value, got 'x'"},
      {"box:", "missing parameter 'x'"},
      {"tetrahedron:a=1", "unknown parameter 'a'"},
      {"box", "shape 'box': expected name:key=value"},
      // Found by fuzz_shape_spec: each size is valid alone, but together they give no valid solid.
      {"box: x = 1e73 , y=3.5e2,z=7", "sizes out of range (mesh: size out of range"},
      {"box:x=1e20,y=1e-20,z=1", "sizes out of range (mesh: "},
      {"box:x=1e300,y=1e300,z=1e300", "sizes out of range (mesh: size out of range"},
      {"tetrahedron:edge=1e-300", "sizes out of range (mesh: zero volume"},
  };
  for (const auto& [spec, expected] : cases) {
    try {
      make_shape(spec);
      ADD_FAILURE() << "no error for '" << spec << "'";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(expected), std::string::npos) << "spec '" << spec << "' gave: " << message;
      EXPECT_EQ(message.rfind("shape '" + spec + "': ", 0), 0u) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
}

TEST(Shapes, ParametersAreParsedExactly) {
  EXPECT_NO_THROW(make_shape("box: x = 1 , y=2e-3,z=0.5"));
  EXPECT_EQ(bounding_box(make_shape("box:x=1,y=2e-3,z=0.5").vertices).max, Vec3(0.5, 1e-3, 0.25));
  EXPECT_NO_THROW(make_shape("irregular:seed=18446744073709551615,size=2,n=2"));
}

}  // namespace
}  // namespace repose
