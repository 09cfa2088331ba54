// The contact forces with Coulomb friction (contact_forces.hpp).
#include "contact_forces.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <bit>
#include <cstdint>
#include <optional>

#include "../body/kinematics.hpp"
#include "../tolerances.hpp"
#include "sliding_face.hpp"

namespace repose::sim {

namespace {
// The normal forces of sliding points only (each F_i = λ_i·(−μ·ŝ_i, 1)): the LCP w = M·λ + q ≥ 0, λ ≥ 0,
// λ·w = 0 with M_ij = ẑ·W_ij·(−μ·ŝ_j, 1) and q the normal values without contact forces, decided exactly by
// enumerating its complementary sets. Empty where it has no solution (Painlevé's inconsistent case); else
// the solution with the fewest pressed points (the first found).
std::optional<Eigen::VectorXd> enumerate_sliding(const ContactProblem& p, const Vec3& lin, const Vec3& ang,
                                                 std::span<const PointCondition> conditions) {
  const std::size_t n = p.arms.size();
  const auto size = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd M(size, size);
  Eigen::VectorXd q(size);
  for (std::size_t i = 0; i < n; ++i) {
    q(static_cast<Eigen::Index>(i)) = point_value(p, i, lin, ang).z();
    for (std::size_t j = 0; j < n; ++j) {
      const Vec3 direction(-p.friction * conditions[j].direction.x(),
                           -p.friction * conditions[j].direction.y(), 1);
      M(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          (delassus_block(p.mass, p.inverse_inertia, p.arms[i], p.arms[j]) * direction).z();
    }
  }
  const double slack = tol::kEnumerationSlack * p.scale;
  std::vector<std::uint32_t> masks(std::size_t{1} << n);
  for (std::uint32_t m = 0; m < masks.size(); ++m) masks[m] = m;
  std::stable_sort(masks.begin(), masks.end(),
                   [](std::uint32_t a, std::uint32_t b) { return std::popcount(a) < std::popcount(b); });
  for (const std::uint32_t mask : masks) {
    std::vector<Eigen::Index> pressed;
    for (std::size_t i = 0; i < n; ++i)
      if (mask >> i & 1u) pressed.push_back(static_cast<Eigen::Index>(i));
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(size);
    if (!pressed.empty()) {
      const auto k = static_cast<Eigen::Index>(pressed.size());
      Eigen::MatrixXd A(k, k);
      Eigen::VectorXd b(k);
      for (Eigen::Index r = 0; r < k; ++r) {
        b(r) = -q(pressed[static_cast<std::size_t>(r)]);
        for (Eigen::Index c = 0; c < k; ++c)
          A(r, c) = M(pressed[static_cast<std::size_t>(r)], pressed[static_cast<std::size_t>(c)]);
      }
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
      if (!lu.isInvertible()) continue;
      const Eigen::VectorXd x = lu.solve(b);
      for (Eigen::Index r = 0; r < k; ++r) lambda(pressed[static_cast<std::size_t>(r)]) = x(r);
    }
    const Eigen::VectorXd w = M * lambda + q;
    if (lambda.allFinite() && lambda.minCoeff() >= -slack && w.minCoeff() >= -slack)
      return lambda.cwiseMax(0.0);
  }
  return std::nullopt;
}
}  // namespace

ContactForces contact_forces(const ContactBody& body, const Motion& motion, std::span<const Vec3> arms,
                             double friction, double slip_speed) {
  PointList<PointCondition> conditions(arms.size());
  for (std::size_t i = 0; i < arms.size(); ++i) {
    const Vec2 slip = (point_velocity(motion.velocity, motion.omega, arms[i])).head<2>();
    if (slip.norm() > slip_speed) {
      conditions[i].rule = PointRule::sliding;
      conditions[i].direction = slip.normalized();
    }
  }
  return contact_forces(body, motion, arms, friction, view(conditions));
}

ContactForces contact_forces(const ContactBody& body, const Motion& motion, std::span<const Vec3> arms,
                             double friction, std::span<const PointCondition> conditions,
                             std::span<const Vec3> start) {
  if (auto face = sliding_face(body, motion, arms, friction, conditions)) return *face;
  const std::size_t n = arms.size();
  const Vec3& w = motion.omega;
  ContactProblem problem;
  problem.mass = body.mass;
  problem.inverse_inertia = body.inertia.inverse();
  problem.arms.assign(arms.begin(), arms.end());
  problem.friction = friction;
  // The accelerations without contact forces: gravity, the damping moment and the gyroscopic one.
  const Vec3 lin = Vec3(0, 0, -body.gravity);
  const Vec3 ang = problem.inverse_inertia * (-body.damping * w - w.cross(body.inertia * w));
  problem.offsets.resize(n, Vec3::Zero());
  problem.scale = body.gravity;
  for (std::size_t i = 0; i < n; ++i) {
    problem.offsets[i] = w.cross(w.cross(arms[i]));  // centripetal
    problem.scale = std::max(problem.scale, point_value(problem, i, lin, ang).norm());
  }
  ContactSolution s = solve_contacts(problem, lin, ang, conditions, start);
  const bool all_sliding = std::all_of(conditions.begin(), conditions.end(),
                                       [](const PointCondition& c) { return c.rule == PointRule::sliding; });
  bool no_solution = false;  // decided by enumeration: Painlevé's inconsistent case
  // Enumerated too where the sweeps met a point with no consistent force on its own and Lemke's method
  // reached no solution: the points together may have one (two corners of a rod's end, each twisted into the
  // wall by its own friction, hold the end together; PainleveRod.TwoCornersOfASlidingEnd...).
  if ((!s.solved || s.painleve > 0) && all_sliding && n <= tol::kMaxEnumeratedPoints) {
    if (const auto lambda = enumerate_sliding(problem, lin, ang, conditions)) {
      s.solved = true;
      s.converged = true;
      s.painleve = 0;
      s.lin = lin;
      s.ang = ang;
      for (std::size_t i = 0; i < n; ++i) {
        const double l = (*lambda)(static_cast<Eigen::Index>(i));
        s.reactions[i] =
            l * Vec3(-friction * conditions[i].direction.x(), -friction * conditions[i].direction.y(), 1);
        s.lin += s.reactions[i] / problem.mass;
        s.ang += problem.inverse_inertia * arms[i].cross(s.reactions[i]);
      }
    } else {
      no_solution = true;
    }
  }
  // No solution reached (Gauss–Seidel diverged and Lemke's method ended on a ray, which is not the same as
  // no solution existing): no contact force, flagged for the run to count (ContactForces::solved).
  if (!s.solved || no_solution) {
    s.reactions.assign(n, Vec3::Zero());
    s.lin = lin;
    s.ang = ang;
  }
  ContactForces out;
  out.forces = s.reactions;
  out.acceleration = s.lin;
  out.angular_acceleration = s.ang;
  out.converged = s.converged;
  out.painleve = s.painleve;
  out.pyramid = s.pyramid;
  out.solved = s.solved || no_solution;
  out.modes.resize(n);
  out.inconsistent.assign(n, 0);
  const double tiny = tol::kModeTiny * problem.scale;
  for (std::size_t i = 0; i < n; ++i) {
    const bool pressed = s.reactions[i].z() > 0;
    const Vec3 value = point_value(problem, i, s.lin, s.ang);
    const bool slipping = conditions[i].rule == PointRule::sliding || value.head<2>().norm() > tiny;
    out.modes[i] = !pressed ? ContactMode::open : slipping ? ContactMode::slide : ContactMode::stick;
    // Painlevé: a sliding point driven into the wall that no normal force can hold, decided by the problem —
    // its own normal force would drive it in faster, W_nn − μ·W_nt·ŝ ≤ 0 (contact_problem.hpp) — not by a
    // solver failing (issue 48: a problem with several solutions was read as none).
    // A pressed sliding point at a dynamic jam (tolerances.hpp, kJamCompliance) is the same case in the
    // limit.
    if (conditions[i].rule != PointRule::sliding) continue;
    const Mat3 W = delassus_block(problem.mass, problem.inverse_inertia, arms[i]);
    const double compliance = sliding_compliance(W, friction, conditions[i].direction);
    if (!pressed && value.z() < -tiny)
      out.inconsistent[i] = no_solution || compliance <= 0;
    else if (pressed)
      out.inconsistent[i] = compliance <= tol::kJamCompliance * W(2, 2) &&
                            s.reactions[i].z() >= tol::kJamForce * problem.mass * problem.scale;
  }
  return out;
}

}  // namespace repose::sim
