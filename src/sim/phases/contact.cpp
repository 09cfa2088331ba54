// The contact phase's start and step (contact.hpp).
#include "contact.hpp"

#include <utility>

namespace repose::sim {

Contact::Contact(Run& run) : run_(run), walks_(run.particle.hull) {
  const std::size_t n = run.particle.hull.vertices.size();
  z_.resize(n);
  in_contact_.resize(n);
  if (run.params.integrator == Integrator::adaptive)
    stepper_.emplace<AdaptiveStepper>(run.body, run.tol.length, run.params.tolerance, run.tol.dt);
}

std::optional<RestPose> Contact::begin(const Vec3& com_velocity, const Vec3& omega, bool carry) {
  Run& run = run_;
  const int lowest = run.lowest_vertex(run.q);
  const Vec3 p = run.particle.hull.vertices[static_cast<std::size_t>(lowest)];
  const Vec3 arm = run.q * p;
  set_support({Vec3(run.com.x() + arm.x(), run.com.y() + arm.y(), 0.0), p, false, Vec3::UnitX()}, lowest);
  rot_ = {run.q, Vec3::Zero(), Vec3::Zero()};
  if (carry) {
    rot_.momentum = momentum_after_switch(run.body, run.q, run.com, omega, com_velocity, support_);
    rot_.omega = omega_from_momentum(run.body, support_, run.q, rot_.momentum);
  }
  restart_motion(/*from_rest=*/true);
  update(carry ? omega : Vec3::Zero(), com_velocity);
  return std::exchange(rest_, std::nullopt);
}

std::optional<RestPose> Contact::step() {
  if (auto* adaptive = std::get_if<AdaptiveStepper>(&stepper_))
    adaptive_step(*adaptive);
  else
    paper_step();
  return std::exchange(rest_, std::nullopt);
}

void Contact::restart_motion(bool from_rest) {
  if (auto* adaptive = std::get_if<AdaptiveStepper>(&stepper_)) {
    adaptive->next = AdaptiveStepper::Next::restart;
    if (from_rest) adaptive->restart_step = 0;
  }
}

double Contact::kinetic_energy() const { return rotational_energy(run_.body, support_, rot_.q, rot_.omega); }

// Heights of all hull vertices for orientation `qq` about the current support (only the third row of R).
void Contact::heights(const Quat& qq, std::vector<double>& out) const {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  const auto& verts = run_.particle.hull.vertices;
  for (std::size_t k = 0; k < verts.size(); ++k)
    out[k] = support_.world.z() + r3.dot(verts[k] - support_.body);
}

}  // namespace repose::sim
