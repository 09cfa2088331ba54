// Mass properties of a closed triangle mesh: Eberly, "Polyhedral Mass Properties (Revisited)" (2002), the
// divergence-theorem reduction of Mirtich (1996) to per-triangle polynomial sums.
#include "repose/geometry/mass.hpp"

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <sstream>

#include "repose/error.hpp"

namespace repose {
namespace {

// Eberly's per-coordinate subexpressions for one triangle with coordinates w0, w1, w2.
struct Sub {
  double f1, f2, f3, g0, g1, g2;
};

Sub subexpressions(double w0, double w1, double w2) {
  const double temp0 = w0 + w1;
  const double temp1 = w0 * w0;
  const double temp2 = temp1 + w1 * temp0;
  Sub s{};
  s.f1 = temp0 + w2;
  s.f2 = temp2 + w2 * s.f1;
  s.f3 = w0 * temp1 + w1 * temp2 + w2 * s.f2;
  s.g0 = s.f2 + w0 * (s.f1 + w0);
  s.g1 = s.f2 + w1 * (s.f1 + w1);
  s.g2 = s.f2 + w2 * (s.f1 + w2);
  return s;
}

// Principal moments (ascending) and axes of props.inertia, with deterministic signs: the largest component
// of each axis is positive, and the axes form a proper rotation.
void set_principal_frame(MassProperties& props) {
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(props.inertia);
  props.principal_moments = solver.eigenvalues();
  Mat3 axes = solver.eigenvectors();
  for (int j = 0; j < 3; ++j) {
    Eigen::Index k = 0;
    axes.col(j).cwiseAbs().maxCoeff(&k);
    if (axes(k, j) < 0) axes.col(j) = -axes.col(j);
  }
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
  props.principal_axes = axes;
}

}  // namespace

MassProperties with_center_of_mass(const MassProperties& props, const Vec3& point) {
  MassProperties moved = props;
  const Vec3 d = point - props.center_of_mass;
  moved.inertia = props.inertia + props.mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  moved.center_of_mass = point;
  set_principal_frame(moved);
  return moved;
}

MassProperties compute_mass_properties(const TriangleMesh& mesh, double density) {
  if (!(std::isfinite(density) && density > 0)) {
    std::ostringstream msg;
    msg << "mass properties: density must be a finite positive number, got " << density;
    throw Error(msg.str());
  }

  // Integrate in a frame centred on the bounding box, so that the polynomial sums (up to cubic in the
  // coordinates) do not cancel catastrophically for a particle far from the origin.
  const Vec3 ref = bounding_box(mesh.vertices).center();

  // Volume integrals of 1, x, y, z, x², y², z², xy, yz, zx (times 6, 24, 24, 24, 60, ..., 120).
  std::array<double, 10> integral{};
  double area = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3 p0 = mesh.vertices[static_cast<std::size_t>(t[0])] - ref;
    const Vec3 p1 = mesh.vertices[static_cast<std::size_t>(t[1])] - ref;
    const Vec3 p2 = mesh.vertices[static_cast<std::size_t>(t[2])] - ref;
    const Vec3 d = (p1 - p0).cross(p2 - p0);
    area += 0.5 * d.norm();
    const Sub sx = subexpressions(p0.x(), p1.x(), p2.x());
    const Sub sy = subexpressions(p0.y(), p1.y(), p2.y());
    const Sub sz = subexpressions(p0.z(), p1.z(), p2.z());
    integral[0] += d.x() * sx.f1;
    integral[1] += d.x() * sx.f2;
    integral[2] += d.y() * sy.f2;
    integral[3] += d.z() * sz.f2;
    integral[4] += d.x() * sx.f3;
    integral[5] += d.y() * sy.f3;
    integral[6] += d.z() * sz.f3;
    integral[7] += d.x() * (p0.y() * sx.g0 + p1.y() * sx.g1 + p2.y() * sx.g2);
    integral[8] += d.y() * (p0.z() * sy.g0 + p1.z() * sy.g1 + p2.z() * sy.g2);
    integral[9] += d.z() * (p0.x() * sz.g0 + p1.x() * sz.g1 + p2.x() * sz.g2);
  }
  integral[0] /= 6.0;
  for (int i = 1; i <= 3; ++i) integral[static_cast<std::size_t>(i)] /= 24.0;
  for (int i = 4; i <= 6; ++i) integral[static_cast<std::size_t>(i)] /= 60.0;
  for (int i = 7; i <= 9; ++i) integral[static_cast<std::size_t>(i)] /= 120.0;

  MassProperties props;
  const double volume = integral[0];
  props.volume = volume;
  props.area = area;
  props.mass = density * volume;
  if (volume == 0) {
    // Nothing to divide by: a surface enclosing no volume has no centre of mass (the caller validates that
    // this does not happen); report the reference point and zero inertia.
    props.center_of_mass = ref;
    return props;
  }

  // Centre of mass in the shifted frame, then second moments about it (parallel-axis theorem, per unit
  // density): ∫(y-cy)² = ∫y² - V·cy², ∫(x-cx)(y-cy) = ∫xy - V·cx·cy.
  const Vec3 c(integral[1] / volume, integral[2] / volume, integral[3] / volume);
  const double xx = integral[4] - volume * c.x() * c.x();
  const double yy = integral[5] - volume * c.y() * c.y();
  const double zz = integral[6] - volume * c.z() * c.z();
  const double xy = integral[7] - volume * c.x() * c.y();
  const double yz = integral[8] - volume * c.y() * c.z();
  const double zx = integral[9] - volume * c.z() * c.x();

  Mat3 inertia;
  inertia(0, 0) = yy + zz;
  inertia(1, 1) = xx + zz;
  inertia(2, 2) = xx + yy;
  inertia(0, 1) = inertia(1, 0) = -xy;
  inertia(1, 2) = inertia(2, 1) = -yz;
  inertia(0, 2) = inertia(2, 0) = -zx;
  inertia *= density;

  props.center_of_mass = ref + c;
  props.inertia = inertia;
  set_principal_frame(props);
  return props;
}

MassProperties compute_shell_properties(const TriangleMesh& mesh, double areal_density) {
  if (!(std::isfinite(areal_density) && areal_density > 0)) {
    std::ostringstream msg;
    msg << "mass properties: surface density must be a finite positive number, got " << areal_density;
    throw Error(msg.str());
  }
  const Vec3 ref = bounding_box(mesh.vertices).center();
  // Over a triangle of area A with corners p0, p1, p2 (uniform density): ∫dA = A, ∫p dA = A·s/3 and
  // ∫p pᵀ dA = A/12·(Σ pₖpₖᵀ + s sᵀ) with s = p0 + p1 + p2 (exact: the integrand is quadratic).
  double area = 0;
  Vec3 first = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  for (const Triangle& t : mesh.triangles) {
    const Vec3 p0 = mesh.vertices[static_cast<std::size_t>(t[0])] - ref;
    const Vec3 p1 = mesh.vertices[static_cast<std::size_t>(t[1])] - ref;
    const Vec3 p2 = mesh.vertices[static_cast<std::size_t>(t[2])] - ref;
    const double a = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    const Vec3 s = p0 + p1 + p2;
    area += a;
    first += a / 3.0 * s;
    second +=
        a / 12.0 * (p0 * p0.transpose() + p1 * p1.transpose() + p2 * p2.transpose() + s * s.transpose());
  }
  MassProperties props;
  props.area = area;
  props.mass = areal_density * area;
  if (!(area > 0)) {
    props.center_of_mass = ref;
    return props;
  }
  const Vec3 c = first / area;
  const Mat3 covariance = second - area * c * c.transpose();  // ∫(p − c)(p − c)ᵀ dA
  props.center_of_mass = ref + c;
  props.inertia = areal_density * (covariance.trace() * Mat3::Identity() - covariance);
  set_principal_frame(props);
  return props;
}

}  // namespace repose
