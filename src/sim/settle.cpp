// The settling engine's public API and the run's life cycle (paper §2.1-2.4); the steps themselves are in the
// files listed in settler.hpp.
//
// Two sets of points drive the method, both over the convex hull's vertices (only they can touch a flat
// wall):
//   - the contact set (the paper's): vertices within ε of the wall; it gives the contact type (Algorithm 1),
//     the best-fit rotation axis, and the stability tests of §2.4;
//   - the touching set: vertices on the wall (within 1e-9·L). The rotation always keeps its support point on
//     the wall, and no vertex may pass below it: every new touch is located inside the step by bisection.
// When the paper's stability test fires, the run finishes the rotation on touching points alone until they
// hold the centre of mass, then sets the supporting hull face exactly flush: the rest is a true equilibrium.
#include "repose/sim/settle.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "repose/error.hpp"
#include "settler.hpp"

namespace repose {

const char* to_string(ContactType type) {
  switch (type) {
    case ContactType::free_fall:
      return "free-fall";
    case ContactType::point:
      return "point";
    case ContactType::line:
      return "line";
    case ContactType::surface:
      return "surface";
    case ContactType::flight:
      return "flight";
  }
  return "?";
}

const char* to_string(Status status) {
  switch (status) {
    case Status::running:
      return "running";
    case Status::rest:
      return "rest";
    case Status::max_time:
      return "max-time";
    case Status::max_steps:
      return "max-steps";
  }
  return "?";
}

const char* to_string(RestKind kind) {
  switch (kind) {
    case RestKind::none:
      return "none";
    case RestKind::surface:
      return "surface";
    case RestKind::points:
      return "points";
    case RestKind::smooth:
      return "smooth";
  }
  return "?";
}

double default_sample_dt(const Particle& particle, const SettleParams& params) {
  if (params.integrator == Integrator::paper) return 0;
  return 1e-3 * std::sqrt(particle.length / params.gravity);
}

bool is_smooth_surface(const Particle& particle) {
  return particle.convex_surface && particle.max_dihedral_angle < std::numbers::pi / 6;
}

Settler::Impl::Impl(const Particle& p, const SettleParams& prm, const Quat& orientation)
    : particle(p), params(prm) {
  validate(params);
  if (!std::isfinite(orientation.norm()) || orientation.norm() < 1e-12)
    throw Error("orientation must be a finite non-zero quaternion");
  body = {p.mass.mass, p.mass.inertia, params.gravity, params.damping};
  length = p.length;
  band = params.contact_threshold * length;
  touch_tol = 1e-9 * length;
  event_tol = 1e-12 * length;
  rss_threshold = params.line_threshold * length * length;
  const double time_scale = std::sqrt(length / params.gravity);
  adaptive = params.integrator == Integrator::adaptive;
  dt = params.dt > 0 ? params.dt : (adaptive ? kAdaptiveMaxStep : 1e-3) * time_scale;
  if (adaptive) integrator.emplace(body, length, params.tolerance, dt);
  double fall_time =
      (std::sqrt(params.drop_speed * params.drop_speed + 2 * params.gravity * params.drop_height)) /
      params.gravity;
  if (uses_impacts(params) || params.velocity != Vec3::Zero()) {
    // A toss rises first, and bounces take at most (1 + E)/(1 − E) times its first fall (a ball's series).
    const double up = params.velocity.z() - params.drop_speed, g = params.gravity;
    const double bounces = std::min(1e3, (1 + params.restitution) / std::max(1e-3, 1 - params.restitution));
    fall_time = (std::abs(up) + std::sqrt(up * up + 2 * g * params.drop_height)) / g * bounces;
  }
  // The impact rule's "pulled back within a tenth of a step" (impact_support.cpp) is on the paper's step; the
  // adaptive integrator's steps have no fixed length, so it uses a fixed time scale, 0.05·τ, instead.
  rebound_window = adaptive ? kReboundWindow * time_scale : dt;
  max_time = params.max_time > 0 ? params.max_time : 2000 * time_scale + fall_time;
  smooth =
      params.smooth == SmoothMode::on || (params.smooth == SmoothMode::automatic && is_smooth_surface(p));

  q = orientation.normalized();
  const std::size_t n = p.hull.vertices.size();
  for (const Vec3& v : p.hull.vertices) hull_radius = std::max(hull_radius, v.norm());
  z.resize(n);
  in_contact.resize(n);
  walk_visited.resize(n);
  id_bits.resize((n + 63) / 64);
  lowest_body_height = INFINITY;
  for (const Vec3& v : p.hull.vertices) lowest_body_height = std::min(lowest_body_height, (q * v).z());
  com = Vec3(0, 0, params.drop_height - lowest_body_height);
  rigid_impacts = uses_impacts(params);
  impact_law = {params.restitution, params.friction};
  const Vec3 velocity = params.velocity - Vec3(0, 0, params.drop_speed);
  const bool toss = params.velocity != Vec3::Zero() || params.spin != Vec3::Zero();
  energy_start = (toss ? 0.5 * body.mass * velocity.squaredNorm()
                       : 0.5 * body.mass * params.drop_speed * params.drop_speed) +
                 potential_energy();
  if (params.spin != Vec3::Zero()) {
    const Mat3 R = q.toRotationMatrix();
    energy_start += 0.5 * params.spin.dot(R * body.inertia * R.transpose() * params.spin);
  }
  if (params.drop_height > 0 || toss)
    begin_flight(velocity, params.spin, params.drop_height);
  else
    begin_contact(Vec3(0, 0, -params.drop_speed));
}

double Settler::Impl::kinetic_energy() const {
  if (falling) {
    const Vec3 v = flight_velocity();
    const Mat3 R = q.toRotationMatrix();
    return 0.5 * body.mass * v.z() * v.z() + 0.5 * body.mass * (v.x() * v.x() + v.y() * v.y()) +
           0.5 * flight_omega.dot(R * body.inertia * R.transpose() * flight_omega);
  }
  if (status == Status::rest) return 0;
  return sim::rotational_energy(body, support, rot.q, rot.omega);
}

bool Settler::Impl::advance_to(double time) {
  limit = time;
  while (status == Status::running && t < time) step();
  limit = INFINITY;
  return status == Status::running;
}

bool Settler::Impl::step() {
  if (status != Status::running) return false;
  if (t >= max_time) {
    status = Status::max_time;
  } else if (steps >= params.max_steps) {
    status = Status::max_steps;
  } else if (falling) {
    fall_step();
  } else {
    rotate();
  }
  if (!phases.empty()) phases.back().t1 = t;
  return status == Status::running;
}

Sample Settler::Impl::sample() const {
  Sample s;
  s.t = t;
  s.orientation = q;
  s.omega = falling ? flight_omega : status == Status::rest ? Vec3::Zero() : rot.omega;
  s.com = com;
  s.contact = type;
  s.contact_count = falling ? 0 : static_cast<int>(contact.size());
  s.kinetic_energy = kinetic_energy();
  s.potential_energy = potential_energy();
  return s;
}

SettleResult Settler::Impl::result() const {
  SettleResult r;
  r.status = status;
  r.time = t;
  r.stable_time = stable_time;
  r.steps = steps;
  r.max_penetration = max_penetration;
  r.orientation = q;
  r.com = com;
  r.rest = rest;
  r.rest_face = rest_face;
  r.contact_points = rest_points;
  r.down_normal_body = q.conjugate() * Vec3(0, 0, -1);
  r.phases = phases;
  r.impacts = impacts;
  r.bounces = bounces;
  r.energy_start = energy_start;
  r.energy_end = kinetic_energy() + potential_energy();
  r.smooth = smooth;
  r.dt = dt;
  r.unconverged_steps = unconverged;
  return r;
}

Settler::Settler(const Particle& particle, const SettleParams& params, const Quat& orientation)
    : impl_(std::make_unique<Impl>(particle, params, orientation)) {}
Settler::~Settler() = default;
Settler::Settler(Settler&&) noexcept = default;
Settler& Settler::operator=(Settler&&) noexcept = default;

bool Settler::step() { return impl_->step(); }
bool Settler::advance_to(double time) { return impl_->advance_to(time); }
Sample Settler::sample() const { return impl_->sample(); }
Status Settler::status() const { return impl_->status; }
SettleResult Settler::result() const { return impl_->result(); }

SettleResult Settler::run(const std::function<void(const Sample&)>& observer, double sample_dt) {
  if (!(std::isfinite(sample_dt) && sample_dt >= 0))
    throw Error("sample interval must be a finite number >= 0, got " + std::to_string(sample_dt));
  if (observer) observer(sample());
  if (sample_dt > 0) {
    for (long k = 1; impl_->status == Status::running; ++k) {
      advance_to(static_cast<double>(k) * sample_dt);
      if (observer) observer(sample());
    }
    return result();
  }
  while (impl_->status == Status::running) {
    const long steps_before = impl_->steps;
    const double t_before = impl_->t;
    step();
    if (observer && (impl_->steps != steps_before || impl_->t != t_before)) observer(sample());
  }
  return result();
}

SettleResult settle(const Particle& particle, const SettleParams& params, const Quat& orientation,
                    const std::function<void(const Sample&)>& observer, double sample_dt) {
  Settler settler(particle, params, orientation);
  return settler.run(observer, sample_dt);
}

}  // namespace repose
