// Several points striking the wall at once (multi_impact.hpp).
#include "multi_impact.hpp"

#include <algorithm>
#include <cmath>

#include "../solver/contact_problem.hpp"
#include "../tolerances.hpp"

namespace repose::sim {

MultiImpactOutcome collide_points(double mass, const Mat3& inertia, const std::vector<Vec3>& arms,
                                  const Motion& before, const ImpactLaw& law) {
  const std::size_t n = arms.size();
  ContactProblem problem;
  problem.mass = mass;
  problem.inverse_inertia = inertia.inverse();
  problem.arms.assign(arms.begin(), arms.end());
  problem.friction = law.friction;
  problem.scale = 0;
  for (std::size_t i = 0; i < n; ++i)
    problem.scale = std::max(problem.scale, point_value(problem, i, before.velocity, before.omega).norm());

  MultiImpactOutcome out;
  // Compression: plastic, with Coulomb at every point. Where no solution was reached (neither Gauss–Seidel
  // nor Lemke's method), or one that would add kinetic energy (an exact one never does: ΔK = P·u⁺ − ½·Pᵀ·W·P
  // with P·u⁺ = −Σ μ·λ_i·|u_t,i⁺| ≤ 0) or is not finite, the frictionless plastic impact instead, counted
  // as not converged.
  ContactSolution compression =
      solve_contacts(problem, before.velocity, before.omega, std::vector<PointCondition>(n));
  const double energy_before = kinetic_energy(mass, inertia, before);
  if (!compression.solved || !(kinetic_energy(mass, inertia, {compression.lin, compression.ang}) <=
                               energy_before * (1 + tol::kKineticRoundOff))) {
    ContactProblem frictionless = problem;
    frictionless.friction = 0;
    compression = solve_contacts(frictionless, before.velocity, before.omega, std::vector<PointCondition>(n));
    compression.converged = false;
  }
  out.converged = compression.converged;
  Motion after{compression.lin, compression.ang};
  std::vector<Vec3> total(compression.reactions.begin(), compression.reactions.end());
  if (law.restitution > 0) {
    // Restitution: Poisson's at each point, friction within μ times it; never above the energy before the
    // impact: the normal impulses halved (and friction solved again) until so.
    const double limit = energy_before;
    std::vector<PointCondition> given(n);
    double scale = 1;
    for (int k = 0; k <= tol::kRestitutionHalvings; ++k, scale *= 0.5) {
      for (std::size_t i = 0; i < n; ++i) {
        given[i].rule = PointRule::given_normal;
        given[i].normal = scale * law.restitution * compression.reactions[i].z();
      }
      const ContactSolution restitution = solve_contacts(problem, after.velocity, after.omega, given);
      if (kinetic_energy(mass, inertia, {restitution.lin, restitution.ang}) > limit) continue;
      out.converged = out.converged && restitution.converged;
      for (std::size_t i = 0; i < n; ++i) total[i] += restitution.reactions[i];
      after = {restitution.lin, restitution.ang};
      break;
    }
  }
  out.after = after;
  out.impulses = total;
  out.speed_after.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    out.speed_after[i] = point_value(problem, i, after.velocity, after.omega);
  return out;
}

}  // namespace repose::sim
