// The contact problem as one linear complementarity problem, solved by Lemke's method
// (contact_problem.hpp: solve_contacts' fallback where Gauss–Seidel does not converge).
#include <cmath>
#include <numbers>

#include "../tolerances.hpp"
#include "contact_problem.hpp"
#include "lemke.hpp"

namespace repose::sim {

// The problem as one LCP, solved by Lemke's method where Gauss–Seidel does not converge (Stewart & Trinkle
// 1996's formulation, at the level of the values x): a sliding point carries λ ≥ 0 along (−μ·ŝ, 1),
// complementary to its x_n; a point at rest carries λ ≥ 0 and β_k ≥ 0 along the pyramid's edges e_k, with
// its slip speed γ ≥ 0: x_n ⊥ λ, e_k·x_t + γ ⊥ β_k, μ·λ − Σβ_k ⊥ γ (it sticks, or slides with the pyramid's
// maximal dissipation). A given normal reaction is not part of it. Empty where Lemke's method ends on a ray:
// no solution (Painlevé's inconsistent case) or one it cannot reach (several solutions).
std::optional<ContactSolution> solve_contacts_by_pivoting(const ContactProblem& p, const Vec3& lin,
                                                          const Vec3& ang,
                                                          std::span<const PointCondition> conditions) {
  const std::size_t n = p.arms.size();
  // Each point's force directions (the columns G_i: F_i = G_i·z_i) and its first unknown's index.
  std::vector<Eigen::MatrixXd> G(n);
  std::vector<Eigen::Index> first(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const PointCondition& c = conditions[i];
    if (c.rule == PointRule::given_normal) return std::nullopt;
    if (c.rule == PointRule::sliding) {
      G[i] = Vec3(-p.friction * c.direction.x(), -p.friction * c.direction.y(), 1);
    } else {
      G[i] = Eigen::MatrixXd::Zero(3, 1 + tol::kPyramidEdges);
      G[i](2, 0) = 1;
      for (int k = 0; k < tol::kPyramidEdges; ++k) {
        const double angle = 2 * std::numbers::pi * k / tol::kPyramidEdges;
        G[i](0, 1 + k) = std::cos(angle), G[i](1, 1 + k) = std::sin(angle);
      }
    }
    // A point at rest has one more unknown, γ.
    first[i + 1] = first[i] + G[i].cols() + (c.rule == PointRule::sliding ? 0 : 1);
  }
  const Eigen::Index size = first[n];
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(size, size);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(size);
  for (std::size_t i = 0; i < n; ++i) {
    // The rows of point i: its x_n, then (at rest) e_k·x_t; Gᵢᵀ·x_i with the first row the normal alone (a
    // sliding direction is not a row).
    const Eigen::Index cols_i = G[i].cols();
    Eigen::MatrixXd rows_i = G[i].transpose();
    rows_i.row(0) = Eigen::RowVector3d(0, 0, 1);
    q.segment(first[i], cols_i) = rows_i * point_value(p, i, lin, ang);
    for (std::size_t j = 0; j < n; ++j) {
      const Mat3 W = delassus_block(p.mass, p.inverse_inertia, p.arms[i], p.arms[j]);
      M.block(first[i], first[j], cols_i, G[j].cols()) = rows_i * W * G[j];
    }
    if (conditions[i].rule == PointRule::sliding) continue;
    // The cone's rows and γ's column.
    const Eigen::Index gamma = first[i] + cols_i;
    M.block(first[i] + 1, gamma, tol::kPyramidEdges, 1).setOnes();
    M(gamma, first[i]) = p.friction;
    M.block(gamma, first[i] + 1, 1, tol::kPyramidEdges).setConstant(-1);
  }
  // Lemke's method ends within a few pivots per unknown; the bound keeps a degenerate problem finite.
  const std::optional<Eigen::VectorXd> z =
      solve_lcp(M, q, static_cast<int>(tol::kLemkePivotsPerUnknown * size + tol::kLemkePivotsBase));
  if (!z || !z->allFinite()) return std::nullopt;
  ContactSolution s;
  s.reactions.resize(n, Vec3::Zero());
  s.lin = lin;
  s.ang = ang;
  for (std::size_t i = 0; i < n; ++i) {
    s.reactions[i] = G[i] * z->segment(first[i], G[i].cols());
    // Within the cone to round-off (the pyramid is inside it): the round-off taken off.
    const double cone = p.friction * s.reactions[i].z(), tangential = s.reactions[i].head<2>().norm();
    if (tangential > cone) s.reactions[i].head<2>() *= tangential > 0 ? cone / tangential : 0.0;
    s.lin += s.reactions[i] / p.mass;
    s.ang += p.inverse_inertia * p.arms[i].cross(s.reactions[i]);
  }
  return s;
}

}  // namespace repose::sim
