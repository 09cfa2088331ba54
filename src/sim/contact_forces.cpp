// The contact forces with Coulomb friction (contact_forces.hpp).
#include "contact_forces.hpp"

#include <algorithm>

#include "sliding_face.hpp"

namespace repose::sim {

ContactForces contact_forces(const ContactBody& body, const Motion& motion, const std::vector<Vec3>& arms,
                             double friction, double slip_speed) {
  std::vector<PointCondition> conditions(arms.size());
  for (std::size_t i = 0; i < arms.size(); ++i) {
    const Vec2 slip = (motion.velocity + motion.omega.cross(arms[i])).head<2>();
    if (slip.norm() > slip_speed) {
      conditions[i].rule = PointRule::sliding;
      conditions[i].direction = slip.normalized();
    }
  }
  return contact_forces(body, motion, arms, friction, conditions);
}

ContactForces contact_forces(const ContactBody& body, const Motion& motion, const std::vector<Vec3>& arms,
                             double friction, const std::vector<PointCondition>& conditions,
                             const std::vector<Vec3>* start) {
  if (auto face = sliding_face(body, motion, arms, friction, conditions)) return *face;
  const std::size_t n = arms.size();
  const Vec3& w = motion.omega;
  ContactProblem problem;
  problem.mass = body.mass;
  problem.inverse_inertia = body.inertia.inverse();
  problem.arms = arms;
  problem.friction = friction;
  // The accelerations without contact forces: gravity, the damping moment and the gyroscopic one.
  const Vec3 lin = Vec3(0, 0, -body.gravity);
  const Vec3 ang = problem.inverse_inertia * (-body.damping * w - w.cross(body.inertia * w));
  problem.offsets.resize(n);
  problem.scale = body.gravity;
  for (std::size_t i = 0; i < n; ++i) {
    problem.offsets[i] = w.cross(w.cross(arms[i]));  // centripetal
    problem.scale = std::max(problem.scale, point_value(problem, i, lin, ang).norm());
  }
  ContactSolution s = solve_contacts(problem, lin, ang, conditions, start);
  // No solution reached (Gauss–Seidel diverged and Lemke's method ended on a ray): no contact force, and
  // every sliding point driven into the wall is Painlevé's inconsistent case (below), resolved by the phase.
  const bool solved = s.solved;
  if (!solved) {
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
  out.modes.resize(n);
  out.inconsistent.assign(n, 0);
  const double tiny = 1e-12 * problem.scale;
  for (std::size_t i = 0; i < n; ++i) {
    const bool pressed = s.reactions[i].z() > 0;
    const Vec3 value = point_value(problem, i, s.lin, s.ang);
    const bool slipping = conditions[i].rule == PointRule::sliding || value.head<2>().norm() > tiny;
    out.modes[i] = !pressed ? ContactMode::open : slipping ? ContactMode::slide : ContactMode::stick;
    // Painlevé: a sliding point driven into the wall that no normal force can hold (contact_problem.hpp).
    if (conditions[i].rule == PointRule::sliding && !pressed && value.z() < -tiny) {
      const Mat3 W = delassus_block(problem.mass, problem.inverse_inertia, arms[i]);
      out.inconsistent[i] =
          !solved || W(2, 2) - friction * W.block<1, 2>(2, 0).dot(conditions[i].direction) <= 0;
    }
  }
  return out;
}

}  // namespace repose::sim
