// design_for_toss (toss_design.hpp): quasi-Newton steps on the tossed residual over the quasi-static targets,
// each iterate a quasi-static descent (descent.hpp) from the start.
#include "repose/design/toss_design.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>

#include "descent.hpp"
#include "repose/error.hpp"
#include "tossed.hpp"

namespace repose {

namespace {

// The smallest quasi-static probability a surrogate target asks of an outcome: an outcome asked for 0 loses
// its stable faces, and with them every gradient that could bring it back.
constexpr double kSurrogateFloor = 1e-3;
// An estimate's standard error is at most this fraction of the residual it is to resolve.
constexpr double kErrorPerResidual = 1.0 / 3;
// The most a step changes any outcome's quasi-static target (a trust region: the Jacobian is a local model).
constexpr double kMaxSurrogateStep = 0.1;
// Singular values of the Jacobian (restricted to changes that keep Σq = 1) below this fraction of the largest
// are taken as zero: the least-squares step then leaves that direction alone.
constexpr double kRankThreshold = 1e-3;

using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;

void check(const TossDesignOptions& o) {
  if (o.model.drops == 0 || o.model.check_drops == 0)
    throw Error("design: --drops and --check-drops must be at least 1");
  if (o.model.drops > UINT64_MAX - o.model.check_drops)
    throw Error("design: --drops + --check-drops overflow");
  if (o.model.settings.method != PoseMethod::dynamic)
    throw Error("design: the tossed model needs the dynamic method");
  if (o.max_iterations < 0 || o.max_retries < 0 || !(o.tolerance >= 0) || o.min_drops == 0 ||
      !(o.difference_step > 0 && o.difference_step < 0.5))
    throw Error(
        "design: --toss-iterations must be >= 0, the tossed tolerance >= 0, the smallest estimate >= 1 drop "
        "and the difference step in (0, 0.5)");
}

// The minimum-norm least-squares solver of `a`, singular values below kRankThreshold of the largest taken as
// zero. The threshold must be set before the decomposition: Eigen computes the complete orthogonal factor Z
// for the rank it sees then, and a solve at a lower rank set afterwards would apply a Z never computed (it
// read uninitialised coefficients: a run's steps changed from one run to the next).
Eigen::CompleteOrthogonalDecomposition<Matrix> least_squares(const Matrix& a) {
  Eigen::CompleteOrthogonalDecomposition<Matrix> out(a.rows(), a.cols());
  out.setThreshold(kRankThreshold);
  out.compute(a);
  return out;
}

// The first `k` entries (the outcomes) of a probability vector.
Vector outcomes_of(const std::vector<double>& p, std::size_t k) {
  return Eigen::Map<const Vector>(p.data(), static_cast<Eigen::Index>(k));
}

// A surrogate target: at least kSurrogateFloor per outcome, summing to 1.
Vector project(Vector q) {
  q = q.cwiseMax(kSurrogateFloor);
  return q / q.sum();
}

DesignTarget with_probabilities(DesignTarget target, const Vector& q) {
  for (std::size_t k = 0; k < target.outcomes.size(); ++k)
    target.outcomes[k].probability = q[static_cast<Eigen::Index>(k)];
  return target;
}

// Σ (p̂ − t)² − Σ p̂(1 − p̂)/(n − 1): unbiased for Σ (p − t)² (E p̂(1 − p̂) = p(1 − p)(n − 1)/n).
double unbiased_objective(const Vector& p, const Vector& t, std::uint64_t n) {
  const double variance = n > 1 ? (p.array() * (1 - p.array())).sum() / static_cast<double>(n - 1) : 0.0;
  return (p - t).squaredNorm() - variance;
}

}  // namespace

namespace detail {

Eigen::MatrixXd difference_jacobian(const Eigen::MatrixXd& dq, const Eigen::MatrixXd& dp) {
  const Eigen::Index n = dq.rows();
  const Matrix keep_sum = Matrix::Identity(n, n) - Matrix::Constant(n, n, 1.0 / static_cast<double>(n));
  // J dq = dp in least squares: Jᵀ = (dqᵀ)⁺ dpᵀ.
  return least_squares(dq.transpose()).solve(dp.transpose()).transpose() * keep_sum;
}

}  // namespace detail

TossDesignResult design_for_toss(const Particle& start, const DesignTarget& target,
                                 const TossDesignOptions& options) {
  check(options);
  const DesignOptions& shape = options.shape;
  const detail::DesignSetup setup = detail::design_setup(start, shape);
  const detail::Point first = detail::start_point(setup, target, shape);
  const DesignTarget& goal = first.target;  // the target, its outcomes assigned to the start's hull
  const std::size_t k = goal.outcomes.size();
  const Eigen::Index n = static_cast<Eigen::Index>(k);
  Vector t(n);
  for (std::size_t o = 0; o < k; ++o) t[static_cast<Eigen::Index>(o)] = goal.outcomes[o].probability;
  const std::uint64_t most = options.model.drops;
  const double spread = (t.array() * (1 - t.array())).maxCoeff();  // the largest binomial variance per drop
  // The estimate size whose standard error is kErrorPerResidual of `residual`, within [min_drops, drops].
  auto drops_for = [&](double residual) {
    const double wanted = spread / std::pow(kErrorPerResidual * std::max(residual, 1e-12), 2);
    const double low = static_cast<double>(std::min(options.min_drops, most));
    return static_cast<std::uint64_t>(std::clamp(std::ceil(wanted), low, static_cast<double>(most)));
  };

  TossDesignResult result;
  struct Iterate {
    detail::Descent descent;
    DesignTarget assigned;  // the true target, its outcomes assigned to this hull
    std::vector<std::uint64_t> counts;
    Vector q, tossed;  // quasi-static and tossed probabilities of the outcomes
    TossDesignStep step;
  };
  // Grows `it`'s estimate to drops [0, size): only the drops it has not run yet (tallies of disjoint ranges
  // add up).
  auto extend = [&](Iterate& it, std::uint64_t size) {
    const std::uint64_t have = it.step.tossed.drops.end;
    if (size <= have) return;
    const detail::Point& at = it.descent.at;
    const TossedOutcomes more =
        detail::tossed_outcomes(at.particle, at.landscape, it.assigned, options.model, {have, size});
    result.settles += size - have;
    it.counts.resize(more.counts.size(), 0);
    for (std::size_t c = 0; c < more.counts.size(); ++c) it.counts[c] += more.counts[c];
    it.step.tossed = detail::summarise({0, size}, it.counts, std::vector<double>(t.data(), t.data() + n));
    it.tossed = outcomes_of(it.step.tossed.probability, k);
    it.step.objective = unbiased_objective(it.tossed, t, size);
  };
  // The quasi-static design toward `q` from `from` (the accepted design: a small change of q is a small
  // change of shape, as the secant steps assume); if that stops short of q, also from the start (the other
  // branch a changed structure may need), the nearer to q kept. Then its tossed estimate over drops [0,
  // size).
  auto iterate = [&](const Vector& q_goal, std::uint64_t size, const char* kind, const detail::Point& from) {
    const DesignTarget surrogate = with_probabilities(goal, q_goal);
    Iterate it;
    it.descent = detail::descend(detail::retarget(from, surrogate), surrogate, setup, shape);
    it.step.inner_iterations = static_cast<int>(it.descent.history.size());
    if (it.descent.stop != "converged" && &from != &first) {
      detail::Descent again = detail::descend(detail::retarget(first, surrogate), surrogate, setup, shape);
      it.step.inner_iterations += static_cast<int>(again.history.size());
      it.step.inner_restarted = true;
      if (again.at.objective < it.descent.at.objective) it.descent = std::move(again);
    }
    const detail::Point& at = it.descent.at;
    it.assigned = with_probabilities(at.target, t);
    it.step.kind = kind;
    it.step.surrogate.assign(q_goal.data(), q_goal.data() + n);
    it.step.quasi_static = at.achieved;
    it.step.inner_stop = it.descent.stop;
    it.q = outcomes_of(at.achieved, k);
    extend(it, size);
    return it;
  };

  // The starting point: the quasi-static design for the target itself.
  Iterate at = iterate(t, std::min(options.min_drops, most), "start", first);
  result.quasi_static_design = detail::design_result(setup, first, at.descent);
  const detail::Point quasi_static_point = at.descent.at;
  at.step.accepted = true;
  extend(at, drops_for((at.tossed - t).cwiseAbs().maxCoeff()));
  result.history.push_back(at.step);

  // The Jacobian d(tossed)/dq by finite differences: one outcome's quasi-static probability raised by
  // difference_step·(1 − q) and the others lowered in proportion, each estimate as large as needed for an
  // error a sixth of the step's effect (the difference of two estimates of the same drops).
  const Matrix keep_sum = Matrix::Identity(n, n) - Matrix::Constant(n, n, 1.0 / static_cast<double>(n));
  Matrix jac = Matrix::Identity(n, n);
  if (options.max_iterations > 0 && n > 1) {
    const double h = options.difference_step;
    const std::uint64_t size = drops_for(h / 2);
    extend(at, size);
    Matrix dq(n, n), dp(n, n);
    for (Eigen::Index o = 0; o < n; ++o) {
      Vector unit = Vector::Zero(n);
      unit[o] = 1;
      Iterate side = iterate(project(at.q + h * (unit - at.q)), size, "difference", at.descent.at);
      dq.col(o) = side.q - at.q;
      dp.col(o) = side.tossed - at.tossed;
      result.history.push_back(side.step);
    }
    // Least squares over the n columns. They span only the changes that keep Σq = 1 (rank n − 1), so the
    // solve must treat the last direction as absent (the threshold), and J acts on those changes alone.
    jac = detail::difference_jacobian(dq, dp);
  }

  // Done when every outcome is within options.tolerance, or (tolerance 0) when the estimate is as close to
  // the target as a typical sample of the target itself: its χ² below the median of χ² with outcomes − 1
  // degrees of freedom. Closer would fit this sample's noise rather than the physics.
  const double median =
      n > 1 ? boost::math::median(boost::math::chi_squared_distribution<double>(static_cast<double>(n - 1)))
            : 0.0;
  auto close_enough = [&](const Iterate& it) {
    if (options.tolerance > 0)
      return ((it.tossed - t).cwiseAbs().array() <= options.tolerance).all() && it.counts[k] == 0 &&
             it.counts[k + 1] == 0;
    return it.step.tossed.chi_square <= median && it.counts[k] == 0 && it.counts[k + 1] == 0;
  };
  // The steps: along the least-squares solution d of J d = −r over the changes that keep Σq = 1, a length α
  // chosen by a secant line search — the residual taken as linear along d between the point and each trial
  // (the same drops), α where it is least. The tossed landings are far more sensitive near the design than
  // the Jacobian's first estimate says (measured: 3–4 against 2), and secants of single steps are too noisy
  // to correct it outcome by outcome; the line search corrects its scale along the step from all outcomes at
  // once, and the next step starts from the length that worked (γ).
  int steps = 0;
  double gamma = 1;
  result.stop = "iterations";
  while (true) {
    extend(at, drops_for((at.tossed - t).cwiseAbs().maxCoeff()));
    const Vector residual = at.tossed - t;
    if (close_enough(at)) {
      extend(at, most);  // the test at the full size
      if (close_enough(at)) {
        result.stop = "converged";
        break;
      }
      continue;
    }
    const Eigen::CompleteOrthogonalDecomposition<Matrix> solver = least_squares(jac * keep_sum);
    Vector direction = -(keep_sum * solver.solve(residual));
    const bool singular = solver.rank() < n - 1 || !direction.allFinite();
    if (singular) direction = -(keep_sum * residual);
    double alpha = std::min(gamma, kMaxSurrogateStep / std::max(direction.cwiseAbs().maxCoeff(), 1e-300));
    bool accepted = false;
    for (int trial = 0; trial <= options.max_retries && !accepted; ++trial) {
      if (steps == options.max_iterations) break;
      Iterate next =
          iterate(project(at.q + alpha * direction), at.step.tossed.drops.end, "step", at.descent.at);
      ++steps;
      next.step.jacobian_reset = singular;
      const Vector change = next.tossed - residual - t;  // the residual's change over this trial
      const double best = change.squaredNorm() > 0
                              ? alpha * std::clamp(-residual.dot(change) / change.squaredNorm(), 0.1, 2.0)
                              : alpha;
      // Broyden's update from the secant (quasi-static change → tossed change, over the same drops): only a
      // change larger than the estimates' standard error says anything about the slope.
      const Vector s = next.q - at.q;
      const double noise =
          std::sqrt(spread / static_cast<double>(std::max<std::uint64_t>(at.step.tossed.drops.end, 1)));
      const bool updated = s.cwiseAbs().maxCoeff() > 3 * noise;
      if (updated) jac += (next.tossed - at.tossed - jac * s) * s.transpose() / s.squaredNorm();
      accepted = next.step.objective < at.step.objective;
      next.step.accepted = accepted;
      result.history.push_back(next.step);
      if (accepted) {
        at = std::move(next);
        gamma = updated ? 1.0 : std::clamp(best, 0.25, 2.0);  // an updated Jacobian carries the scale itself
      } else {
        alpha = std::clamp(best, 0.1 * alpha, 0.75 * alpha);
      }
    }
    if (!accepted) {
      result.stop = steps == options.max_iterations ? "iterations" : "stalled";
      break;
    }
  }

  result.design = detail::design_result(setup, first, at.descent);
  // The checks: drops after the common ones, which the optimiser never saw; both designs on the same drops.
  const DropRange fresh{most, most + options.model.check_drops};
  const detail::Point& design = at.descent.at;
  result.check =
      detail::tossed_outcomes(design.particle, design.landscape, at.assigned, options.model, fresh);
  detail::count_fit_noise(result.check, std::vector<double>(t.data(), t.data() + n),
                          at.step.tossed.drops.size());
  result.check_quasi_static =
      detail::tossed_outcomes(quasi_static_point.particle, quasi_static_point.landscape,
                              with_probabilities(quasi_static_point.target, t), options.model, fresh);
  result.settles += 2 * fresh.size();
  return result;
}

}  // namespace repose
