// Internal: the contact forces on a rigid body touching the wall z = 0 at several points with Coulomb
// friction (issue 34: the contact phase with finite μ). The body: mass m, inertia I (world frame), velocity v
// and angular velocity ω; gravity −g·ẑ and the paper's damping moment −C·ω act on it. At each point on the
// wall (offset r_i from the centre of mass, its velocity u_i = v + ω × r_i with u_n = 0):
//   a point that slides (|u_t| above `slip_speed`) takes F = (−μ·N·ŝ, N) with ŝ = u_t/|u_t|;
//   a point at rest on the wall sticks (its acceleration zero, |F_t| ≤ μ·N) or starts to slide (F_t on the
//   cone, against the tangential acceleration it then has);
// and every normal force is complementary to the point's normal acceleration: N ≥ 0, a_n ≥ 0, N·a_n = 0 (a
// point with a_n > 0 lifts off). The point accelerations are a_i = a + α × r_i + ω × (ω × r_i), with
// m·a = −m·g·ẑ + ΣF and I·α = −C·ω − ω × (I·ω) + Σ r_i × F_i (contact_problem.hpp solves it).
#pragma once

#include <span>
#include <vector>

#include "../impact/rigid_impact.hpp"
#include "contact_problem.hpp"

namespace repose::sim {

enum class ContactMode { open, stick, slide };

struct ContactForces {
  PointList<Vec3> forces;                    ///< on the body at each point, world frame
  PointList<ContactMode> modes;              ///< open (N = 0: lifting off or just touching), stick or slide
  Vec3 acceleration = Vec3::Zero();          ///< of the centre of mass
  Vec3 angular_acceleration = Vec3::Zero();  ///< world frame
  bool converged = true;
  int painleve = 0;              ///< sliding points with no consistent normal force (Painlevé's paradox)
  PointList<char> inconsistent;  ///< which points those are (1: Painlevé's case at that point)
  /// Lemke's pyramid friction kept at points at rest (ContactSolution::pyramid): a fallback, counted.
  bool pyramid = false;
  /// No solution reached (Gauss–Seidel diverged and Lemke's method ended on a ray): the forces are zero and
  /// the run counts it. Painlevé's case is decided by the problem (`inconsistent`), not by this.
  bool solved = true;
};

struct ContactBody {
  double mass = 1;
  Mat3 inertia = Mat3::Identity();  ///< about the centre of mass, world frame
  double gravity = 0;               ///< the run's g (set by the caller)
  double damping = 0;               ///< C of the paper's Eq 4
};

/// The forces at the points `arms` (on the wall) of the body moving with `motion`; friction μ finite. A
/// point slides along its slip if that is faster than `slip_speed`, else it is at rest on the wall.
ContactForces contact_forces(const ContactBody& body, const Motion& motion, std::span<const Vec3> arms,
                             double friction, double slip_speed);

/// The same with each point's rule given (an event-driven phase keeps them between its events): `sliding`
/// with its direction, or `unilateral` (at rest on the wall: it sticks or starts to slide).
ContactForces contact_forces(const ContactBody& body, const Motion& motion, std::span<const Vec3> arms,
                             double friction, std::span<const PointCondition> conditions,
                             std::span<const Vec3> start = {});

}  // namespace repose::sim
