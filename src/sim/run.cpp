#include "run.hpp"

#include <cstdlib>

#include "body/kinematics.hpp"
#include "repose/error.hpp"

namespace repose::sim {

namespace {
const SettleParams& validated(const SettleParams& params) {
  validate(params);
  return params;
}

double largest_radius(const Particle& p) {
  double r = 0;
  for (const Vec3& v : p.hull.vertices) r = std::max(r, v.norm());
  return r;
}
}  // namespace

Run::Run(const Particle& p, const SettleParams& prm, const Quat& orientation)
    : particle(p),
      params(validated(prm)),
      body{p.mass.mass, p.mass.inertia, params.gravity, params.damping},
      tol(make_tolerances(p, params)),
      surface(params.smooth == SmoothMode::on ||
                      (params.smooth == SmoothMode::automatic && is_smooth_surface(p))
                  ? SurfaceModel::Kind::smooth
                  : SurfaceModel::Kind::polyhedral),
      trace(std::getenv("REPOSE_TRACE") != nullptr),
      hull_radius(largest_radius(p)),
      near_wall(p.hull) {
  if (!std::isfinite(orientation.norm()) || orientation.norm() < tol::kQuaternionNorm)
    throw Error("orientation must be a finite non-zero quaternion");
  q = orientation.normalized();
  com = Vec3(0, 0, params.drop_height - lowest_offset(q));
  // The energy at t = 0: the toss's (or the drop speed's) kinetic energy, its spin's, and the potential.
  const Vec3 velocity = params.velocity - Vec3(0, 0, params.drop_speed);
  const bool toss = params.velocity != Vec3::Zero() || params.spin != Vec3::Zero();
  record.energy_start = (toss ? 0.5 * body.mass * velocity.squaredNorm()
                              : 0.5 * body.mass * params.drop_speed * params.drop_speed) +
                        potential_energy();
  if (params.spin != Vec3::Zero()) {
    const Mat3 R = q.toRotationMatrix();
    record.energy_start += 0.5 * params.spin.dot(angular_momentum(R, body.inertia, params.spin));
  }
}

}  // namespace repose::sim
