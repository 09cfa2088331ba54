// Internal: rotation of the particle about a fixed contact point or contact line (section 2.3).
#pragma once

#include "repose/geometry/types.hpp"

namespace repose::sim {

/// The constant rigid-body data the equations need.
struct Body {
  double mass = 0;
  Mat3 inertia = Mat3::Zero();  ///< about the centre of mass, body frame
  double gravity = 0;           ///< |g| along −z
  double damping = 0;           ///< C of Eq 4
};

/// The fixed support of a rotation phase: a point of the particle that stays at `world` (on the wall), and
/// for a line contact the world direction of the rotation axis through it.
struct Support {
  Vec3 world = Vec3::Zero();
  Vec3 body = Vec3::Zero();  ///< the same material point in body coordinates
  bool line = false;
  Vec3 axis = Vec3::UnitX();  ///< unit, world frame (line contacts only)
};

/// The rotational state: orientation, angular velocity and angular momentum about the support point
/// (for a line contact only its component along the axis is meaningful; it is stored as ℓ·axis).
struct Rotation {
  Quat q = Quat::Identity();
  Vec3 omega = Vec3::Zero();
  Vec3 momentum = Vec3::Zero();
};

/// dq/dt = ½ ω ⊗ q with ω in the world frame (Eq 9; q maps body to world), as Eigen's (x, y, z, w)
/// coefficients.
Eigen::Vector4d quaternion_rate(const Quat& q, const Vec3& omega);

/// World position of the centre of mass: the support point plus the rotated offset (Eq 3).
Vec3 com_position(const Support& s, const Quat& q);

/// Eq 7: inertia about the support point, world frame.
Mat3 inertia_about_support(const Body& body, const Support& s, const Quat& q);

/// Angular velocity from angular momentum (Eq 15; for a line, ω = ℓ / (eᵀ I_O e) · e).
Vec3 omega_from_momentum(const Body& body, const Support& s, const Quat& q, const Vec3& momentum);

/// The same with the support's constants computed once (the inertia about it in the body frame and its
/// inverse), for an integrator that evaluates it many times per support; bit-identical to the above.
struct SupportInertia {
  Mat3 inertia = Mat3::Identity();  ///< I_O, body frame
  Mat3 inverse = Mat3::Identity();  ///< I_O⁻¹ (point supports)
};
SupportInertia support_inertia(const Body& body, const Support& s);
Vec3 omega_from_momentum(const SupportInertia& inertia, const Support& s, const Quat& q,
                         const Vec3& momentum);

/// Eq 4 (point) or Eq 17 (line, projected on the axis): weight moment about the support minus C·ω.
Vec3 moment(const Body& body, const Support& s, const Quat& q, const Vec3& omega);

/// One time step of Eqs 10-16: trapezoidal rule for the angular momentum and the orientation (Crank–Nicolson
/// for dq/dt = ½ ω ⊗ q), solved together by the paper's pseudo-time fixed-point iteration to `tolerance` on
/// the quaternion, then renormalised. Returns the number of iterations (max_iterations if not converged).
int rotate_step(const Body& body, const Support& s, const Rotation& now, double dt, double tolerance,
                int max_iterations, Rotation& next);

/// Angular momentum about a new support right after an inelastic impact that makes it the support: the
/// impulse acts at the new support, so angular momentum about it is conserved (for a line, its component
/// along the new axis). `omega` is the angular velocity and `com_velocity` the centre-of-mass velocity
/// just before.
Vec3 momentum_after_switch(const Body& body, const Quat& q, const Vec3& com, const Vec3& omega,
                           const Vec3& com_velocity, const Support& next);

/// Kinetic energy of a rotation about the support, ½ ωᵀ I_O ω.
double rotational_energy(const Body& body, const Support& s, const Quat& q, const Vec3& omega);

}  // namespace repose::sim
