// Internal: the rigid body's kinematics, written once (issue 48: the point velocity v + ω × r was written out
// 19 times, the world inertia R·I·Rᵀ 12). World frame throughout; r is a point's offset from the centre of
// mass. The Delassus blocks here are what the impact laws and the contact problem build on.
#pragma once

#include <algorithm>
#include <vector>

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

/// The motion after the impulses `impulses[i]`, each scaled by `scale`, at the points `arms[i]`.
inline Motion apply_impulses(double mass, const Mat3& inverse_inertia, const Motion& m,
                             const std::vector<Vec3>& arms, const std::vector<Vec3>& impulses,
                             double scale = 1) {
  Motion out = m;
  for (std::size_t i = 0; i < arms.size(); ++i) {
    const Vec3 p = scale * impulses[i];
    out.velocity += p / mass;
    out.omega += inverse_inertia * arms[i].cross(p);
  }
  return out;
}

/// The scale s in [0, 1] of the impulses that leaves the least kinetic energy: along s the energy is
/// K0 + a·s + b·s² (a = Σ P_i·u_i with u_i the points' velocities before, b = K(1) − K0 − a), so s = 1 when
/// the impulses take energy, else the minimiser −a/(2b) clamped to [0, 1]. Impulses changed after they were
/// found (a cone's projection, a pulling component dropped) can add energy; scaled by s they cannot.
inline double energy_minimising_scale(double mass, const Mat3& inertia, const Motion& m,
                                      const std::vector<Vec3>& arms, const std::vector<Vec3>& impulses) {
  const double k0 = kinetic_energy(mass, inertia, m);
  const double k1 = kinetic_energy(mass, inertia, apply_impulses(mass, inertia.inverse(), m, arms, impulses));
  if (!(k1 > k0)) return 1;
  double a = 0;
  for (std::size_t i = 0; i < arms.size(); ++i) a += impulses[i].dot(point_velocity(m, arms[i]));
  const double b = k1 - k0 - a;
  return b > 0 ? std::clamp(-a / (2 * b), 0.0, 1.0) : 0.0;
}

/// [r]×, the matrix of r × ·.
inline Mat3 skew(const Vec3& r) {
  Mat3 x;
  x << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return x;
}

/// The off-diagonal Delassus block: a unit impulse (or force) at r_j changes the velocity (or acceleration)
/// of the point r_i by W_ij·R, W_ij = 1/m − [r_i]× I⁻¹ [r_j]×.
inline Mat3 delassus_block(double mass, const Mat3& inverse_inertia, const Vec3& r_i, const Vec3& r_j) {
  return Mat3::Identity() / mass - skew(r_i) * inverse_inertia * skew(r_j);
}

/// The Delassus block of a point r from the centre of mass: K = 1/m − [r]× I⁻¹ [r]×.
inline Mat3 delassus_block(double mass, const Mat3& inverse_inertia, const Vec3& r) {
  return delassus_block(mass, inverse_inertia, r, r);
}

}  // namespace repose::sim
