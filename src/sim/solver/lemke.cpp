// Lemke's method (lemke.hpp).
#include "lemke.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "../tolerances.hpp"

namespace repose::sim {

std::optional<Eigen::VectorXd> solve_lcp(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, int max_pivots) {
  const Eigen::Index n = q.size();
  if (q.minCoeff() >= 0) return Eigen::VectorXd::Zero(n);
  // The tableau B⁻¹·[I | −M | −e | q] over the columns w (0..n−1), z (n..2n−1), z0 (2n) and the values
  // (2n+1). Its first n columns are B⁻¹ itself, whose rows break ties in the ratio test.
  const Eigen::Index z0 = 2 * n, values = 2 * n + 1;
  Eigen::MatrixXd T(n, 2 * n + 2);
  T.leftCols(n).setIdentity();
  T.middleCols(n, n) = -M;
  T.col(z0).setConstant(-1);
  T.col(values) = q;
  std::vector<Eigen::Index> basis(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) basis[static_cast<std::size_t>(i)] = i;
  // Pivot tolerance relative to the data's scale.
  const double scale = std::max(1.0, M.cwiseAbs().maxCoeff());
  const double tiny = tol::kLemkeTiny * scale;
  const auto pivot = [&](Eigen::Index row, Eigen::Index col) {
    T.row(row) /= T(row, col);
    for (Eigen::Index i = 0; i < n; ++i)
      if (i != row && T(i, col) != 0) T.row(i) -= T(i, col) * T.row(row);
    const Eigen::Index left = basis[static_cast<std::size_t>(row)];
    basis[static_cast<std::size_t>(row)] = col;
    return left;
  };
  // z0 enters at the row of the most negative q: every w is then ≥ 0.
  Eigen::Index row = 0;
  q.minCoeff(&row);
  Eigen::Index left = pivot(row, z0);
  for (int k = 0; k < max_pivots; ++k) {
    // The entering column is the complement of the variable that left.
    const Eigen::Index entering = left < n ? left + n : left - n;
    // Ratio test over the rows whose value the entering variable decreases (−T(i, entering) < 0 in B⁻¹·A's
    // sign convention: the basic variables are T(:, values) − t·T(:, entering)).
    Eigen::Index best = -1;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!(T(i, entering) > tiny)) continue;
      if (best < 0) {
        best = i;
        continue;
      }
      // Lexicographic: (value, B⁻¹ row) / pivot, the smallest.
      const double a = T(i, values) / T(i, entering), b = T(best, values) / T(best, entering);
      if (a < b - tol::kLemkeTie * std::max(std::abs(a), std::abs(b))) {
        best = i;
      } else if (!(a > b + tol::kLemkeTie * std::max(std::abs(a), std::abs(b)))) {
        for (Eigen::Index j = 0; j < n; ++j) {
          const double x = T(i, j) / T(i, entering), y = T(best, j) / T(best, entering);
          if (x < y) {
            best = i;
            break;
          }
          if (x > y) break;
        }
      }
    }
    if (best < 0) return std::nullopt;  // a secondary ray
    // z0 leaves whenever it can (the solution is then complementary).
    for (Eigen::Index i = 0; i < n; ++i)
      if (basis[static_cast<std::size_t>(i)] == z0 && T(i, entering) > tiny) {
        const double a = T(i, values) / T(i, entering), b = T(best, values) / T(best, entering);
        if (!(a > b + tol::kLemkeTie * std::max(std::abs(a), std::abs(b)))) best = i;
      }
    left = pivot(best, entering);
    if (left == z0) {
      Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Index b = basis[static_cast<std::size_t>(i)];
        if (b >= n && b < 2 * n) z(b - n) = std::max(T(i, values), 0.0);
      }
      // The tableau's round-off grows with each pivot on a near-singular M (two points of an edge share a
      // constraint): the answer is checked against M and q themselves, componentwise min(z, w) ≈ 0, w on
      // the scale of the data q (a lost answer can have huge z whose M·z would hide a negative w).
      const Eigen::VectorXd w = M * z + q;
      const double z_scale = std::max(z.cwiseAbs().maxCoeff(), tol::kTinyScale);
      const double w_scale = q.cwiseAbs().maxCoeff();
      for (Eigen::Index i = 0; i < n; ++i)
        if (std::abs(std::min(z(i) / z_scale, w(i) / w_scale)) > tol::kLemkeResidual) return std::nullopt;
      return z;
    }
  }
  return std::nullopt;
}

}  // namespace repose::sim
