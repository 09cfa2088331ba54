// What happens when an airborne particle reaches the wall: the paper's touch (translation stops,
// section 2.1), or rigid-body impacts (issue 14: restitution and friction, rigid_impact.hpp) that end in a
// rebound or hand over to the paper's rotation with the angular momentum the impacts left (docs/method.md,
// "Rebound").
#include <algorithm>
#include <cmath>

#include "settler.hpp"

namespace repose {

namespace {
// Several points on the wall may each need an impact (the first leaves another approaching): bounded.
constexpr int kImpactRounds = 16;
// A run's rebounds are bounded: after this many impacts every touch hands over to the paper's rotation. A
// ball with E = 0.99 bounces ~1,300 times before its rebounds fall below the touching tolerance; the bound
// stops a chatter of ever-shorter flights (a particle with E near 1 rattling on its facets) from taking the
// run's whole step budget.
constexpr std::size_t kMaxImpacts = 10000;
}  // namespace

void Settler::Impl::touch(const Vec3& velocity, const Vec3& omega) {
  falling = false;
  spinning = false;
  if (!rigid_impacts) {
    begin_contact(velocity);
    return;
  }
  const Mat3 R = q.toRotationMatrix();
  const Mat3 inertia = R * body.inertia * R.transpose();  // about the centre of mass, world frame
  std::vector<Vec3> arms;                                 // centre of mass → the vertices on the wall
  for (const Vec3& v : particle.hull.vertices) {
    const Vec3 arm = q * v;
    if (com.z() + arm.z() <= touch_tol) arms.push_back(arm);
  }
  const double v_tol = 1e-9 * std::sqrt(params.gravity * length);
  const double potential = potential_energy();
  sim::Motion m{velocity, omega};
  auto normal_speed = [&](const Vec3& arm) { return (m.velocity + m.omega.cross(arm)).z(); };
  std::vector<Vec3> approaching;
  for (int round = 0; round < kImpactRounds; ++round) {
    approaching.clear();
    for (const Vec3& arm : arms)
      if (normal_speed(arm) < -v_tol) approaching.push_back(arm);
    if (approaching.empty()) break;
    const std::optional<Vec3> centre = approaching.size() == 1
                                           ? std::optional<Vec3>(approaching[0])
                                           : sim::impulse_centre(body.mass, inertia, approaching, m);
    if (!centre) break;
    const sim::ImpactOutcome out = sim::collide(body.mass, inertia, *centre, m, impact_law);
    ImpactRecord record;
    record.t = t;
    record.point = com + *centre;
    record.normal_speed_before = out.speed_before.z();
    record.normal_speed_after = out.speed_after.z();
    record.tangential_speed_before = out.speed_before.head<2>().norm();
    record.tangential_speed_after = out.speed_after.head<2>().norm();
    record.stick = out.stick;
    record.points = static_cast<int>(approaching.size());
    record.energy_before = sim::kinetic_energy(body.mass, inertia, m) + potential;
    m = out.after;
    record.energy_after = sim::kinetic_energy(body.mass, inertia, m) + potential;
    impacts.push_back(record);
  }
  // A rebound: every point on the wall leaves it fast enough to rise above the touching tolerance
  // (u² > 2·g·1e-9·L); otherwise the particle stays on the wall and the paper's rotation takes over.
  double slowest = INFINITY;
  for (const Vec3& arm : arms) slowest = std::min(slowest, normal_speed(arm));
  const bool rebound =
      impacts.size() < kMaxImpacts && slowest * std::abs(slowest) > 2 * params.gravity * touch_tol;
  if (!impacts.empty() && impacts.back().t == t) impacts.back().rebound = rebound;
  if (rebound) {
    ++bounces;
    begin_flight(m.velocity, m.omega, 0.0);
    return;
  }
  begin_contact(m.velocity, m.omega, true);
}

// The start of the rotation (a touch, or a run that starts on the wall): the particle pivots about its
// lowest point. The paper's touch (`carry` false) starts the rotation from rest; after rigid impacts it
// starts with the angular momentum about the pivot that `omega` and `com_velocity` have.
void Settler::Impl::begin_contact(const Vec3& com_velocity, const Vec3& omega, bool carry) {
  falling = false;
  int lowest = 0;
  for (std::size_t k = 0; k < particle.hull.vertices.size(); ++k)
    if ((q * particle.hull.vertices[k]).z() < (q * particle.hull.vertices[lowest]).z())
      lowest = static_cast<int>(k);
  const Vec3 p = particle.hull.vertices[lowest];
  support = {Vec3(com.x() + (q * p).x(), com.y() + (q * p).y(), 0.0), p, false, Vec3::UnitX()};
  support_vertex = lowest;
  reach_radius = hull_radius + support.body.norm();
  com = sim::com_position(support, q);
  rot = {q, Vec3::Zero(), Vec3::Zero()};
  if (carry) {
    rot.momentum = sim::momentum_after_switch(body, q, com, omega, com_velocity, support);
    rot.omega = sim::omega_from_momentum(body, support, q, rot.momentum);
  }
  restart = true;
  restart_step = 0;
  update_contacts(carry ? omega : Vec3::Zero(), com_velocity);
}

}  // namespace repose
