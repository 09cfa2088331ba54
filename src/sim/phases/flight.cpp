// The flight phase (flight.hpp): the parabola, and the torque-free rotation stepped to its touch.
#include "flight.hpp"

#include <algorithm>
#include <cmath>

#include "../body/kinematics.hpp"

namespace repose::sim {

Flight::Flight(Run& run, const Vec3& velocity, const Vec3& omega, double height)
    : run_(run),
      origin_(run.com),
      velocity_(velocity),
      t0_(run.t),
      omega_(omega),
      spinning_(omega != Vec3::Zero()) {
  run.record.set_type(run.record.phases.empty() && !spinning_ ? ContactType::free_fall : ContactType::flight,
                      run.t);
  if (!spinning_) {
    lowest_offset_ = run.lowest_offset(run.q);
    const double up = velocity.z(), g = run.params.gravity;
    touch_time_ = t0_ + (up + std::sqrt(up * up + 2 * g * height)) / g;
    return;
  }
  const Body& body = run.body;
  free_body_ = {body.mass, body.inertia, body.gravity, 0.0};
  rotation_.emplace(free_body_, run.tol.length, run.params.tolerance, run.tol.flight_max_step);
  const Support centre{run.com, Vec3::Zero(), false, Vec3::UnitX()};
  const Mat3 R = run.q.toRotationMatrix();
  const Vec3 momentum = angular_momentum(R, body.inertia, omega);  // about the centre of mass
  rotation_->start(centre, {run.q, omega, momentum}, run.t, run.tol.first_step);
  step_end_ = run.t;
}

Vec3 Flight::velocity() const { return velocity_ - Vec3(0, 0, run_.params.gravity * (run_.t - t0_)); }

std::pair<double, double> Flight::centre_at(double s) const {
  const double tau = s - t0_, g = run_.params.gravity;
  return {origin_.z() + velocity_.z() * tau - 0.5 * g * tau * tau, velocity_.z() - g * tau};
}

double Flight::kinetic_energy() const {
  const Vec3 v = velocity();
  const Mat3 R = run_.q.toRotationMatrix();
  const double m = run_.body.mass;
  return 0.5 * m * v.z() * v.z() + 0.5 * m * (v.x() * v.x() + v.y() * v.y()) +
         0.5 * omega_.dot(angular_momentum(R, run_.body.inertia, omega_));
}

std::pair<double, double> Flight::integrate_step() {
  const auto [a, b] = rotation_->step();
  step_end_ = b;
  touch_ = locate_touch(a, b);
  ++run_.steps;
  return {a, b};
}

std::optional<Flight::Touch> Flight::step() {
  Run& run = run_;
  if (spinning_) {
    // One integrator step at a time, the touch located in each before the flight goes on.
    if (run.t >= step_end_) integrate_step();
    const double end = std::min({touch_, step_end_, run.tol.max_time, run.limit});
    run.t = end;
    const Rotation state = rotation_->state_at(run.t);
    run.q = state.q;
    omega_ = state.omega;
    const double tau = run.t - t0_;
    run.com = origin_ + velocity_ * tau - Vec3(0, 0, 0.5 * run.params.gravity * tau * tau);
    if (end != touch_) return std::nullopt;
    // The bracket's lower end has every vertex on or above the wall: the lowest is set exactly on it (by at
    // most the locator's resolution; the potential energy of the move is in the frictional ledger).
    const double parabola = run.com.z();
    run.com.z() = -run.lowest_offset(run.q);
    run.record.account.repositioning += run.body.mass * run.params.gravity * (run.com.z() - parabola);
    return Touch{velocity(), omega_};
  }
  // Without rotation, exact: the parabola from its start to the touch time. Steps end on the grid of
  // multiples of dt from the flight's start (observers see the fall there); a stop at the time limit or at
  // advance_to() is not a step, so where a run is stopped never changes it.
  const double g = run.params.gravity, down = -velocity_.z();
  const double grid = t0_ + static_cast<double>(grid_steps_ + 1) * run.tol.dt;
  const double end = std::min({grid, touch_time_, run.tol.max_time, run.limit});
  run.t = end;
  const double tau = run.t - t0_;
  run.com.x() = origin_.x() + velocity_.x() * tau;
  run.com.y() = origin_.y() + velocity_.y() * tau;
  if (end == touch_time_) {
    ++run.steps;
    run.com.z() = -lowest_offset_;  // exactly touching
    return Touch{velocity(), Vec3::Zero()};
  }
  if (end == grid) {
    ++grid_steps_;
    ++run.steps;
  }
  run.com.z() = origin_.z() - (down * tau + 0.5 * g * tau * tau);
  return std::nullopt;
}

}  // namespace repose::sim
