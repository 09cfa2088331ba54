// How a mesh becomes a particle (MeshOptions): the convex and shell inertia models against closed forms,
// scale and units, point clouds, and the advice an unloadable surface gets.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <repose/campaign/campaign.hpp>
#include <repose/error.hpp>
#include <repose/geometry/shapes.hpp>
#include <repose/io/mesh_io.hpp>
#include <repose/model/particle.hpp>
#include <repose/sim/settle.hpp>
#include <string>
#include <vector>

namespace repose {
namespace {

MeshOptions convex() {
  MeshOptions o;
  o.inertia = InertiaModel::convex;
  return o;
}

MeshOptions shell() {
  MeshOptions o;
  o.inertia = InertiaModel::shell;
  return o;
}

TriangleMesh cloud(std::vector<Vec3> points) { return TriangleMesh{std::move(points), {}}; }

// The corners of the box [0, a] × [0, b] × [0, c] and points strictly inside it (which the hull ignores).
TriangleMesh box_cloud(double a, double b, double c) {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i) p.emplace_back(i & 1 ? a : 0, i & 2 ? b : 0, i & 4 ? c : 0);
  for (int i = 1; i < 40; ++i)
    p.emplace_back(a * (i % 7 + 0.5) / 8, b * (i % 5 + 0.5) / 6, c * (i % 3 + 0.5) / 4);
  return cloud(p);
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ConvexInertia, BoxPointCloudHasTheSolidBoxMassProperties) {
  // Solid box a × b × c, density ρ: m = ρabc, I = m/12·(b² + c², a² + c², a² + b²), centre at the middle.
  // The hull of the corners is the box exactly, so only round-off separates them (1e-12 relative).
  const double a = 1, b = 2, c = 3, rho = 2.5;
  const Particle p = make_particle(box_cloud(a, b, c), "box cloud", rho, convex());
  const double m = rho * a * b * c;
  EXPECT_NEAR(p.mass.mass, m, 1e-12 * m);
  EXPECT_NEAR(p.mass.volume, a * b * c, 1e-12 * a * b * c);
  EXPECT_TRUE(p.input_offset.isApprox(Vec3(a / 2, b / 2, c / 2), 1e-12));
  const Vec3 expected(m / 12 * (b * b + c * c), m / 12 * (a * a + c * c), m / 12 * (a * a + b * b));
  EXPECT_TRUE(p.mass.inertia.diagonal().isApprox(expected, 1e-12)) << p.mass.inertia;
  for (int i = 0; i < 3; ++i)  // products of inertia: zero on the box's axes (measured: exactly 0)
    for (int j = i + 1; j < 3; ++j) EXPECT_NEAR(p.mass.inertia(i, j), 0, 1e-12 * expected.minCoeff());
  EXPECT_TRUE(p.surface_is_hull);
  EXPECT_EQ(p.hull.vertices.size(), 8u);
  EXPECT_NEAR(p.length, std::cbrt(6 * a * b * c / std::numbers::pi), 1e-12);
}

TEST(ConvexInertia, RegularTetrahedronCloudHasIsotropicInertiaMaOverTwenty) {
  // A regular tetrahedron of edge s: V = s³/(6√2), centroid at the corners' mean (the origin here), and its
  // inertia about the centroid is m·s²/20 about any axis (closed form; the tetrahedral group makes the
  // tensor isotropic, so every product of inertia is zero). Density 1.7: the mass is ρ·V. Round-off only
  // (four triangles): measured ≤ 5.2e-16 relative; bound 1e-12.
  const double s = 0.7, rho = 1.7;
  const double k = s / (2 * std::sqrt(2.0));
  TriangleMesh m = cloud({{k, k, k}, {k, -k, -k}, {-k, k, -k}, {-k, -k, k}, {0.01, 0.02, -0.01}});
  const Particle p = make_particle(m, "tetra cloud", rho, convex());
  const double volume = s * s * s / (6 * std::sqrt(2.0)), mass = rho * volume, moment = mass * s * s / 20;
  EXPECT_NEAR(p.mass.volume, volume, 1e-12 * volume);
  EXPECT_NEAR(p.mass.mass, mass, 1e-12 * mass);
  EXPECT_LT(p.input_offset.norm(), 1e-12 * s);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(p.mass.inertia(i, j), i == j ? moment : 0.0, 1e-12 * moment);
}

TEST(ConvexInertia, SampledEllipsoidApproachesTheEllipsoidFromInside) {
  // 20,000 points on an ellipsoid (a Fibonacci lattice mapped by the semi-axes): the hull is inscribed, so
  // its volume and moments are below the ellipsoid's, V = 4/3·π·abc, I_x = m/5·(b² + c²). The deficit of an
  // inscribed polytope with edges h on a radius R is about h²/(4R²) of the volume (each triangle misses a
  // cap of mean height r_c²/(4R), r_c = h/√3); here h ≈ 0.027·R, so ≈ 2e-4 (measured 2.9e-4): checked
  // below 1e-3, and above 0 (inscribed).
  // The moments: the hull commutes with the axes' stretch, so the missing caps are those of the unit
  // sphere's inscribed polytope, a thin layer at the surface spread evenly over it. A thin shell at the
  // surface carries (b² + c²)/3 per unit mass about x against the solid's (b² + c²)/5: each moment's
  // deficit is 5/3 of the volume's (measured 1.6628-1.6668; the caps' depth, ~1e-4·R, and the lattice's
  // uneven spread account for the rest). Bound: 2 % of 5/3. Products of inertia vanish by the ellipsoid's
  // symmetry, the lattice breaks it only slightly (measured 2.6e-10 of the smallest moment; bound 1e-6).
  const double a = 1.0, b = 0.8, c = 0.6;
  const int n = 20000;
  std::vector<Vec3> points;
  const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z);
    points.emplace_back(a * r * std::cos(golden * i), b * r * std::sin(golden * i), c * z);
  }
  const Particle p = make_particle(cloud(points), "ellipsoid cloud", 1.0, convex());
  const double volume = 4.0 / 3.0 * std::numbers::pi * a * b * c;
  const double deficit = 1 - p.mass.volume / volume;
  EXPECT_GT(deficit, 0);
  EXPECT_LT(deficit, 1e-3);
  const Vec3 expected(volume / 5 * (b * b + c * c), volume / 5 * (a * a + c * c),
                      volume / 5 * (a * a + b * b));
  for (int i = 0; i < 3; ++i) {
    const double moment_deficit = 1 - p.mass.inertia(i, i) / expected[i];
    EXPECT_NEAR(moment_deficit / deficit, 5.0 / 3.0, 0.02 * 5.0 / 3.0) << "axis " << i;
    for (int j = i + 1; j < 3; ++j) EXPECT_NEAR(p.mass.inertia(i, j), 0, 1e-6 * expected.minCoeff());
  }
  EXPECT_LT(p.input_offset.norm(), 1e-3 * a);  // symmetric sampling: the centre to the deficit's order
}

TEST(ConvexInertia, AClosedConcaveSolidKeepsItsSurfaceButTakesTheHullsMass) {
  // An L-shaped prism (a 2 × 2 square minus a 1 × 1 corner, height 1): the solid has volume 3, its hull
  // (the square with the corner cut diagonally) 3.5.
  const Particle solid = load_particle("box:x=1,y=1,z=1", 1.0);  // a sanity anchor for the shapes module
  EXPECT_NEAR(solid.mass.volume, 1, 1e-12);
  TriangleMesh l_shape;
  const std::vector<Vec2> outline{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  for (double z : {0.0, 1.0})
    for (const Vec2& q : outline) l_shape.vertices.emplace_back(q.x(), q.y(), z);
  const int k = static_cast<int>(outline.size());
  // Bottom (clockwise from above, so outward is −z) and top, as fans from the reflex corner's neighbour 0.
  for (int i = 1; i + 1 < k; ++i) {
    l_shape.triangles.push_back({0, i + 1, i});
    l_shape.triangles.push_back({k, k + i, k + i + 1});
  }
  for (int i = 0; i < k; ++i) {
    const int j = (i + 1) % k;
    l_shape.triangles.push_back({i, j, k + j});
    l_shape.triangles.push_back({i, k + j, k + i});
  }
  const Particle exact = make_particle(l_shape, "L", 1.0);
  EXPECT_NEAR(exact.mass.volume, 3, 1e-12);
  const Particle hull = make_particle(l_shape, "L", 1.0, convex());
  EXPECT_NEAR(hull.mass.volume, 3.5, 1e-12);
  EXPECT_FALSE(hull.surface_is_hull);  // a closed solid keeps its own surface
  EXPECT_EQ(hull.mesh.triangles.size(), l_shape.triangles.size());
  // The hull's centre: the square's (1, 1) minus the cut triangle's (area 0.5 at (5/3, 5/3)): 3.5·c = 4·1 −
  // 0.5·5/3 per axis.
  const double c = (4.0 - 0.5 * 5.0 / 3.0) / 3.5;
  EXPECT_TRUE(hull.input_offset.isApprox(Vec3(c, c, 0.5), 1e-12)) << hull.input_offset.transpose();
}

// A thin closed box's surface inertia in closed form: each face a plate of mass σ·area, its own moments
// (m/12 of its sides squared) plus m·d² for its offset d from the axis.
Vec3 box_shell_moments(double a, double b, double c, double sigma) {
  const double mx = sigma * b * c, my = sigma * a * c, mz = sigma * a * b;  // one face of each pair
  const double ixx =
      2 * (mx * (b * b + c * c) / 12 + my * (c * c / 12 + b * b / 4) + mz * (b * b / 12 + c * c / 4));
  const double iyy =
      2 * (mx * (c * c / 12 + a * a / 4) + my * (a * a + c * c) / 12 + mz * (a * a / 12 + c * c / 4));
  const double izz =
      2 * (mx * (b * b / 12 + a * a / 4) + my * (a * a / 12 + b * b / 4) + mz * (a * a + b * b) / 12);
  return {ixx, iyy, izz};
}

TEST(ShellInertia, ClosedBoxSurfaceMatchesItsPlatesInClosedForm) {
  const double a = 1, b = 2, c = 3, sigma = 0.4;
  const Particle p = make_particle(make_shape("box:x=1,y=2,z=3"), "box shell", sigma, shell());
  const double area = 2 * (a * b + b * c + a * c);
  EXPECT_NEAR(p.mass.area, area, 1e-12 * area);
  EXPECT_NEAR(p.mass.mass, sigma * area, 1e-12 * area);
  EXPECT_EQ(p.mass.volume, 0);
  const Vec3 expected = box_shell_moments(a, b, c, sigma);
  // The surface is the box exactly (12 triangles): round-off only, measured ≤ 2.9e-16 relative (products of
  // inertia: 0); bound 1e-12.
  EXPECT_TRUE(p.mass.inertia.diagonal().isApprox(expected, 1e-12)) << p.mass.inertia.diagonal().transpose();
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) EXPECT_NEAR(p.mass.inertia(i, j), 0, 1e-12 * expected.minCoeff());
  // L is the hull's volume-equivalent diameter (here the box's).
  EXPECT_NEAR(p.length, std::cbrt(6 * a * b * c / std::numbers::pi), 1e-12);
  // A shell carries its mass farther out than the solid: each moment per unit mass is larger.
  const Particle solid = load_particle("box:x=1,y=2,z=3", 1.0);
  for (int i = 0; i < 3; ++i)
    EXPECT_GT(p.mass.inertia(i, i) / p.mass.mass, solid.mass.inertia(i, i) / solid.mass.mass);
}

TEST(ShellInertia, AnOpenBoxLoadsAndItsCentreOfMassDropsTowardsItsFloor) {
  // The unit cube without its top face: five plates of mass σ; the floor at z = 0, the four walls centred
  // at z = 1/2, so the centre of mass is at z = (0 + 4·½)/5 = 0.4 above the floor (the closed cube: ½).
  TriangleMesh open = make_shape("box:x=1,y=1,z=1");
  std::vector<Triangle> kept;
  double zmax = -INFINITY;
  for (const Vec3& v : open.vertices) zmax = std::max(zmax, v.z());
  for (const Triangle& t : open.triangles) {
    bool on_top = true;
    for (int i : t) on_top = on_top && open.vertices[static_cast<std::size_t>(i)].z() == zmax;
    if (!on_top) kept.push_back(t);
  }
  ASSERT_EQ(kept.size(), 10u);
  open.triangles = kept;
  EXPECT_THROW(make_particle(open, "open box", 1.0), SurfaceError);
  const Particle p = make_particle(open, "open box", 1.0, shell());
  EXPECT_NEAR(p.mass.area, 5, 1e-12);
  EXPECT_NEAR(p.input_offset.z() - (zmax - 1), 0.4, 1e-12);
  // Convex: the same file is its hull, the whole solid cube.
  const Particle hull = make_particle(open, "open box", 1.0, convex());
  EXPECT_NEAR(hull.mass.volume, 1, 1e-12);
  EXPECT_TRUE(hull.surface_is_hull);
}

TEST(MeshScale, ScaleMultipliesEveryLengthBeforeAnythingElse) {
  MeshOptions mm;
  mm.scale = mesh_unit_scale("mm");
  const Particle metres = load_particle("box:x=10,y=20,z=30", 1000.0, mm);
  // 10 × 20 × 30 mm = 6e-6 m³: mass 6e-3 kg at 1000 kg/m³; I_zz = m/12·(a² + b²) in kg·m².
  EXPECT_NEAR(metres.mass.volume, 6e-6, 1e-18);
  EXPECT_NEAR(metres.mass.mass, 6e-3, 1e-15);
  EXPECT_NEAR(metres.mass.inertia(2, 2), 6e-3 / 12 * (1e-4 + 4e-4), 1e-18);
  EXPECT_NEAR(metres.bounds.size().z(), 0.03, 1e-15);
  const Particle unscaled = load_particle("box:x=10,y=20,z=30", 1000.0);
  EXPECT_NEAR(metres.length, 1e-3 * unscaled.length, 1e-12 * metres.length);
  EXPECT_EQ(mesh_unit_scale("cm"), 1e-2);
  EXPECT_EQ(mesh_unit_scale("in"), 0.0254);
  EXPECT_EQ(mesh_unit_scale("m"), 1.0);
  EXPECT_NEAR(mesh_unit_scale("mm", true), 0.1, 1e-16);  // to centimetres (--units cgs)
  EXPECT_NE(message_of([] { mesh_unit_scale("ft"); }).find("mm, cm, m or in"), std::string::npos);
  MeshOptions bad;
  bad.scale = -1;
  EXPECT_NE(message_of([&] { load_particle("box:x=1,y=1,z=1", 1.0, bad); }).find("scale must be"),
            std::string::npos);
}

TEST(MeshAdvice, UnloadableSurfacesNameTheOptionThatLoadsThem) {
  TriangleMesh open = make_shape("box:x=1,y=1,z=1");
  open.triangles.pop_back();
  const std::string m = message_of([&] { make_particle(open, "scan.obj", 1.0); });
  EXPECT_EQ(m.rfind("scan.obj: open surface", 0), 0u) << m;
  EXPECT_NE(m.find("--repair"), std::string::npos) << m;
  EXPECT_NE(m.find("--inertia convex"), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos);
  const std::string c = message_of([] { make_particle(box_cloud(1, 1, 1), "grain.xyz", 1.0); });
  EXPECT_EQ(c.rfind("grain.xyz: no faces", 0), 0u) << c;
  EXPECT_NE(c.find("--inertia convex"), std::string::npos) << c;
  EXPECT_NE(message_of([] { make_particle(box_cloud(1, 1, 1), "grain.xyz", 1.0, shell()); }).find("no faces"),
            std::string::npos);
  TriangleMesh bad = box_cloud(1, 1, 1);
  bad.vertices[3].y() = NAN;
  const std::string n = message_of([&] { make_particle(bad, "grain.xyz", 1.0, convex()); });
  EXPECT_EQ(n, "grain.xyz: vertex 3 has a non-finite coordinate");
  // Three points span no solid.
  EXPECT_EQ(message_of([] {
              make_particle(cloud({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), "flat.xyz", 1.0, convex());
            }).rfind("flat.xyz: ", 0),
            0u);
}

// Found by fuzz_mesh_options: an open, overlapping pair of boxes whose largest part, once repaired, is closed
// and consistently wound with its centre of mass inside its hull, but passes through itself: its inertia
// tensor had a principal moment of −0.47. No body has a principal moment above the sum of the other two
// (each is a sum of two non-negative second moments), so such a surface is refused as no solid.
TEST(MeshAdvice, ASurfaceThroughItselfWithAnImpossibleInertiaIsNoSolid) {
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\n"
      "f 3 8 7\nf 4 1 5\nf 4 5 8\nv 3 0 0\nv 5 0 0\nv 5 2 0\nv 3 2 0\nv 4 0 2\nv 5 0 2\nv 5 2 2\nv 3 2 2\n"
      "f 9 11 10\nf 1 12 11\nf 13 14 15\nf 13 15 15 2 2\nv 3 2 2\nf 9 11 10\nf 9 12 11\nf 13 13 15\n"
      "f 13 15 16\nf 9 10 14\nf 9 14 13\nf 10 11 15\nf 10 15 14\nf 11 12 16\nf 11 16 15\nf 12 9 13\n"
      "f 12 13 16\n";
  MeshOptions largest;
  largest.largest_component = true;
  const std::string m =
      message_of([&] { make_particle(read_mesh_from_memory(obj, "parts.obj"), "parts.obj", 1.0, largest); });
  EXPECT_EQ(m.rfind("parts.obj: not a solid: its principal moments of inertia", 0), 0u) << m;
  EXPECT_NE(m.find("--inertia convex"), std::string::npos) << m;
  // Its hull is a body.
  const Particle hull = make_particle(read_mesh_from_memory(obj, "parts.obj"), "parts.obj", 1.0, convex());
  const Vec3 pm = hull.mass.principal_moments;
  EXPECT_GE(pm.sum() / 2 - pm.maxCoeff(), 0);
}

TEST(MeshAdvice, ANonManifoldFinLoadsByRepairOrShell) {
  // The unit cube with a fin: one extra triangle on a top edge, so that edge has three triangles (a
  // non-manifold fan). Exact: rejected, naming the options. Repair cuts the fin apart at the edge; alone it
  // encloses no volume, so it is removed and the cube's volume stays exact (1e-12). Shell: the fin's area
  // (½) adds to the cube's 6.
  TriangleMesh fin = make_shape("box:x=1,y=1,z=1");
  double zmax = -INFINITY;
  for (const Vec3& v : fin.vertices) zmax = std::max(zmax, v.z());
  int a = -1, b = -1;  // two corners of a top edge along x
  for (int i = 0; i < static_cast<int>(fin.vertices.size()); ++i) {
    const Vec3& v = fin.vertices[static_cast<std::size_t>(i)];
    if (v.z() == zmax && v.y() == zmax) (a < 0 ? a : b) = i;
  }
  ASSERT_GE(b, 0);
  fin.vertices.emplace_back(0.5 * (fin.vertices[a] + fin.vertices[b]) + Vec3(0, 0, 1));
  fin.triangles.push_back({a, b, static_cast<int>(fin.vertices.size()) - 1});
  const std::string m = message_of([&] { make_particle(fin, "fin.obj", 1.0); });
  EXPECT_EQ(m.rfind("fin.obj: non-manifold surface", 0), 0u) << m;
  EXPECT_NE(m.find("--repair"), std::string::npos) << m;
  MeshOptions repair;
  repair.repair = true;
  const Particle repaired = make_particle(fin, "fin.obj", 1.0, repair);
  EXPECT_NEAR(repaired.mass.volume, 1, 1e-12);
  ASSERT_TRUE(repaired.repair.has_value());
  EXPECT_EQ(repaired.repair->flat_components, 1);
  const Particle shelled = make_particle(fin, "fin.obj", 1.0, shell());
  EXPECT_NEAR(shelled.mass.area, 6.5, 1e-12);
}

TEST(MeshOptionsSettle, ABoxPointCloudRestsFlatOnAFace) {
  // The settling engine needs only the hull, the centre of mass and the inertia: a box given as points
  // rests on a face with its centre of mass at half the face's normal extent (up to the engine's 1e-9·L).
  const Particle p = make_particle(box_cloud(1, 2, 3), "box cloud", 1.0, convex());
  SettleParams params;
  params.damping = 0.05 * p.mass.mass * std::sqrt(9.81 * std::pow(p.length, 3));
  const SettleResult r = settle(p, params, Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 0.5).normalized())));
  ASSERT_EQ(r.status, Status::rest);
  const double h = r.com.z();
  const bool on_a_face = std::abs(h - 0.5) < 1e-9 * p.length || std::abs(h - 1.0) < 1e-9 * p.length ||
                         std::abs(h - 1.5) < 1e-9 * p.length;
  EXPECT_TRUE(on_a_face) << h;
}

TEST(ManifestOptions, ALineOverridesTheJobsMeshOptionsForItsOwnInput) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("repose-manifest-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path manifest = dir / "list.txt";
  std::ofstream(manifest) << "# scans\nbox:x=1,y=1,z=1 --mesh-units mm --inertia convex --repair\n"
                             "box:x=2,y=1,z=1\ntetrahedron:edge=1 --scale 2 --inertia shell\n";
  MeshOptions job;
  job.inertia = InertiaModel::exact;
  const std::vector<CampaignParticle> ps = resolve_particles({}, manifest.string(), job, true);
  ASSERT_EQ(ps.size(), 3u);
  EXPECT_EQ(ps[0].source, "box:x=1,y=1,z=1");
  EXPECT_NEAR(ps[0].mesh.scale, 0.1, 1e-16);  // mm → cm (lengths in cm)
  EXPECT_EQ(ps[0].mesh.inertia, InertiaModel::convex);
  EXPECT_TRUE(ps[0].mesh.repair);
  EXPECT_EQ(ps[1].mesh, job);
  EXPECT_EQ(ps[2].mesh.scale, 2.0);
  EXPECT_EQ(ps[2].mesh.inertia, InertiaModel::shell);
  std::ofstream(manifest) << "box:x=1,y=1,z=1\nbox:x=2,y=1,z=1 --density 3\n";
  const std::string m = message_of([&] { resolve_particles({}, manifest.string()); });
  EXPECT_EQ(m.rfind(manifest.string() + ": line 2: unknown option '--density'", 0), 0u) << m;
  std::ofstream(manifest) << "box:x=1,y=1,z=1 --scale 2 --mesh-units mm\n";
  EXPECT_NE(
      message_of([&] { resolve_particles({}, manifest.string()); }).find("either --scale or --mesh-units"),
      std::string::npos);
  // A line's known centre of mass (a weighted part), in its file's coordinates.
  std::ofstream(manifest) << "box:x=1,y=1,z=1 --com 0.1,-0.2,3e-2\nbox:x=1,y=1,z=1 --com 1,2\n";
  const std::string bad_com = message_of([&] { resolve_particles({}, manifest.string()); });
  EXPECT_EQ(bad_com.rfind(manifest.string() + ": line 2: option --com must be X,Y,Z", 0), 0u) << bad_com;
  std::ofstream(manifest) << "box:x=1,y=1,z=1 --com 0.1,-0.2,3e-2\n";
  const std::vector<CampaignParticle> weighted = resolve_particles({}, manifest.string());
  ASSERT_EQ(weighted.size(), 1u);
  ASSERT_TRUE(weighted[0].mesh.center_of_mass.has_value());
  EXPECT_EQ(*weighted[0].mesh.center_of_mass, Vec3(0.1, -0.2, 0.03));
  std::ofstream(manifest) << "box:x=1,y=1,z=1 --inertia\n";
  EXPECT_NE(message_of([&] { resolve_particles({}, manifest.string()); }).find("--inertia needs a value"),
            std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace repose
