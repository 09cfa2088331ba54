// Internal: the rigid body's kinematics, written once (issue 48: the point velocity v + ω × r was written out
// 19 times, the world inertia R·I·Rᵀ 12). World frame throughout; r is a point's offset from the centre of
// mass. The impulse and contact blocks built on these (the Delassus matrix K = 1/m − [r]× I⁻¹ [r]×) are in
// solver/contact_problem.hpp.
#pragma once

#include "repose/geometry/types.hpp"

namespace repose::sim {

/// Velocity of the centre of mass and angular velocity, world frame.
struct Motion {
  Vec3 velocity = Vec3::Zero();
  Vec3 omega = Vec3::Zero();
};

/// The velocity of the body point at offset r: v + ω × r.
inline Vec3 point_velocity(const Vec3& velocity, const Vec3& omega, const Vec3& r) {
  return velocity + omega.cross(r);
}
inline Vec3 point_velocity(const Motion& m, const Vec3& r) { return point_velocity(m.velocity, m.omega, r); }

/// The acceleration of the body point at offset r: a + α × r + ω × (ω × r).
inline Vec3 point_acceleration(const Vec3& acceleration, const Vec3& angular_acceleration, const Vec3& omega,
                               const Vec3& r) {
  return acceleration + angular_acceleration.cross(r) + omega.cross(omega.cross(r));
}

/// The inertia about the centre of mass in the world frame, R·I·Rᵀ (R: body → world), and its inverse.
inline Mat3 world_inertia(const Mat3& R, const Mat3& body_inertia) {
  return R * body_inertia * R.transpose();
}
inline Mat3 world_inverse_inertia(const Mat3& R, const Mat3& body_inertia) {
  return R * body_inertia.inverse() * R.transpose();
}

/// The angular momentum about the centre of mass, R·I·Rᵀ·ω, as one expression (Eigen evaluates it lazily,
/// with other roundings than world_inertia(R, I)·ω; the paper's pinned references are defined by this one).
inline Vec3 angular_momentum(const Mat3& R, const Mat3& body_inertia, const Vec3& omega) {
  return R * body_inertia * R.transpose() * omega;
}

/// ½·m·|v|² + ½·ωᵀ·I·ω, with I the world inertia.
inline double kinetic_energy(double mass, const Mat3& inertia, const Motion& m) {
  return 0.5 * mass * m.velocity.squaredNorm() + 0.5 * m.omega.dot(inertia * m.omega);
}

}  // namespace repose::sim
