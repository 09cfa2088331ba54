// The touch that ends a spinning flight: the first instant at which a hull vertex reaches the wall, by the
// wall-crossing search (events/wall_crossing.hpp) with the bound |z''| ≤ A = g + 2·R·|L|²/I_min² on every
// vertex's height (the centre of mass's fall plus the body's centripetal and torque-free angular
// accelerations, |ω| ≤ |L|/I_min).
#include <Eigen/Eigenvalues>
#include <cmath>

#include "../body/kinematics.hpp"
#include "../events/wall_crossing.hpp"
#include "flight.hpp"

namespace repose::sim {

// The lower end of a bracket kEventResolution of the step wide, so nothing is ever below the wall; +∞ if no
// vertex reaches the wall in (a, b].
double Flight::locate_touch(double a, double b) {
  const auto& verts = run_.particle.hull.vertices;
  if (inertia_min_ == 0)
    inertia_min_ = Eigen::SelfAdjointEigenSolver<Mat3>(run_.body.inertia, Eigen::EigenvaluesOnly)
                       .eigenvalues()
                       .minCoeff();
  const double spin_momentum = angular_momentum(run_.q.toRotationMatrix(), run_.body.inertia, omega_).norm();
  const double accel = run_.params.gravity +
                       2 * run_.hull_radius * spin_momentum * spin_momentum / (inertia_min_ * inertia_min_);
  // The body at an instant, as the wall-crossing search takes it: the torque-free rotation's dense output and
  // the centre of mass's parabola.
  const auto frame_at = [&](double s) {
    const Rotation st = rotation_->state_at(s);
    const auto [height, speed] = centre_at(s);
    return WallFrame{st.q, st.omega, height, speed};
  };
  return wall_.first_crossing(a, b, verts, run_.near_wall, run_.hull_radius, accel,
                              (b - a) * kEventResolution, frame_at, [](std::size_t) { return 0.0; });
}

}  // namespace repose::sim
