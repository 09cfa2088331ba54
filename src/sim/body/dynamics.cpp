#include "dynamics.hpp"

#include "kinematics.hpp"

namespace repose::sim {

Eigen::Vector4d quaternion_rate(const Quat& q, const Vec3& w) {
  const Quat wq = Quat(0, w.x(), w.y(), w.z()) * q;
  return 0.5 * wq.coeffs();
}

namespace {
Vec3 project_on_axis(const Support& s, const Vec3& v) { return s.line ? Vec3(v.dot(s.axis) * s.axis) : v; }
}  // namespace

Vec3 com_position(const Support& s, const Quat& q) { return s.world - q * s.body; }

namespace {
// The inertia tensor about the support point in body coordinates (parallel-axis theorem). Working in the body
// frame keeps it a sum of constants and spares the two rotations of a 3×3 matrix per call.
Mat3 body_inertia_about_support(const Body& body, const Support& s) {
  const Vec3& r = s.body;  // centre of mass → support, body frame (the sign does not matter here)
  return body.inertia + body.mass * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
}
}  // namespace

Mat3 inertia_about_support(const Body& body, const Support& s, const Quat& q) {
  const Mat3 R = q.toRotationMatrix();
  return R * body_inertia_about_support(body, s) * R.transpose();
}

SupportInertia support_inertia(const Body& body, const Support& s) {
  SupportInertia r;
  r.inertia = body_inertia_about_support(body, s);
  r.inverse = r.inertia.inverse();
  return r;
}

Vec3 omega_from_momentum(const SupportInertia& inertia, const Support& s, const Quat& q,
                         const Vec3& momentum) {
  if (s.line) {
    const Vec3 e = q.conjugate() * s.axis;
    return (momentum.dot(s.axis) / e.dot(inertia.inertia * e)) * s.axis;
  }
  return q * Vec3(inertia.inverse * (q.conjugate() * momentum));
}

Vec3 omega_from_momentum(const Body& body, const Support& s, const Quat& q, const Vec3& momentum) {
  const Mat3 I = body_inertia_about_support(body, s);
  if (s.line) {
    // A rotation constrained to the axis e has ω = ω_e·e, and its momentum component is eᵀ I e · ω_e.
    const Vec3 e = q.conjugate() * s.axis;
    return (momentum.dot(s.axis) / e.dot(I * e)) * s.axis;
  }
  // ω = R I⁻¹ Rᵀ L. I is symmetric positive definite (a solid's inertia about any point), so its fixed-size
  // closed-form inverse is well conditioned.
  return q * Vec3(I.inverse() * (q.conjugate() * momentum));
}

Vec3 moment(const Body& body, const Support& s, const Quat& q, const Vec3& omega) {
  const Vec3 r = -(q * s.body);
  const Vec3 weight(0, 0, -body.mass * body.gravity);
  return project_on_axis(s, r.cross(weight) - body.damping * omega);
}

int rotate_step(const Body& body, const Support& s, const Rotation& now, double dt, double tolerance,
                int max_iterations, Rotation& next) {
  const Vec3 moment_now = moment(body, s, now.q, now.omega);
  const Eigen::Vector4d rate_now = quaternion_rate(now.q, now.omega);
  next = now;
  for (int it = 1; it <= max_iterations; ++it) {
    const Vec3 momentum =
        project_on_axis(s, now.momentum) + 0.5 * dt * (moment_now + moment(body, s, next.q, next.omega));
    Eigen::Vector4d coeffs = now.q.coeffs() + 0.5 * dt * (rate_now + quaternion_rate(next.q, next.omega));
    coeffs.normalize();
    const double change = (coeffs - next.q.coeffs()).norm();
    next.q.coeffs() = coeffs;
    next.momentum = momentum;
    next.omega = omega_from_momentum(body, s, next.q, momentum);
    // Not before the second pass: the first one advances q with the previous step's ω, so from rest (ω = 0)
    // it would "converge" with q unchanged and the new ω discarded from the orientation update.
    if (it > 1 && change < tolerance) return it;
  }
  return max_iterations;
}

Vec3 momentum_after_switch(const Body& body, const Quat& q, const Vec3& com, const Vec3& omega,
                           const Vec3& com_velocity, const Support& next) {
  const Mat3 R = q.toRotationMatrix();
  const Vec3 spin = angular_momentum(R, body.inertia, omega);
  const Vec3 momentum = spin + body.mass * (com - next.world).cross(com_velocity);
  return project_on_axis(next, momentum);
}

double rotational_energy(const Body& body, const Support& s, const Quat& q, const Vec3& omega) {
  const Vec3 w = q.conjugate() * omega;
  return 0.5 * w.dot(body_inertia_about_support(body, s) * w);
}

}  // namespace repose::sim
