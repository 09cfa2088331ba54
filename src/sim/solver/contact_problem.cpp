// The frictional contact problem (contact_problem.hpp).
#include "contact_problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "../tolerances.hpp"

namespace repose::sim {

namespace {

// What a sweep met: sliding points with no consistent normal reaction, points whose sliding direction was not
// found.
struct Counts {
  int painleve = 0;
  int unresolved = 0;
};

// The root of φ(β) = |p(β)| − μ·λ(p(β)) in [lo, hi] (φ(lo) > 0 > φ(hi)), p(β) = (A + β·I)⁻¹·b, λ(p) = c0 +
// c·p: Newton's method on ψ(β) = 1/|p(β)| − 1/(μ·λ(p(β))), which has the same root and is nearly linear in β
// (exactly where A is a multiple of I and c = 0: Reinsch 1971, Moré & Sorensen 1983), kept inside the
// bracket, which each iterate narrows by the sign of φ; a step that would leave it, or not halve the step
// before, bisects instead (Numerical Recipes' rtsafe). Stops at |φ| within 4 ulps of its terms or a bracket
// of 2 ulps.
double secular_root(const Eigen::Matrix2d& A, const Vec2& b, double c0, const Vec2& c, double mu, double lo,
                    double hi) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  double beta = lo, step_before = hi - lo;
  for (int k = 0; k < tol::kCapSearchSteps; ++k) {
    const double a = A(0, 0) + beta, d = A(1, 1) + beta, off = A(0, 1), det = a * d - off * off;
    const auto solve = [&](const Vec2& v) -> Vec2 {
      return Vec2(d * v.x() - off * v.y(), a * v.y() - off * v.x()) / det;
    };
    const Vec2 p = solve(b), dp = -solve(p);
    const double norm = p.norm(), lambda = c0 + c.dot(p), phi = norm - mu * lambda;
    if (std::abs(phi) <= 4 * eps * (norm + mu * std::abs(lambda))) return beta;  // a root to round-off
    (phi > 0 ? lo : hi) = beta;
    if (hi - lo <= 2 * eps * hi) break;
    // Newton's step where it stays inside the bracket and at least halves the step before (rtsafe).
    double next = 0.5 * (lo + hi);
    if (norm > 0 && lambda > 0) {
      const double psi = 1 / norm - 1 / (mu * lambda);
      const double slope = -p.dot(dp) / (norm * norm * norm) + c.dot(dp) / (mu * lambda * lambda);
      const double newton = beta - psi / slope;
      if (newton > lo && newton < hi && 2 * std::abs(newton - beta) <= step_before) next = newton;
    }
    step_before = std::abs(next - beta);
    beta = next;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

// The sliding reaction R = (−p, λ) of one point, p = μ·λ·ŝ, with the slip after it, x_t = b − A·p, along ŝ
// (friction opposes the slip). Along ŝ means b − A·p = β·p for some β ≥ 0, so p(β) = (A + β·I)⁻¹·b, and the
// reaction is on the cone's edge, |p| = μ·λ(p) with λ(p) = c0 + c·p: a root in β of the secular equation
// φ(β) = |p(β)| − μ·λ(p(β)), as in a trust region's step (Moré & Sorensen 1983).
//   unilateral (x_n = 0): A = W_tt − w_tn·w_ntᵀ/W_nn (a Schur complement of W, symmetric positive definite),
//                         b = f_t − w_tn·f_n/W_nn, λ(p) = (w_nt·p − f_n)/W_nn;
//   given normal λ:       A = W_tt, b = f_t + λ·w_tn, λ(p) = λ.
// Called where sticking (β = 0) is outside the cone, φ(0) > 0; as β → ∞, p → 0 and φ → −μ·λ(0) < 0: a root
// exists. The bracket is found by halving or doubling β from the scale trace(A) and closed by secular_root.
// Where φ has several roots (Painlevé's non-uniqueness at a point at rest) the one found this way is taken.
// Empty only when the data are not finite.
std::optional<Vec3> sliding_reaction(const Mat3& W, const Vec3& f, double mu, double given_normal) {
  const bool unilateral = given_normal < 0;
  const Vec2 wtn = W.block<2, 1>(0, 2), wnt = W.block<1, 2>(2, 0).transpose();
  const Eigen::Matrix2d A = unilateral
                                ? Eigen::Matrix2d(W.topLeftCorner<2, 2>() - wtn * wnt.transpose() / W(2, 2))
                                : Eigen::Matrix2d(W.topLeftCorner<2, 2>());
  const Vec2 b =
      unilateral ? Vec2(f.head<2>() - wtn * f.z() / W(2, 2)) : Vec2(f.head<2>() + given_normal * wtn);
  const double c0 = unilateral ? -f.z() / W(2, 2) : given_normal;
  const Vec2 c = unilateral ? Vec2(wnt / W(2, 2)) : Vec2::Zero();
  if (!A.allFinite() || !b.allFinite() || !std::isfinite(c0) || !(c0 >= 0)) return std::nullopt;
  if (!(mu * c0 > 0) || !(b.norm() > 0)) return Vec3(0, 0, c0);  // no friction to apply
  const auto p_of = [&](double beta) -> Vec2 {
    const double a = A(0, 0) + beta, d = A(1, 1) + beta, off = A(0, 1);
    const double det = a * d - off * off;
    return Vec2(d * b.x() - off * b.y(), a * b.y() - off * b.x()) / det;
  };
  const auto phi = [&](double beta) {
    const Vec2 p = p_of(beta);
    return p.norm() - mu * (c0 + c.dot(p));
  };
  // The bracket [lo, hi] with φ(lo) > 0 ≥ φ(hi); each search is bounded (2^±1100 covers every double).
  double hi = std::max(A.trace(), tol::kTinyScale), lo = 0;
  if (phi(hi) > 0) {
    lo = hi;
    for (int k = 0; k < tol::kDoublingsOfADouble && phi(hi) > 0; ++k) lo = hi, hi *= 2;
  } else {
    for (int k = 0; k < tol::kDoublingsOfADouble && hi > 0 && !(phi(0.5 * hi) > 0); ++k) hi *= 0.5;
    lo = 0.5 * hi;
    if (!(phi(lo) > 0)) lo = 0;
  }
  const double f_lo = phi(lo), f_hi = phi(hi);
  if (!(f_lo > 0) || f_hi > 0) return std::nullopt;
  double beta = hi;
  if (f_hi < 0) beta = secular_root(A, b, c0, c, mu, lo, hi);
  const Vec2 p = p_of(beta);
  if (!(p.norm() > 0)) return Vec3(0, 0, c0);
  const Vec2 s = p.normalized();
  const double lambda = std::max(c0 + c.dot(p), 0.0);
  return Vec3(-mu * lambda * s.x(), -mu * lambda * s.y(), lambda);
}

namespace {

// One point's reaction given its value `f` without it (the others' reactions included) and its own block W of
// the Delassus matrix (x = f + W·R), by its rule (contact_problem.hpp).
// Each point's Delassus block, and for a point at rest (unilateral) its factorisation, which every sweep's
// sticking reaction solves with: made once per solve, not once per sweep.
struct DiagonalBlocks {
  PointList<Mat3> W;
  // (none where the point's rule is not unilateral: a default LDLT leaves its state unset, which a move of
  // the list to the heap beyond kInlinePoints would read)
  PointList<std::optional<Eigen::LDLT<Mat3>>> stick;
};

DiagonalBlocks diagonal_blocks(const ContactProblem& p, std::span<const PointCondition> conditions) {
  DiagonalBlocks d;
  for (std::size_t i = 0; i < p.arms.size(); ++i) {
    d.W.push_back(delassus_block(p.mass, p.inverse_inertia, p.arms[i]));
    if (conditions[i].rule == PointRule::unilateral)
      d.stick.emplace_back(std::in_place, d.W.back());
    else
      d.stick.emplace_back(std::nullopt);
  }
  return d;
}

Vec3 local_reaction(const Mat3& W, const std::optional<Eigen::LDLT<Mat3>>& stick_solver, const Vec3& f,
                    double mu, const PointCondition& c, Counts& counts) {
  const Eigen::Matrix2d wtt = W.topLeftCorner<2, 2>();
  const Vec2 wtn = W.block<2, 1>(0, 2);
  const Vec2 ft = f.head<2>();
  if (c.rule == PointRule::sliding) {
    if (f.z() >= 0) return Vec3::Zero();
    const double d = sliding_compliance(W, mu, c.direction);
    if (!(d > 0)) {
      ++counts.painleve;
      return Vec3::Zero();
    }
    const double lambda = -f.z() / d;
    return Vec3(-mu * lambda * c.direction.x(), -mu * lambda * c.direction.y(), lambda);
  }
  const double normal = c.normal;
  if (c.rule == PointRule::unilateral) {
    if (f.z() >= 0) return Vec3::Zero();
    const Vec3 stick = -stick_solver->solve(f);
    if (stick.z() > 0 && stick.head<2>().norm() <= mu * stick.z()) return stick;
    // Sliding: P = (−μλŝ, λ) with u_n = 0 and ŝ the direction of u_t after.
    const std::optional<Vec3> sliding = sliding_reaction(W, f, mu, -1);
    if (sliding) return *sliding;
    ++counts.unresolved;  // the frictionless plastic reaction instead
    return Vec3(0, 0, -f.z() / W(2, 2));
  }
  // The normal impulse given: the tangential one that stops the slip, if the cone allows, else sliding.
  const Vec2 stick = -wtt.ldlt().solve(ft + wtn * normal);
  if (stick.norm() <= mu * normal) return Vec3(stick.x(), stick.y(), normal);
  const std::optional<Vec3> sliding = sliding_reaction(W, f, mu, normal);
  if (sliding) return *sliding;
  ++counts.unresolved;  // no tangential reaction instead
  return Vec3(0, 0, normal);
}

// The body's values with the reactions `reactions` applied to (lin, ang).
void apply_reactions(const ContactProblem& p, const Vec3& lin, const Vec3& ang, ContactSolution& s) {
  s.lin = lin;
  s.ang = ang;
  for (std::size_t i = 0; i < p.arms.size(); ++i) {
    s.lin += s.reactions[i] / p.mass;
    s.ang += p.inverse_inertia * p.arms[i].cross(s.reactions[i]);
  }
}

// One block Gauss–Seidel sweep over the points; the largest change of a point's value it made. `at_start`:
// scratch for the values at the sweep's start (a solve's sweeps share it).
double sweep_once(const ContactProblem& p, const DiagonalBlocks& diagonal,
                  std::span<const PointCondition> conditions, ContactSolution& s, Counts& counts,
                  PointList<Vec3>& at_start) {
  const std::size_t n = p.arms.size();
  at_start.resize(n, Vec3::Zero());
  for (std::size_t i = 0; i < n; ++i) at_start[i] = point_value(p, i, s.lin, s.ang);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 f = point_value(p, i, s.lin, s.ang) - diagonal.W[i] * s.reactions[i];
    const Vec3 next = local_reaction(diagonal.W[i], diagonal.stick[i], f, p.friction, conditions[i], counts);
    const Vec3 delta = next - s.reactions[i];
    s.lin += delta / p.mass;
    s.ang += p.inverse_inertia * p.arms[i].cross(delta);
    s.reactions[i] = next;
  }
  double change = 0;
  for (std::size_t i = 0; i < n; ++i)
    change = std::max(change, (point_value(p, i, s.lin, s.ang) - at_start[i]).norm());
  return change;
}

}  // namespace

double sliding_compliance(const Mat3& W, double mu, const Vec2& direction) {
  return W(2, 2) - mu * W.block<1, 2>(2, 0).dot(direction);
}

namespace {
// Lemke's answer, whose points at rest have the pyramid's friction (up to 15° off the slip and 3.4 % short of
// the cone), made exact where it can be (issue 48): Newton's method on the exact cone from it, accepted where
// a Gauss–Seidel sweep from Newton's reactions changes no value by more than tol::kPolished of the scale (a
// solution of the exact problem to that accuracy; the sweep's own reactions are kept). Else the pyramid's
// answer, flagged (ContactSolution::pyramid).
ContactSolution exact_from_pyramid(const ContactProblem& p, const DiagonalBlocks& diagonal, const Vec3& lin,
                                   const Vec3& ang, std::span<const PointCondition> conditions,
                                   ContactSolution pyramid) {
  const bool at_rest = std::any_of(conditions.begin(), conditions.end(),
                                   [](const PointCondition& c) { return c.rule == PointRule::unilateral; });
  if (!at_rest) return pyramid;  // sliding points only: Lemke's problem is the exact one
  const std::size_t n = p.arms.size();
  if (n <= tol::kMaxPolishedPoints) {
    if (auto newton = solve_contacts_by_newton(p, lin, ang, conditions, view(pyramid.reactions))) {
      ContactSolution s;
      s.reactions = *newton;
      apply_reactions(p, lin, ang, s);
      Counts counts;
      PointList<Vec3> at_start;
      const double change = sweep_once(p, diagonal, conditions, s, counts, at_start);
      if (change <= tol::kPolished * p.scale && counts.painleve == 0 && counts.unresolved == 0) return s;
    }
  }
  pyramid.pyramid = true;
  return pyramid;
}
}  // namespace

ContactSolution solve_contacts(const ContactProblem& p, const Vec3& lin, const Vec3& ang,
                               std::span<const PointCondition> conditions, std::span<const Vec3> start) {
  const std::size_t n = p.arms.size();
  const DiagonalBlocks diagonal = diagonal_blocks(p, conditions);
  ContactSolution s;
  s.reactions.assign(n, Vec3::Zero());
  s.lin = lin;
  s.ang = ang;
  if (start.size() == n) {
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& r = start[i];
      if (!r.allFinite()) continue;
      s.reactions[i] = r;
      s.lin += r / p.mass;
      s.ang += p.inverse_inertia * p.arms[i].cross(r);
    }
  }
  double previous_change = INFINITY;
  int next_polish = tol::kSweepsBeforeNewton;
  PointList<Vec3> at_start(n, Vec3::Zero());
  for (int sweep = 0; sweep < tol::kContactSweeps; ++sweep) {
    Counts counts;
    const double change = sweep_once(p, diagonal, conditions, s, counts, at_start);
    double largest = 0, round_off = 0;
    for (std::size_t i = 0; i < n; ++i) {
      largest = std::max(largest, point_value(p, i, s.lin, s.ang).norm());
      round_off = std::max(round_off, s.lin.norm() + s.ang.norm() * p.arms[i].norm() +
                                          (p.offsets.empty() ? 0.0 : p.offsets[i].norm()));
    }
    s.painleve = counts.painleve;
    // Converged: the change within the tolerance, or stalled at the values' round-off (a body whose points
    // nearly rest while it turns: its velocities' round-off can exceed 1e-14 of the points' scale).
    const bool stalled = change <= tol::kContactRoundOff * round_off && change >= previous_change;
    const bool slow = change > tol::kSlowSweep * previous_change;
    previous_change = change;
    if (change <= tol::kContactConverged * p.scale || stalled) {
      s.converged = counts.unresolved == 0;
      // A sliding point with no consistent force on its own may have one with the others (the whole LCP
      // decides Painlevé's case).
      if (s.painleve > 0)
        if (auto pivoted = solve_contacts_by_pivoting(p, lin, ang, conditions))
          return exact_from_pyramid(p, diagonal, lin, ang, conditions, *pivoted);
      return s;
    }
    if (!(largest <= tol::kContactDiverged * p.scale)) break;  // diverging (or not finite)
    if (n <= tol::kMaxPolishedPoints && slow && sweep + 1 >= next_polish && counts.painleve == 0 &&
        counts.unresolved == 0) {
      next_polish = 2 * (sweep + 1);
      // Polished by Newton's method; the sweeps' own test then accepts the result or sweeps on from it.
      if (auto newton = solve_contacts_by_newton(p, lin, ang, conditions, view(s.reactions))) {
        s.reactions = *newton;
        s.lin = lin;
        s.ang = ang;
        for (std::size_t i = 0; i < n; ++i) {
          s.lin += s.reactions[i] / p.mass;
          s.ang += p.inverse_inertia * p.arms[i].cross(s.reactions[i]);
        }
        previous_change = INFINITY;
      }
    }
  }
  if (auto pivoted = solve_contacts_by_pivoting(p, lin, ang, conditions))
    return exact_from_pyramid(p, diagonal, lin, ang, conditions, *pivoted);
  s.converged = false;
  s.solved = false;
  return s;
}

}  // namespace repose::sim
