// The six-degree-of-freedom integrator (body_integrator.hpp).
#include "body_integrator.hpp"

#include <cmath>

#include "../body/dynamics.hpp"
#include "dense_stepper.hpp"

namespace repose::sim {

using State = BodyIntegrator::State;

namespace {

struct Scales {
  double length = 1, time = 1, speed = 1, energy = 1;  // L, T, L/T, m·g·L
};

BodyState body_state(const State& y, const Scales& u) {
  BodyState s;
  s.com = u.length * Vec3(y[0], y[1], y[2]);
  s.velocity = u.speed * Vec3(y[3], y[4], y[5]);
  s.q = Quat(y[9], y[6], y[7], y[8]);  // Eigen's coefficient order is (x, y, z, w)
  s.q.normalize();
  s.omega = Vec3(y[10], y[11], y[12]) / u.time;
  return s;
}

// dy/ds with s = t / T.
struct Equations {
  Scales units;
  BodyIntegrator::Rates rates;

  void operator()(const State& y, State& dyds, double /*s*/) const {
    const BodyState s = body_state(y, units);
    const BodyRates r = rates(s);
    const double t = units.time;
    for (int i = 0; i < 3; ++i) {
      dyds[i] = s.velocity[i] * t / units.length;
      dyds[3 + i] = r.acceleration[i] * t / units.speed;
      dyds[10 + i] = r.angular_acceleration[i] * t * t;
    }
    const Eigen::Vector4d dq = quaternion_rate(s.q, s.omega) * t;
    for (int i = 0; i < 4; ++i) dyds[6 + i] = dq[i];
    dyds[13] = -r.friction_power * t / units.energy;
    dyds[14] = -r.damping_power * t / units.energy;
    dyds[15] = r.slip_rate * t / units.length;
    dyds[16] = r.normal_power * t / units.energy;
  }
};

}  // namespace

struct BodyIntegrator::Impl {
  Equations equations;
  DenseStepper<State> stepper;

  Impl(double mass, double length, double gravity, double tolerance, double max_step)
      : stepper(std::sqrt(length / gravity), tolerance, max_step) {
    Scales& u = equations.units;
    u.length = length;
    u.time = std::sqrt(length / gravity);
    u.speed = length / u.time;
    u.energy = mass * gravity * length;
  }
};

BodyIntegrator::BodyIntegrator(double mass, double length, double gravity, double tolerance, double max_step)
    : impl_(std::make_unique<Impl>(mass, length, gravity, tolerance, max_step)) {}
BodyIntegrator::~BodyIntegrator() = default;
BodyIntegrator::BodyIntegrator(BodyIntegrator&&) noexcept = default;
BodyIntegrator& BodyIntegrator::operator=(BodyIntegrator&&) noexcept = default;

void BodyIntegrator::start(const BodyState& state, const BodyLedger& ledger, double t, double first_step,
                           Rates rates) {
  Equations& e = impl_->equations;
  e.rates = std::move(rates);
  const Scales& u = e.units;
  State y;
  const Quat q = state.q.normalized();
  for (int i = 0; i < 3; ++i) {
    y[i] = state.com[i] / u.length;
    y[3 + i] = state.velocity[i] / u.speed;
    y[10 + i] = state.omega[i] * u.time;
  }
  y[6] = q.x();
  y[7] = q.y();
  y[8] = q.z();
  y[9] = q.w();
  y[13] = ledger.friction_work / u.energy;
  y[14] = ledger.damping_work / u.energy;
  y[15] = ledger.sliding_distance / u.length;
  y[16] = ledger.normal_work / u.energy;
  impl_->stepper.start(y, t, first_step);
}

std::pair<double, double> BodyIntegrator::step() { return impl_->stepper.step(impl_->equations); }

BodyState BodyIntegrator::state_at(double t) const {
  return body_state(impl_->stepper.state_at(t), impl_->equations.units);
}

BodyLedger BodyIntegrator::ledger_at(double t) const {
  const State y = impl_->stepper.state_at(t);
  const Scales& u = impl_->equations.units;
  return {y[13] * u.energy, y[14] * u.energy, y[15] * u.length, y[16] * u.energy};
}

double BodyIntegrator::proposed_step() const { return impl_->stepper.proposed_step(); }

}  // namespace repose::sim
