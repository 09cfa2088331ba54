// Internal: Lemke's complementary pivoting method for the linear complementarity problem LCP(M, q): find
// z ≥ 0 with w = M·z + q ≥ 0 and zᵀ·w = 0 (Lemke 1965; Cottle, Pang & Stone, The Linear Complementarity
// Problem, 1992, §4.4). The contact problem's fallback where block Gauss–Seidel does not converge
// (contact_problem.cpp).
//
// The covering vector is all ones and ties in the ratio test are broken lexicographically, so the method
// never cycles: it ends in a solution or on a secondary ray (no solution it can reach: Painlevé's case for a
// contact problem with sliding friction). It solves every LCP whose M is copositive-plus and feasible (a
// frictionless contact problem) and every P-matrix LCP (a unique solution).
#pragma once

#include <Eigen/Dense>
#include <optional>

namespace repose::sim {

/// z, or empty on a secondary ray, past `max_pivots` pivots, or where z fails the check against M and q
/// (|min(z_i, w_i)| within 1e-9 of the vectors' scales: a near-singular M's pivots can lose the answer).
std::optional<Eigen::VectorXd> solve_lcp(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, int max_pivots);

}  // namespace repose::sim
