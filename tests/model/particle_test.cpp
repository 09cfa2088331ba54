// The particle model against closed forms: the static stability margin of each hull face (the distance from
// the centre of mass's projection on the face to the face's nearest edge), what it refuses as a solid, and
// orientation specs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <repose/error.hpp>
#include <repose/model/orientation.hpp>
#include <repose/model/particle.hpp>
#include <repose/sim/settle.hpp>
#include <string>
#include <utility>
#include <vector>

namespace repose {
namespace {

// The margin of the face whose outward normal is `n` (the hull face closest to that direction).
double margin_of(const Particle& p, const Vec3& n) {
  std::size_t best = 0;
  for (std::size_t f = 1; f < p.hull.faces.size(); ++f)
    if (p.hull.faces[f].normal.dot(n) > p.hull.faces[best].normal.dot(n)) best = f;
  EXPECT_NEAR(p.hull.faces[best].normal.dot(n), 1.0, 1e-12);
  return p.face_stability_margin[best];
}

TEST(FaceStabilityMargin, BoxFacesHoldTheCentreOfMassByHalfTheirShorterSide) {
  // Box 1 × 2 × 3: the centre of mass projects to each face's centre, so the margin is half the face's
  // shorter side: ±x faces (2 × 3) 1, ±y faces (1 × 3) 0.5, ±z faces (1 × 2) 0.5. Exact in floating point up
  // to the hull's round-off (1e-12).
  const Particle box = load_particle("box:x=1,y=2,z=3", 1.0);
  ASSERT_EQ(box.hull.faces.size(), 6u);
  for (double s : {1.0, -1.0}) {
    EXPECT_NEAR(margin_of(box, Vec3(s, 0, 0)), 1.0, 1e-12);
    EXPECT_NEAR(margin_of(box, Vec3(0, s, 0)), 0.5, 1e-12);
    EXPECT_NEAR(margin_of(box, Vec3(0, 0, s)), 0.5, 1e-12);
  }
}

// A centre of mass given for the part (MeshOptions::center_of_mass, --com): the unit cube centred at the
// origin with its centre of mass at (0, 0.1, −0.4) (a weighted base). Each face's margin is the distance from
// the centre of mass's projection to the face's boundary (closed form): the bottom face −z 0.4 (the nearest
// edge y = 0.5 is 0.4 away), the top +z likewise 0.4, the sides ±x min(0.5 − 0.1, 0.5 − 0.4) = 0.1, −y 0.1
// (z = −0.4 is 0.1 from the edge z = −0.5), +y 0.1. The inertia is the uniform cube's about that point
// (parallel-axis theorem): I = m/6·1 + m·(|d|²·1 − d·dᵀ). The given point, scaled like the file, becomes the
// input offset; a point outside the hull is refused naming --com.
TEST(FaceStabilityMargin, AGivenCentreOfMassMovesEveryMargin) {
  MeshOptions options;
  options.center_of_mass = Vec3(0, 0.05, -0.2);
  options.scale = 2;  // the cube's file coordinates are doubled: a cube of side 2, the point (0, 0.1, −0.4)
  const Particle cube = load_particle("box:x=0.5,y=0.5,z=0.5", 1.0, options);
  EXPECT_TRUE(cube.input_offset.isApprox(Vec3(0, 0.1, -0.4), 1e-15));
  for (const auto& [normal, margin] : std::vector<std::pair<Vec3, double>>{{Vec3(0, 0, -1), 0.4},
                                                                           {Vec3(0, 0, 1), 0.4},
                                                                           {Vec3(1, 0, 0), 0.1},
                                                                           {Vec3(-1, 0, 0), 0.1},
                                                                           {Vec3(0, 1, 0), 0.1},
                                                                           {Vec3(0, -1, 0), 0.1}})
    EXPECT_NEAR(margin_of(cube, normal), margin, 1e-12) << normal.transpose();
  const Vec3 d(0, 0.1, -0.4);
  const Mat3 expected = Mat3::Identity() / 6 + (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  EXPECT_TRUE(cube.mass.inertia.isApprox(expected, 1e-14)) << cube.mass.inertia;
  EXPECT_NEAR(cube.mass.mass, 1.0, 1e-14);
  EXPECT_TRUE(cube.mass.center_of_mass.isZero(0));
  const Mat3 rebuilt = cube.mass.principal_axes * cube.mass.principal_moments.asDiagonal() *
                       cube.mass.principal_axes.transpose();
  EXPECT_TRUE(rebuilt.isApprox(expected, 1e-14));
  options.center_of_mass = Vec3(0, 0.3, 0);  // 0.6 after scaling: outside the cube
  try {
    load_particle("box:x=0.5,y=0.5,z=0.5", 1.0, options);
    ADD_FAILURE() << "a centre of mass outside the hull was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--com"), std::string::npos) << e.what();
  }
}

TEST(FaceStabilityMargin, TetrahedronFacesHoldItByTheirInradius) {
  // Regular tetrahedron of edge a: the centre of mass projects to each face's centroid, whose distance to
  // the edges is the inradius of the equilateral triangle, a/(2√3).
  const Particle tet = load_particle("tetrahedron:edge=2", 1.0);
  ASSERT_EQ(tet.hull.faces.size(), 4u);
  for (double m : tet.face_stability_margin) EXPECT_NEAR(m, 2 / (2 * std::sqrt(3.0)), 1e-12);
}

TEST(FaceStabilityMargin, AnOverhangingFaceIsUnstable) {
  // A prism 1 deep (y) over the obtuse triangle (0, 0), (1, 0), (3, 2) in x-z: its centroid is at x = 4/3,
  // beyond the short base [0, 1], so on that face the centre of mass projects 1/3 outside (margin −1/3) and
  // the prism tips over. On the ±y caps it projects to the centroid, whose distance to the nearest side of
  // the triangle is the smallest of (twice the area)/(3·side): area 1, sides 1, √8 and √13, so 2/(3·√13).
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {3, 0, 2}, {0, 1, 0}, {1, 1, 0}, {3, 1, 2}};
  m.triangles = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  const Particle prism = make_particle(m, "prism", 1.0);
  EXPECT_NEAR(margin_of(prism, Vec3(0, 0, -1)), -1.0 / 3, 1e-12);
  EXPECT_NEAR(margin_of(prism, Vec3(0, 1, 0)), 2 / (3 * std::sqrt(13.0)), 1e-12);
  EXPECT_NEAR(margin_of(prism, Vec3(0, -1, 0)), 2 / (3 * std::sqrt(13.0)), 1e-12);
}

// An L-shaped prism: the footprint [0,2]×[0,1] ∪ [0,1]×[0,2] (area 3), height 1. Its hull's caps are the
// pentagon (0,0), (2,0), (2,1), (1,2), (0,2) of area 3.5, so the mesh covers 3/3.5 = 86 % of each cap: a cap
// is not flat (a particle resting on it stands on the cap's corners, not on a surface), nor is the hull face
// across the notch (covered 0 %), while the four full sides are flat (covered 100 %).
TriangleMesh l_prism(double scale) {
  const std::vector<Vec2> foot = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};  // counter-clockwise
  TriangleMesh m;
  for (double z : {0.0, 1.0})
    for (const Vec2& p : foot) m.vertices.push_back(scale * Vec3(p.x(), p.y(), z));
  const int n = static_cast<int>(foot.size());
  for (int i = 1; i + 1 < n; ++i) {                // the footprint is star-shaped from vertex 0: a fan
    m.triangles.push_back({0, i + 1, i});          // bottom, facing −z
    m.triangles.push_back({n, n + i, n + i + 1});  // top, facing +z
  }
  for (int i = 0; i < n; ++i) {  // sides, facing outwards
    const int j = (i + 1) % n;
    m.triangles.push_back({i, j, n + j});
    m.triangles.push_back({i, n + j, n + i});
  }
  return m;
}

// The same at any size (the coverage's plane tolerance is 1e-9·L): 1e-6, 1 and 1e6 units.
TEST(FaceIsFlat, OnlyHullFacesTheMeshCoversWhollyAreSurfaces) {
  for (const double scale : {1.0, 1e-6, 1e6}) {
    const Particle l = make_particle(l_prism(scale), "L-prism", 1.0);
    ASSERT_EQ(l.hull.faces.size(), 7u);  // 2 caps, 4 full sides, 1 across the notch
    for (std::size_t f = 0; f < l.hull.faces.size(); ++f) {
      const Vec3& normal = l.hull.faces[f].normal;
      const bool cap = std::abs(normal.z()) > 0.5;
      const bool notch = normal.x() > 0.1 && normal.y() > 0.1;  // (1, 1)/√2
      EXPECT_EQ(l.face_is_flat[f], !cap && !notch)
          << scale << ": hull face with normal " << normal.transpose();
    }
  }
}

// A density that is not a finite positive number is refused before any work, naming the particle.
TEST(ParticleValidation, ADensityThatIsNotFinitePositiveIsRefusedNamingTheParticle) {
  for (const auto& [density, shown] : std::vector<std::pair<double, std::string>>{
           {0.0, "0"}, {-2.5, "-2.5"}, {std::nan(""), "nan"}, {INFINITY, "inf"}}) {
    try {
      load_particle("box:x=1,y=1,z=1", density);
      ADD_FAILURE() << shown << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()),
                "box:x=1,y=1,z=1: density must be a finite positive number, got " + shown);
    }
  }
}

// An n-gonal bipyramid (equator radius r at z = 0, apexes at ±h), outward wound. Its face normals are
// (h·cos φ, h·sin φ, ±a), a = r·cos(π/n) the equator's apothem, φ the face's mid azimuth. So neighbouring
// upper faces meet at acos((h²·cos(2π/n) + a²)/(h² + a²)) and an upper and a lower face at the equator at
// 2·atan(a/h); every edge is convex.
TriangleMesh bipyramid(int n, double r, double h) {
  TriangleMesh m;
  for (int i = 0; i < n; ++i) {
    const double theta = 2 * std::numbers::pi * i / n;
    m.vertices.emplace_back(r * std::cos(theta), r * std::sin(theta), 0.0);
  }
  m.vertices.emplace_back(0, 0, h);
  m.vertices.emplace_back(0, 0, -h);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.push_back({i, j, n});
    m.triangles.push_back({j, i, n + 1});
  }
  return m;
}

// SmoothMode::automatic treats a particle as smooth when its mesh is convex and neighbouring triangles meet
// at less than 30° (docs/method.md). 24-gonal bipyramids whose equator angle (the largest; the lateral ones
// are below 2π/24 = 15°) is 28° and 32°: the first is smooth, the second not. The angle itself is the closed
// form of the bipyramid comment, to round-off (1e-12 rad).
TEST(SmoothSurface, ThirtyDegreesBetweenNeighbouringTrianglesIsTheLimit) {
  const int n = 24;
  const double a = std::cos(std::numbers::pi / n);  // r = 1
  for (const double degrees : {28.0, 32.0}) {
    const double equator = degrees * std::numbers::pi / 180;
    const double h = a / std::tan(equator / 2);
    const double lateral = std::acos((h * h * std::cos(2 * std::numbers::pi / n) + a * a) / (h * h + a * a));
    ASSERT_LT(lateral, equator);
    const Particle p = make_particle(bipyramid(n, 1.0, h), "bipyramid", 1.0);
    EXPECT_NEAR(p.max_dihedral_angle, equator, 1e-12) << degrees;
    EXPECT_TRUE(p.convex_surface) << degrees;
    EXPECT_EQ(is_smooth_surface(p), degrees < 30) << degrees;
  }
  // A reflex edge makes any mesh non-smooth: the L-prism (FaceIsFlat) is not convex.
  const Particle notched = make_particle(l_prism(1.0), "l-prism", 1.0);
  EXPECT_FALSE(notched.convex_surface);
  EXPECT_FALSE(is_smooth_surface(notched));
}

// Found by fuzz_mesh_off / fuzz_mesh_ply: a cube whose vertices were moved until its faces pass through each
// other is closed, consistently wound and of positive volume, but its centre of mass lies outside its convex
// hull: no solid. Rejected with one line naming the file.
TEST(ParticleValidation, ASelfIntersectingSurfaceIsNoSolid) {
  for (const char* file : {"fuzz/off_self_intersecting.off", "fuzz/ply_self_intersecting.ply"}) {
    const std::string path = std::string(REPOSE_TEST_DATA) + "/" + file;
    try {
      load_particle(path, 1.0);
      ADD_FAILURE() << file << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(
          std::string(e.what()),
          path +
              ": not a solid: the surface intersects itself (its centre of mass is outside its convex hull)");
    }
  }
}

// Found by fuzz_orientation_spec: the axis of an axis-angle spec is any non-zero vector; a tiny one (whose
// squares underflow) names the same rotation as the unit vector: cos(θ/2), sin(θ/2)·axis exactly.
TEST(OrientationSpec, ATinyAxisNamesTheSameRotation) {
  for (const char* spec :
       {"axis-angle:1e-160,1e-160,0,1", "axis-angle:1e-300,1e-300,0,1", "axis-angle:7,7,0,1"}) {
    const Quat q = parse_orientation(spec);
    EXPECT_NEAR(q.w(), std::cos(0.5), 1e-15) << spec;
    EXPECT_NEAR(q.x(), std::sin(0.5) / std::sqrt(2.0), 1e-15) << spec;
    EXPECT_NEAR(q.y(), std::sin(0.5) / std::sqrt(2.0), 1e-15) << spec;
    EXPECT_NEAR(q.z(), 0.0, 1e-15) << spec;
  }
  EXPECT_THROW(parse_orientation("axis-angle:0,0,0,1"), Error);
}

}  // namespace
}  // namespace repose
