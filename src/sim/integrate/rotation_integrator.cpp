#include "rotation_integrator.hpp"

#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <cmath>

namespace repose::sim {

namespace odeint = boost::numeric::odeint;
using State = RotationIntegrator::State;

namespace {

Quat quat_of(const State& y) {
  Quat q(y[3], y[0], y[1], y[2]);  // Eigen's coefficient order is (x, y, z, w)
  q.normalize();
  return q;
}

// The right-hand side of Eqs 4, 9 and 15 (17 for a line) in the scaled state.
struct Motion {
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

using Stepper = odeint::runge_kutta_dopri5<State>;
using Dense = odeint::result_of::make_dense_output<Stepper>::type;

}  // namespace

struct RotationIntegrator::Impl {
  Motion motion;
  Dense dense;
  double time_unit;

  Impl(const Body& body, double length, double tolerance, double max_step)
      : dense(odeint::make_dense_output(tolerance, tolerance, max_step / std::sqrt(length / body.gravity),
                                        Stepper())),
        time_unit(std::sqrt(length / body.gravity)) {
    motion.body = &body;
    motion.time_unit = time_unit;
    motion.momentum_unit = body.mass * length * length / time_unit;
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
  impl_->dense.initialize(y, t / impl_->time_unit, first_step / impl_->time_unit);
}

std::pair<double, double> RotationIntegrator::step() {
  const auto [s0, s1] = impl_->dense.do_step(std::cref(impl_->motion));
  return {s0 * impl_->time_unit, s1 * impl_->time_unit};
}

Rotation RotationIntegrator::state_at(double t) const {
  State y;
  impl_->dense.calc_state(t / impl_->time_unit, y);
  return impl_->motion.rotation(y);
}

Quat RotationIntegrator::orientation_at(double t) const {
  State y;
  impl_->dense.calc_state(t / impl_->time_unit, y);
  return quat_of(y);
}

double RotationIntegrator::time() const { return impl_->dense.current_time() * impl_->time_unit; }

double RotationIntegrator::proposed_step() const {
  return impl_->dense.current_time_step() * impl_->time_unit;
}

}  // namespace repose::sim
