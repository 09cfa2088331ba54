// The contact forces with Coulomb friction (contact_forces.hpp).
#include "contact_forces.hpp"

#include <algorithm>
#include <optional>

namespace repose::sim {

namespace {

// A face flush on the wall whose points all slide (a block skidding or spinning on its face), solved as a
// planar sliding body: the face stays on the wall (every point's normal acceleration zero: the centre of
// mass's vertical and the tilting accelerations follow) and the normal forces vary linearly over its points,
// N_i = c0 + c1·x_i + c2·y_i (the pressure under a rigid block on a uniform elastic foundation; exact for
// three points, and the least-norm forces for more). Newton–Euler's six equations and the three of the flush
// face are linear in (a, α, c): one 9 × 9 solve. Empty where the points are collinear or a normal force comes
// out negative (the face would tip: the general problem decides which points stay). Block Gauss–Seidel does
// not converge on such a face: its normal forces are indeterminate and friction makes the iteration
// unsymmetric.
std::optional<ContactForces> sliding_face(const ContactBody& body, const Motion& motion,
                                          const std::vector<Vec3>& arms, double mu,
                                          const std::vector<PointCondition>& conditions) {
  const std::size_t n = arms.size();
  if (n < 3) return std::nullopt;
  for (const PointCondition& c : conditions)
    if (c.rule != PointRule::sliding) return std::nullopt;
  Vec2 centre = Vec2::Zero();
  for (const Vec3& r : arms) centre += r.head<2>() / static_cast<double>(n);
  Eigen::MatrixXd B(n, 3);
  double extent = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 d = arms[i].head<2>() - centre;
    B.row(static_cast<Eigen::Index>(i)) << 1, d.x(), d.y();
    extent = std::max(extent, d.norm());
  }
  // Collinear points (an edge) hold no face: the smallest singular value of the scaled columns.
  Eigen::MatrixXd scaled = B;
  scaled.rightCols<2>() /= extent;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled);
  if (!(svd.singularValues()(2) > 1e-6 * svd.singularValues()(0))) return std::nullopt;
  const Vec3& w = motion.omega;
  const double m = body.mass;
  Eigen::Matrix<double, 9, 9> A = Eigen::Matrix<double, 9, 9>::Zero();
  Eigen::Matrix<double, 9, 1> rhs = Eigen::Matrix<double, 9, 1>::Zero();
  // m·a − Σ d_i·N_i = −m·g·ẑ and I·α − Σ r_i × d_i·N_i = −C·ω − ω × I·ω, with d_i = (−μ·ŝ_i, 1).
  A.block<3, 3>(0, 0) = m * Mat3::Identity();
  A.block<3, 3>(3, 3) = body.inertia;
  rhs.segment<3>(0) = Vec3(0, 0, -m * body.gravity);
  rhs.segment<3>(3) = -body.damping * w - w.cross(body.inertia * w);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 d(-mu * conditions[i].direction.x(), -mu * conditions[i].direction.y(), 1);
    const Eigen::RowVector3d b = B.row(static_cast<Eigen::Index>(i));
    A.block<3, 3>(0, 6) -= d * b;
    A.block<3, 3>(3, 6) -= arms[i].cross(d) * b;
    // The flush face: Bᵀ·(a_z + (α × r_i)_z + (ω × (ω × r_i))_z) = 0, the point accelerations' normal part
    // being affine over the face.
    const Vec3& r = arms[i];
    A.block<3, 1>(6, 2) += b.transpose();
    A.block<3, 1>(6, 3) += b.transpose() * r.y();
    A.block<3, 1>(6, 4) -= b.transpose() * r.x();
    rhs.segment<3>(6) -= b.transpose() * w.cross(w.cross(r)).z();
  }
  const Eigen::FullPivLU<Eigen::Matrix<double, 9, 9>> lu(A);
  if (!lu.isInvertible()) return std::nullopt;
  const Eigen::Matrix<double, 9, 1> x = lu.solve(rhs);
  if (!x.allFinite()) return std::nullopt;
  ContactForces out;
  out.acceleration = x.segment<3>(0);
  out.angular_acceleration = x.segment<3>(3);
  out.forces.resize(n);
  out.modes.assign(n, ContactMode::slide);
  out.inconsistent.assign(n, 0);
  const Vec3 c = x.segment<3>(6);
  for (std::size_t i = 0; i < n; ++i) {
    const double normal = B.row(static_cast<Eigen::Index>(i)).dot(c);
    if (normal < 0) return std::nullopt;
    out.forces[i] = normal * Vec3(-mu * conditions[i].direction.x(), -mu * conditions[i].direction.y(), 1);
  }
  return out;
}

}  // namespace

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
                             double friction, const std::vector<PointCondition>& conditions) {
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
  const ContactSolution s = solve_contacts(problem, lin, ang, conditions);
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
      out.inconsistent[i] = W(2, 2) - friction * W.block<1, 2>(2, 0).dot(conditions[i].direction) <= 0;
    }
  }
  return out;
}

}  // namespace repose::sim
