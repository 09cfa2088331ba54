// The impact phase (impact.hpp).
#include "impact.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "../body/kinematics.hpp"
#include "../impact/multi_impact.hpp"

namespace repose::sim {

Impact::Impact(Run& run) : run_(run), law_{run.params.restitution, run.params.friction} {}

Impact::Outcome Impact::resolve(const Motion& motion) {
  const Run& run = run_;
  const auto& verts = run.particle.hull.vertices;
  const auto height = [&](int k) { return run.com.z() + (run.q * verts[static_cast<std::size_t>(k)]).z(); };
  std::vector<Vec3> arms;
  for (int k : run.near_wall.vertices_below(run.q, run.com.z(), run.tol.touch, run.tol.event,
                                            [&](int k) { return height(k) <= run.tol.touch; }))
    arms.push_back(run.q * verts[static_cast<std::size_t>(k)]);
  return resolve(motion, arms, law_);
}

Impact::Outcome Impact::resolve(const Motion& motion, const std::vector<Vec3>& arms, const ImpactLaw& law,
                                bool every_point) {
  Run& run = run_;
  const Body& body = run.body;
  const Mat3 R = run.q.toRotationMatrix();
  const Mat3 inertia = world_inertia(R, body.inertia);  // about the centre of mass, world frame
  arms_ = arms;
  const double v_tol = run.tol.speed;
  const double potential = run.potential_energy();
  Motion m = motion;
  auto normal_speed = [&](const Vec3& arm) { return (point_velocity(m.velocity, m.omega, arm)).z(); };
  std::vector<ImpactRecord>& impacts = run.record.impacts;
  for (int round = 0; round < tol::kImpactRounds; ++round) {
    approaching_.clear();
    for (const Vec3& arm : arms_)
      if (normal_speed(arm) < -v_tol) approaching_.push_back(arm);
    if (approaching_.empty()) break;
    // Restitution above the threshold only (SettleParams::restitution_threshold).
    double fastest = 0;
    for (const Vec3& arm : approaching_) fastest = std::max(fastest, -normal_speed(arm));
    const ImpactLaw round_law{fastest < run.params.restitution_threshold ? 0.0 : law.restitution,
                              law.friction};
    ImpactRecord record;
    record.t = run.t;
    record.points = static_cast<int>(approaching_.size());
    record.energy_before = sim::kinetic_energy(body.mass, inertia, m) + potential;
    const Vec3 velocity_before = m.velocity;
    const std::size_t points = every_point ? arms_.size() : approaching_.size();
    if (points > 1 && std::isfinite(law.friction)) {
      // Several points with finite friction: Coulomb at each of them (multi_impact.hpp), over every point on
      // the wall (one not approaching takes an impulse only if the others' push it into the wall).
      const MultiImpactOutcome out = collide_points(body.mass, inertia, arms_, m, round_law);
      Vec3 centre = Vec3::Zero();
      double total = 0;
      bool stick = true;
      for (std::size_t i = 0; i < arms_.size(); ++i) {
        centre += out.impulses[i].z() * arms_[i];
        total += out.impulses[i].z();
        if (out.impulses[i].z() > 0) stick = stick && out.speed_after[i].head<2>().norm() <= v_tol;
      }
      centre = total > 0 ? Vec3(centre / total) : approaching_[0];
      const Vec3 before = point_velocity(m.velocity, m.omega, centre),
                 after = point_velocity(out.after.velocity, out.after.omega, centre);
      record.point = run.com + centre;
      record.normal_speed_before = before.z();
      record.normal_speed_after = after.z();
      record.tangential_speed_before = before.head<2>().norm();
      record.tangential_speed_after = after.head<2>().norm();
      record.stick = stick;
      record.unresolved = !out.converged;
      m = out.after;
    } else {
      // One point (Stronge's law), or several without slip: the one-point law at their impulses' centre.
      const std::optional<Vec3> centre = approaching_.size() == 1
                                             ? std::optional<Vec3>(approaching_[0])
                                             : impulse_centre(body.mass, inertia, approaching_, m);
      if (!centre) break;
      const ImpactOutcome out = collide(body.mass, inertia, *centre, m, round_law);
      record.point = run.com + *centre;
      record.normal_speed_before = out.speed_before.z();
      record.normal_speed_after = out.speed_after.z();
      record.tangential_speed_before = out.speed_before.head<2>().norm();
      record.tangential_speed_after = out.speed_after.head<2>().norm();
      record.stick = out.stick;
      record.unresolved = out.fallback;
      m = out.after;
    }
    record.energy_after = sim::kinetic_energy(body.mass, inertia, m) + potential;
    record.impulse = body.mass * (m.velocity - velocity_before);
    impacts.push_back(record);
  }
  // A rebound: every point on the wall leaves it fast enough to rise above the touching tolerance
  // (u² > 2·g·touch); otherwise the particle stays on the wall and the contact phase takes over.
  double slowest = INFINITY;
  for (const Vec3& arm : arms_) slowest = std::min(slowest, normal_speed(arm));
  const bool rebound = impacts.size() < tol::kMaxImpacts &&
                       slowest * std::abs(slowest) > 2 * run.params.gravity * run.tol.touch;
  if (!impacts.empty() && impacts.back().t == run.t) impacts.back().rebound = rebound;
  if (rebound) ++run.record.bounces;
  return {rebound, m};
}

}  // namespace repose::sim
