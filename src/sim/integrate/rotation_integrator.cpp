#include "rotation_integrator.hpp"

#include <cmath>

#include "dense_stepper.hpp"

namespace repose::sim {

using State = RotationIntegrator::State;

namespace {

Quat quat_of(const State& y) {
  Quat q(y[3], y[0], y[1], y[2]);  // Eigen's coefficient order is (x, y, z, w)
  q.normalize();
  return q;
}

// The right-hand side of Eqs 4, 9 and 15 (17 for a line) in the scaled state.
struct RotationEquations {
  const Body* body = nullptr;
  Support support;
  SupportInertia inertia;    // of `support`, computed once per support
  double momentum_unit = 1;  // m·L²/T
  double time_unit = 1;      // T: the state's time derivatives are per T (see operator())

  Rotation rotation(const State& y) const {
    Rotation r;
    r.q = quat_of(y);
    r.momentum = momentum_unit * Vec3(y[4], y[5], y[6]);
    r.omega = omega_from_momentum(inertia, support, r.q, r.momentum);
    return r;
  }

  // dy/ds with s = t / T: the time variable of the integration is scaled too.
  void operator()(const State& y, State& dyds, double /*s*/) const {
    const Rotation r = rotation(y);
    const Eigen::Vector4d dq = quaternion_rate(r.q, r.omega) * time_unit;
    const Vec3 dl = moment(*body, support, r.q, r.omega) * (time_unit / momentum_unit);
    for (int i = 0; i < 4; ++i) dyds[i] = dq[i];
    for (int i = 0; i < 3; ++i) dyds[4 + i] = dl[i];
  }
};

}  // namespace

struct RotationIntegrator::Impl {
  RotationEquations motion;
  DenseStepper<State> stepper;

  Impl(const Body& body, double length, double tolerance, double max_step)
      : stepper(std::sqrt(length / body.gravity), tolerance, max_step) {
    motion.body = &body;
    motion.time_unit = stepper.time_unit();
    motion.momentum_unit = body.mass * length * length / stepper.time_unit();
  }
};

RotationIntegrator::RotationIntegrator(const Body& body, double length, double tolerance, double max_step)
    : impl_(std::make_unique<Impl>(body, length, tolerance, max_step)) {}
RotationIntegrator::~RotationIntegrator() = default;
RotationIntegrator::RotationIntegrator(RotationIntegrator&&) noexcept = default;
RotationIntegrator& RotationIntegrator::operator=(RotationIntegrator&&) noexcept = default;

void RotationIntegrator::start(const Support& support, const Rotation& state, double t, double first_step) {
  impl_->motion.support = support;
  impl_->motion.inertia = support_inertia(*impl_->motion.body, support);
  State y;
  const Quat q = state.q.normalized();
  y[0] = q.x();
  y[1] = q.y();
  y[2] = q.z();
  y[3] = q.w();
  const Vec3 l = state.momentum / impl_->motion.momentum_unit;
  for (int i = 0; i < 3; ++i) y[4 + i] = l[i];
  impl_->stepper.start(y, t, first_step);
}

std::pair<double, double> RotationIntegrator::step() { return impl_->stepper.step(impl_->motion); }

Rotation RotationIntegrator::state_at(double t) const {
  return impl_->motion.rotation(impl_->stepper.state_at(t));
}

Quat RotationIntegrator::orientation_at(double t) const { return quat_of(impl_->stepper.state_at(t)); }

double RotationIntegrator::time() const { return impl_->stepper.time(); }

double RotationIntegrator::proposed_step() const { return impl_->stepper.proposed_step(); }

}  // namespace repose::sim
