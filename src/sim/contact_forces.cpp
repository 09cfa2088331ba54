// The contact forces with Coulomb friction (contact_forces.hpp).
#include "contact_forces.hpp"

#include <algorithm>

#include "contact_problem.hpp"

namespace repose::sim {

ContactForces contact_forces(const ContactBody& body, const Motion& motion, const std::vector<Vec3>& arms,
                             double friction, double slip_speed) {
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
  std::vector<PointCondition> conditions(n);
  problem.offsets.resize(n);
  problem.scale = body.gravity;
  for (std::size_t i = 0; i < n; ++i) {
    problem.offsets[i] = w.cross(w.cross(arms[i]));  // centripetal
    problem.scale = std::max(problem.scale, point_value(problem, i, lin, ang).norm());
    const Vec2 slip = (motion.velocity + w.cross(arms[i])).head<2>();
    if (slip.norm() > slip_speed) {
      conditions[i].rule = PointRule::sliding;
      conditions[i].direction = slip.normalized();
    }
  }
  const ContactSolution s = solve_contacts(problem, lin, ang, conditions);
  ContactForces out;
  out.forces = s.reactions;
  out.acceleration = s.lin;
  out.angular_acceleration = s.ang;
  out.converged = s.converged;
  out.painleve = s.painleve;
  out.modes.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool pressed = s.reactions[i].z() > 0;
    const bool slipping = conditions[i].rule == PointRule::sliding ||
                          point_value(problem, i, s.lin, s.ang).head<2>().norm() > 1e-12 * problem.scale;
    out.modes[i] = !pressed ? ContactMode::open : slipping ? ContactMode::slide : ContactMode::stick;
  }
  return out;
}

}  // namespace repose::sim
