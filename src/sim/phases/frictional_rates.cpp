// The frictional contact phase's forces and rates between its events (frictional_contact.hpp): the forces
// at the segment's points by their rules, the rates the integrator takes, and the counts of the solvers'
// fallbacks.
#include <cmath>

#include "../body/kinematics.hpp"
#include "frictional_contact.hpp"

namespace repose::sim {

ContactForces FrictionalContact::forces_at(const BodyState& s) const {
  return forces_at(s, active_, conditions_, view(warm_start_));
}

ContactForces FrictionalContact::forces_at(const BodyState& s, const std::vector<int>& points,
                                           std::span<const PointCondition> start,
                                           std::span<const Vec3> warm) const {
  const Run& run = run_;
  const Mat3 R = s.q.toRotationMatrix();
  const ContactBody body{run.body.mass, world_inertia(R, run.body.inertia), run.params.gravity,
                         run.params.damping};
  PointList<Vec3> arms(points.size(), Vec3::Zero());  // (inline: no allocation per evaluation of the rates)
  PointList<PointCondition> conditions(start.begin(), start.end());
  for (std::size_t i = 0; i < points.size(); ++i) {
    arms[i] = s.q * run.particle.hull.vertices[static_cast<std::size_t>(points[i])];
    // A sliding point slides along its slip as it turns; past the instant its slip stops or turns against
    // its direction at the segment's start (an event: the segment ends there) the motion goes on with that
    // direction, so that the dense output stays smooth up to the event and locates it exactly.
    const Vec2 slip = (point_velocity(s.velocity, s.omega, arms[i])).head<2>();
    if (conditions[i].rule == PointRule::sliding && slip.dot(start[i].direction) > 0)
      conditions[i].direction = slip.normalized();
  }
  return contact_forces(body, Motion{s.velocity, s.omega}, view(arms), run.params.friction, view(conditions),
                        warm);
}

void FrictionalContact::count_fallbacks(const ContactForces& f) const {
  // run_ is the run's, not this phase's: counted from the const rates too.
  FrictionalAccount& account = run_.record.account;
  account.pyramid_forces += f.pyramid;
  account.unsolved_forces += !f.solved;
  account.unresolved_forces += f.solved && !f.converged;
}

std::vector<FrictionalContact::PointForce> FrictionalContact::point_forces() const {
  std::vector<PointForce> out;
  if (!started_ || active_.empty()) return out;
  const ContactForces f = forces_at({run_.com, velocity_, run_.q, omega_});
  for (std::size_t i = 0; i < active_.size(); ++i) {
    const Vec3 arm = run_.q * run_.particle.hull.vertices[static_cast<std::size_t>(active_[i])];
    out.push_back({run_.com + arm, point_velocity(velocity_, omega_, arm), f.forces[i]});
  }
  return out;
}

BodyRates FrictionalContact::rates(const BodyState& s) const {
  BodyRates r;  // (a segment has points on the wall: a hop is the engine's flight)
  const ContactForces f = forces_at(s);
  count_fallbacks(f);
  r.acceleration = f.acceleration;
  r.angular_acceleration = f.angular_acceleration;
  double normal = 0, weighted_slip = 0;
  for (std::size_t i = 0; i < active_.size(); ++i) {
    const Vec3 arm = s.q * run_.particle.hull.vertices[static_cast<std::size_t>(active_[i])];
    const Vec3 u = point_velocity(s.velocity, s.omega, arm);
    r.friction_power += f.forces[i].head<2>().dot(u.head<2>());
    r.normal_power += f.forces[i].z() * u.z();
    // A sliding point's slip along the direction it slides in: past its stop (an event) the motion's
    // extension slides on backwards, and the slip rate stays smooth there (negative) for the dense output.
    const Vec2 ut = u.head<2>();
    const Vec2& s0 = conditions_[i].direction;
    const bool along = conditions_[i].rule == PointRule::sliding && ut.dot(s0) <= 0;
    normal += f.forces[i].z();
    weighted_slip += f.forces[i].z() * (along ? ut.dot(s0) : ut.norm());
  }
  if (normal > 0) r.slip_rate = weighted_slip / normal;
  // The damping moment acts on the wall only (contact_forces.hpp's rates include it).
  r.damping_power = -run_.params.damping * s.omega.squaredNorm();
  return r;
}

}  // namespace repose::sim
