// Tests of compute_mass_properties against closed-form results.
//
// Tolerances: the Eberly/Mirtich integration is exact for a polyhedron, so for shapes whose mesh *is* the
// solid (box, tetrahedron, prism) only floating-point round-off remains: a few hundred operations per
// triangle on O(1) numbers, i.e. ~1e-15 relative (measured: ≤ 1.4e-15 relative, ≤ 8e-17 on centres of mass
// and products of inertia that should vanish); kRoundOff = 1e-12 is a round-off margin for exact closed
// forms, not an error estimate: a wrong coefficient would be off by O(1). The ellipsoid is approximated by an
// inscribed polyhedron, whose error is a discretisation error O(h²) ~ O(n⁻²), checked by its convergence rate
// instead.
#include "repose/geometry/mass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include "repose/error.hpp"
#include "repose/geometry/shapes.hpp"

namespace repose {
namespace {

constexpr double kRoundOff = 1e-12;

void expect_rel(double actual, double expected, double tol, const char* what) {
  EXPECT_NEAR(actual, expected, tol * std::abs(expected)) << what;
}

TEST(MassProperties, BoxIsExact) {
  const double a = 1.3, b = 0.7, c = 2.1, density = 2.5;
  const TriangleMesh mesh = make_shape("box:x=1.3,y=0.7,z=2.1");
  const MassProperties mp = compute_mass_properties(mesh, density);
  const double m = density * a * b * c;
  expect_rel(mp.volume, a * b * c, kRoundOff, "volume");
  expect_rel(mp.area, 2 * (a * b + b * c + c * a), kRoundOff, "area");  // a solid's surface too (info)
  expect_rel(mp.mass, m, kRoundOff, "mass");
  EXPECT_LT(mp.center_of_mass.norm(), kRoundOff);
  expect_rel(mp.inertia(0, 0), m * (b * b + c * c) / 12, kRoundOff, "Ixx");
  expect_rel(mp.inertia(1, 1), m * (a * a + c * c) / 12, kRoundOff, "Iyy");
  expect_rel(mp.inertia(2, 2), m * (a * a + b * b) / 12, kRoundOff, "Izz");
  EXPECT_LT(std::abs(mp.inertia(0, 1)), kRoundOff * m);
  EXPECT_LT(std::abs(mp.inertia(1, 2)), kRoundOff * m);
  EXPECT_LT(std::abs(mp.inertia(0, 2)), kRoundOff * m);
  // Ascending principal moments: the axis of smallest moment is the longest edge (z), the largest is y.
  expect_rel(mp.principal_moments[0], m * (a * a + b * b) / 12, kRoundOff, "I1");
  expect_rel(mp.principal_moments[1], m * (b * b + c * c) / 12, kRoundOff, "I2");
  expect_rel(mp.principal_moments[2], m * (a * a + c * c) / 12, kRoundOff, "I3");
  EXPECT_NEAR(std::abs(mp.principal_axes(2, 0)), 1.0, kRoundOff);
  EXPECT_NEAR(std::abs(mp.principal_axes(0, 1)), 1.0, kRoundOff);
  EXPECT_NEAR(std::abs(mp.principal_axes(1, 2)), 1.0, kRoundOff);
}

TEST(MassProperties, OffsetBoxCentreOfMass) {
  TriangleMesh mesh = make_shape("box:x=1,y=2,z=3");
  const Vec3 shift(5, -3, 2);
  for (Vec3& p : mesh.vertices) p += shift;
  const MassProperties mp = compute_mass_properties(mesh, 1.0);
  EXPECT_LT((mp.center_of_mass - shift).norm(), kRoundOff * shift.norm());
  expect_rel(mp.inertia(0, 0), 6.0 * (4 + 9) / 12, kRoundOff, "Ixx about COM");
}

TEST(MassProperties, RegularTetrahedron) {
  const MassProperties mp = compute_mass_properties(make_shape("tetrahedron:edge=1"), 3.0);
  const double volume = 1.0 / (6.0 * std::sqrt(2.0));  // 0.1178511...
  expect_rel(mp.volume, volume, kRoundOff, "volume");
  EXPECT_NEAR(mp.volume, 0.1178511, 5e-8);  // the literal is rounded to 7 decimals (measured 3.0e-8)
  expect_rel(mp.area, std::sqrt(3.0), kRoundOff, "area");  // four equilateral triangles of edge 1
  EXPECT_LT(mp.center_of_mass.norm(), kRoundOff);
  // A regular tetrahedron's inertia about its COM is isotropic: m·a²/20.
  const double moment = mp.mass / 20.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(mp.inertia(i, j), i == j ? moment : 0.0, kRoundOff * moment) << i << "," << j;
    }
    expect_rel(mp.principal_moments[i], moment, kRoundOff, "principal moment");
  }
}

TEST(MassProperties, RegularPrismMatchesExactFormulas) {
  const double r = 0.67, h = 1.3, density = 1.7;
  for (int n : {3, 8, 64}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    const MassProperties mp =
        compute_mass_properties(make_shape("cylinder:r=0.67,h=1.3,n=" + std::to_string(n)), density);
    const double volume = n / 2.0 * r * r * std::sin(2 * std::numbers::pi / n) * h;
    const double m = density * volume;
    const double c2 = std::pow(std::cos(std::numbers::pi / n), 2);
    const double izz = m * r * r * (1 + 2 * c2) / 6;
    const double ixx = m * (r * r * (1 + 2 * c2) / 12 + h * h / 12);
    expect_rel(mp.volume, volume, kRoundOff, "volume");
    expect_rel(mp.inertia(0, 0), ixx, kRoundOff, "Ixx");
    expect_rel(mp.inertia(1, 1), ixx, kRoundOff, "Iyy");
    expect_rel(mp.inertia(2, 2), izz, kRoundOff, "Izz");
    EXPECT_LT(std::abs(mp.inertia(0, 1)), kRoundOff * m);
    EXPECT_LT(std::abs(mp.inertia(0, 2)), kRoundOff * m);
    EXPECT_LT(std::abs(mp.inertia(1, 2)), kRoundOff * m);
    EXPECT_LT(mp.center_of_mass.norm(), kRoundOff * r);
  }
}

TEST(MassProperties, EllipsoidConvergesAsNSquared) {
  const double a = 1.0, b = 0.7, c = 0.4;
  const double volume = 4.0 / 3.0 * std::numbers::pi * a * b * c;
  double previous = 0;
  for (int n : {5, 10, 20, 40}) {
    const MassProperties mp =
        compute_mass_properties(make_shape("ellipsoid:a=1,b=0.7,c=0.4,n=" + std::to_string(n)), 1.0);
    // Principal moments of a solid ellipsoid, ascending for a > b > c: m(b²+c²)/5, m(a²+c²)/5, m(a²+b²)/5.
    const double m = mp.mass;
    const Vec3 exact(m * (b * b + c * c) / 5, m * (a * a + c * c) / 5, m * (a * a + b * b) / 5);
    double error = std::abs(mp.volume / volume - 1);
    for (int i = 0; i < 3; ++i) error = std::max(error, std::abs(mp.principal_moments[i] / exact[i] - 1));
    std::cout << "ellipsoid n=" << n << ": max relative error (volume, principal moments) = " << error
              << "\n";
    if (previous > 0) {
      // Inscribed polyhedron: error ~ C·n⁻², so doubling n divides it by ~4 (measured 3.95, 3.99, 4.00); an
      // O(n⁻¹) or O(n⁻³) error would give 2 or 8.
      EXPECT_GT(previous / error, 3.5);
      EXPECT_LT(previous / error, 4.5);
    }
    previous = error;
  }
  EXPECT_LT(previous, 1e-3);  // n = 40: measured 3.5e-4
}

TEST(MassProperties, InvariantUnderRigidMotionFarFromOrigin) {
  // Irregular particle of size L = 1, moved by ~1e4·L and rotated. Coordinates then carry an absolute
  // round-off of ~1e4·eps ≈ 2e-12·L, which any exact method inherits. Measured: 0 on the centre of mass,
  // 5.3e-15 relative on the volume, ≤ 3.9e-13 on the moments and the inertia tensor; 1e-11 is 5× the
  // inherited round-off, 25× the measured.
  const TriangleMesh mesh = make_shape("irregular:seed=11,size=1");
  const MassProperties ref = compute_mass_properties(mesh, 2.0);
  const Mat3 rot = Eigen::AngleAxisd(0.7, Vec3(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
  const Vec3 shift(1.0e4, -0.6e4, 0.35e4);
  TriangleMesh moved = mesh;
  for (Vec3& p : moved.vertices) p = rot * p + shift;
  const MassProperties mp = compute_mass_properties(moved, 2.0);
  constexpr double tol = 1e-11;
  expect_rel(mp.volume, ref.volume, tol, "volume");
  for (int i = 0; i < 3; ++i) expect_rel(mp.principal_moments[i], ref.principal_moments[i], tol, "moment");
  EXPECT_LT((mp.center_of_mass - (rot * ref.center_of_mass + shift)).norm(), tol);
  const Mat3 rotated = rot * ref.inertia * rot.transpose();
  EXPECT_LT((mp.inertia - rotated).norm(), tol * ref.inertia.norm());
}

TEST(MassProperties, PrincipalAxesAreAProperRotation) {
  // Seeds 1 and 3 and their mirror images: after each axis is signed so that its largest component is
  // positive, seed 1's axes form a left-handed frame (the last one must be flipped), seed 3's a right-handed.
  std::vector<TriangleMesh> meshes;
  for (const char* spec : {"irregular:seed=1", "irregular:seed=3"}) {
    TriangleMesh mesh = make_shape(spec);
    meshes.push_back(mesh);
    for (Vec3& p : mesh.vertices) p.x() = -p.x();  // mirror image
    for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
    meshes.push_back(mesh);
  }
  for (const TriangleMesh& m : meshes) {
    const MassProperties mp = compute_mass_properties(m, 1.0);
    const Mat3& axes = mp.principal_axes;  // round-off (1e-12, see the top): measured ≤ 7.8e-16
    EXPECT_LT((axes.transpose() * axes - Mat3::Identity()).norm(), 1e-12);
    EXPECT_NEAR(axes.determinant(), 1.0, 1e-12);
    const Mat3 diagonal = axes.transpose() * mp.inertia * axes;
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(diagonal(i, i), mp.principal_moments[i], 1e-12 * mp.principal_moments[2]);
    }
    for (int j = 0; j < 2; ++j) {  // signs: each of the first two axes has its largest component positive
      Eigen::Index k = 0;
      axes.col(j).cwiseAbs().maxCoeff(&k);
      EXPECT_GT(axes(k, j), 0) << "axis " << j;
    }
    EXPECT_LE(mp.principal_moments[0], mp.principal_moments[1]);
    EXPECT_LE(mp.principal_moments[1], mp.principal_moments[2]);
  }
}

TEST(MassProperties, RejectsBadDensity) {
  const TriangleMesh mesh = make_shape("box:x=1,y=1,z=1");
  for (const double density : {0.0, -1.0, std::nan(""), static_cast<double>(INFINITY)}) {
    EXPECT_THROW(compute_mass_properties(mesh, density), Error) << density;
  }
  EXPECT_NEAR(compute_mass_properties(mesh, 7.5).mass, 7.5, kRoundOff * 7.5);
}

}  // namespace
}  // namespace repose
