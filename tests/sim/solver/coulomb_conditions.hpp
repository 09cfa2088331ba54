// An independent judge of contact forces (issue 48): whether forces F_i at points r_i on the wall z = 0,
// with the accelerations a and α that come with them, satisfy Newton–Euler's equations, the Signorini
// conditions and Coulomb's law for the points' rules — checked from the definitions, not by the solver's
// own arithmetic. Used on random convex polyhedra, where the solvers' special cases (a face, a pivot)
// meet configurations no box or prism has.
#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "../../../src/sim/solver/contact_forces.hpp"

namespace repose::sim::test {

/// The first violated condition, or "" if none; `tolerance` is relative to the forces' scale m·g·(1 + μ)
/// (and to that scale times the arm for moments, over the mass for accelerations).
inline std::string coulomb_violation(const ContactBody& body, const Motion& motion,
                                     const std::vector<Vec3>& arms, double mu,
                                     const std::vector<PointCondition>& conditions, const ContactForces& f,
                                     double tolerance) {
  std::ostringstream why;
  const double scale = body.mass * body.gravity * (1 + mu);
  const double force_tol = tolerance * scale, accel_tol = force_tol / body.mass;
  const Vec3& w = motion.omega;
  double reach = 0;
  Vec3 force = Vec3::Zero(), moment = -body.damping * w - w.cross(body.inertia * w);
  for (std::size_t i = 0; i < arms.size(); ++i) {
    force += f.forces[i];
    moment += arms[i].cross(f.forces[i]);
    reach = std::max(reach, arms[i].norm());
  }
  const Vec3 newton = body.mass * f.acceleration - force + Vec3(0, 0, body.mass * body.gravity);
  if (newton.norm() > force_tol) return why << "m·a ≠ ΣF − m·g·ẑ by " << newton.norm(), why.str();
  const Vec3 euler = body.inertia * f.angular_acceleration - moment;
  if (euler.norm() > force_tol * std::max(reach, 1.0))
    return why << "I·α ≠ Σ r × F − C·ω − ω × I·ω by " << euler.norm(), why.str();
  for (std::size_t i = 0; i < arms.size(); ++i) {
    const Vec3& F = f.forces[i];
    const Vec3 a = f.acceleration + f.angular_acceleration.cross(arms[i]) + w.cross(w.cross(arms[i]));
    const double N = F.z();
    const Vec2 Ft = F.head<2>();
    why << "point " << i << " (N = " << N << ", a_n = " << a.z() << "): ";
    if (N < -force_tol) return why << "pulls", why.str();
    if (a.z() < -accel_tol) return why << "accelerates into the wall", why.str();
    if (N > force_tol && a.z() > accel_tol) return why << "pushed while lifting off", why.str();
    if (Ft.norm() > mu * std::max(N, 0.0) + force_tol) return why << "outside the cone", why.str();
    const PointCondition& c = conditions[i];
    if (c.rule == PointRule::sliding) {
      if ((Ft + mu * std::max(N, 0.0) * c.direction).norm() > force_tol)
        return why << "sliding friction not −μ·N·ŝ", why.str();
    } else if (c.rule == PointRule::unilateral && N > force_tol) {
      const Vec2 at = a.head<2>();
      // Sticking (no tangential acceleration) or starting to slide: on the cone, against the acceleration.
      if (at.norm() > accel_tol && (Ft + mu * N * at.normalized()).norm() > force_tol)
        return why << "starts to slide with friction not against its acceleration", why.str();
    }
    why.str("");
  }
  return "";
}

}  // namespace repose::sim::test
