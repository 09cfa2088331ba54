// Internal: the flight phase — off the wall. The first descent (section 2.1) and, for a toss or a rebound,
// a flight (issue 14). The centre of mass follows its parabola exactly; the orientation is fixed (no spin:
// the touch time in closed form) or turns torque-free (Euler's equations, integrated to the engine's
// tolerance), its touch located on the dense output by a search that cannot step over it.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "../events/wall_crossing.hpp"
#include "../integrate/rotation_integrator.hpp"
#include "../run.hpp"

namespace repose::sim {

class Flight {
 public:
  /// Starts a flight at run.t from the run's pose with the centre of mass's `velocity` and the angular
  /// velocity `omega` (world frame); `height` is the lowest point's height above the wall (the caller's
  /// exact value: the drop height, or 0 after a rebound).
  Flight(Run& run, const Vec3& velocity, const Vec3& omega, double height);
  Flight(const Flight&) = delete;  // the integrator keeps a pointer to free_body_
  Flight& operator=(const Flight&) = delete;

  /// The motion when a hull vertex reaches the wall.
  struct Touch {
    Vec3 velocity;
    Vec3 omega;
  };
  /// Advances one step (shorter at the touch, the time limit or advance_to's); the touch, once reached.
  std::optional<Touch> step();

  Vec3 velocity() const;  ///< the centre of mass's velocity at run.t
  const Vec3& omega() const { return omega_; }
  double kinetic_energy() const;

  /// A spinning flight's next integrator step, [a, b], with the touch located in it (located_touch()).
  /// step() takes it when run.t reaches the current step's end; a test may take it first to check the touch.
  std::pair<double, double> integrate_step();
  /// The first instant in (a, b] at which a hull vertex reaches the wall, or +∞ (flight_touch.cpp).
  double locate_touch(double a, double b);
  bool spinning() const { return spinning_; }
  double step_end() const { return step_end_; }
  double located_touch() const { return touch_; }
  /// The centre of mass's height and vertical speed at time s (its parabola).
  std::pair<double, double> centre_at(double s) const;
  const RotationIntegrator& rotation() const { return *rotation_; }

 private:
  Run& run_;
  Vec3 origin_;    // the centre of mass at the flight's start
  Vec3 velocity_;  // its velocity then
  double t0_;      // the flight's start
  Vec3 omega_;
  bool spinning_;  // whether the orientation turns (else it is fixed and the touch time closed-form)
  // Without spin: the touch time in closed form, the grid steps taken (steps end on multiples of dt from the
  // flight's start) and the lowest hull vertex's height below the centre of mass.
  double touch_time_ = INFINITY;
  long grid_steps_ = 0;
  double lowest_offset_ = 0;
  // With spin: the torque-free rotation about the centre of mass (damping 0), its current step's end and
  // the touch located in it.
  Body free_body_;
  std::optional<RotationIntegrator> rotation_;
  double step_end_ = -INFINITY;
  double touch_ = INFINITY;
  double inertia_min_ = 0;  // the body's smallest principal moment (the touch search's bound)
  WallCrossing wall_;       // the touch search, with its working memory kept from step to step
};

}  // namespace repose::sim
