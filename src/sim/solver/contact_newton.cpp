// Newton's method on the contact problem's Alart–Curnier equations (contact_problem.hpp): where block
// Gauss–Seidel creeps (an edge pressed at the limit of its friction cone shares its tangential force along
// the edge between its two points, and the sweeps converge slowly or not at all), a semismooth Newton
// iteration from the sweeps' reactions reaches the solution in a few steps (Alart & Curnier 1991).
//
// The equations, point by point with y = R − ρ·x(R) (x = x0 + W·R the point's value, ρ > 0):
//   unilateral    R_n = max(0, y_n),  R_t = proj(y_t, disk of radius μ·max(0, y_n))
//   sliding       R_n = max(0, y_n),  R_t = −μ·max(0, y_n)·ŝ
//   given_normal  R_n = the given λ,  R_t = proj(y_t, disk of radius μ·λ)
// whose solutions are exactly the reactions of Coulomb's law with complementarity: R_n > 0 only where
// x_n = 0; R_t strictly inside the disk only where x_t = 0, and on its edge opposite to x_t otherwise.
#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "../tolerances.hpp"
#include "contact_problem.hpp"

namespace repose::sim {

namespace {

using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3 * tol::kNewtonStackPoints,
                                  3 * tol::kNewtonStackPoints>;
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3 * tol::kNewtonStackPoints, 1>;

template <class Matrix, class Vector>
struct Residual {
  Vector phi;  // R − F(R), zero at a solution
  Matrix jacobian;
};

// The residual of the equations above at R, and (with_jacobian) an element of its generalized Jacobian.
template <class Matrix, class Vector>
Residual<Matrix, Vector> residual(const Matrix& W, const Vector& x0, const Vector& R, const Vector& rho,
                                  double mu, std::span<const PointCondition> conditions, bool with_jacobian) {
  const Eigen::Index n = static_cast<Eigen::Index>(conditions.size());
  const Vector x = x0 + W * R;
  Residual<Matrix, Vector> out;
  out.phi.resize(3 * n);
  // dF/dR = D·(E − ρ·W), D block-diagonal: each point's derivative of F_i with respect to its own y_i.
  Matrix D = Matrix::Zero(3 * n, 3 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const PointCondition& c = conditions[static_cast<std::size_t>(i)];
    const Vec3 r = R.template segment<3>(3 * i);
    const Vec3 y = r - rho(i) * x.template segment<3>(3 * i);
    const bool pressed = y.z() > 0;
    Vec3 F = Vec3::Zero();
    Mat3 dF = Mat3::Zero();
    if (c.rule == PointRule::sliding) {
      if (pressed) {
        F = Vec3(-mu * y.z() * c.direction.x(), -mu * y.z() * c.direction.y(), y.z());
        dF.col(2) = Vec3(-mu * c.direction.x(), -mu * c.direction.y(), 1);
      }
    } else {
      const double normal = c.rule == PointRule::given_normal ? c.normal : std::max(y.z(), 0.0);
      const double radius = mu * normal;
      const Vec2 yt = y.head<2>();
      const double norm = yt.norm();
      F.z() = normal;
      if (c.rule == PointRule::unilateral && pressed) dF(2, 2) = 1;
      if (norm <= radius) {
        F.head<2>() = yt;
        dF.topLeftCorner<2, 2>().setIdentity();
      } else if (norm > 0) {
        const Vec2 u = yt / norm;
        F.head<2>() = radius * u;
        dF.topLeftCorner<2, 2>() = radius / norm * (Eigen::Matrix2d::Identity() - u * u.transpose());
        if (c.rule == PointRule::unilateral && pressed) dF.block<2, 1>(0, 2) = mu * u;
      }
    }
    out.phi.template segment<3>(3 * i) = r - F;
    D.template block<3, 3>(3 * i, 3 * i) = dF;
  }
  if (with_jacobian) {
    Matrix dy = -W;
    for (Eigen::Index i = 0; i < n; ++i) dy.template middleRows<3>(3 * i) *= rho(i);
    dy += Matrix::Identity(3 * n, 3 * n);
    out.jacobian = Matrix::Identity(3 * n, 3 * n) - D * dy;
  }
  return out;
}

template <class Matrix, class Vector>
std::optional<PointList<Vec3>> newton(const ContactProblem& p, const Vec3& lin, const Vec3& ang,
                                      std::span<const PointCondition> conditions,
                                      std::span<const Vec3> start) {
  const std::size_t n = p.arms.size();
  const Eigen::Index size = static_cast<Eigen::Index>(3 * n);
  Matrix W(size, size);
  Vector x0(size), R(size), rho(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const auto I = static_cast<Eigen::Index>(3 * i);
    for (std::size_t j = 0; j < n; ++j)
      W.template block<3, 3>(I, static_cast<Eigen::Index>(3 * j)) =
          delassus_block(p.mass, p.inverse_inertia, p.arms[i], p.arms[j]);
    x0.template segment<3>(I) = point_value(p, i, lin, ang);
    R.template segment<3>(I) = start[i];
    // ρ of the order of the point's own compliance's inverse: the equations' two terms then weigh alike.
    rho(static_cast<Eigen::Index>(i)) = 3 / W.template block<3, 3>(I, I).trace();
  }
  if (!W.allFinite() || !x0.allFinite() || !R.allFinite()) return std::nullopt;
  // Round-off of the residual: the reactions' and the values' scales (R and ρ·x enter it alike), times the
  // terms summed in W·R.
  const double force_scale = R.template lpNorm<Eigen::Infinity>() + (rho.maxCoeff() * p.scale);
  const double tolerance =
      4 * std::numeric_limits<double>::epsilon() * static_cast<double>(size) * force_scale;
  Residual<Matrix, Vector> at = residual(W, x0, R, rho, p.friction, conditions, true);
  double merit = at.phi.squaredNorm();
  for (int step = 0; step < tol::kNewtonSteps; ++step) {
    if (at.phi.template lpNorm<Eigen::Infinity>() <= tolerance) break;
    // The Jacobian is singular where the reactions are not determined (an edge's two points along it):
    // the least-norm step.
    const Vector d = at.jacobian.completeOrthogonalDecomposition().solve(-at.phi);
    if (!d.allFinite()) return std::nullopt;
    double alpha = 1;
    bool decreased = false;
    for (int h = 0; h < tol::kNewtonHalvings; ++h, alpha *= 0.5) {
      const Residual<Matrix, Vector> trial =
          residual<Matrix, Vector>(W, x0, R + alpha * d, rho, p.friction, conditions, false);
      if (trial.phi.squaredNorm() < merit) {
        R += alpha * d;
        decreased = true;
        break;
      }
    }
    if (!decreased) break;  // at round-off, or stuck
    at = residual(W, x0, R, rho, p.friction, conditions, true);
    merit = at.phi.squaredNorm();
  }
  PointList<Vec3> reactions(n, Vec3::Zero());
  for (std::size_t i = 0; i < n; ++i) reactions[i] = R.template segment<3>(static_cast<Eigen::Index>(3 * i));
  return reactions;
}

}  // namespace

std::optional<PointList<Vec3>> solve_contacts_by_newton(const ContactProblem& p, const Vec3& lin,
                                                        const Vec3& ang,
                                                        std::span<const PointCondition> conditions,
                                                        std::span<const Vec3> start) {
  if (p.arms.size() <= tol::kNewtonStackPoints)
    return newton<SmallMatrix, SmallVector>(p, lin, ang, conditions, start);
  return newton<Eigen::MatrixXd, Eigen::VectorXd>(p, lin, ang, conditions, start);
}

}  // namespace repose::sim
