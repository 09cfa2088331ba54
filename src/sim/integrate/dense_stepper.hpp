// Internal: the one adaptive integrator of the engine's smooth motions: Dormand–Prince 5(4) (Boost.Odeint's
// runge_kutta_dopri5 in its dense-output form) in scaled time s = t / T, T = sqrt(L/g), so one tolerance
// means the same for a grain and a boulder. Dense output (a 4th-order interpolant over each accepted step)
// lets the phases locate events inside a step without integrating again.
//
// The rotation about a support (rotation_integrator.hpp, the paper's phase) and the free body under contact
// forces (body_integrator.hpp, the frictional phase) each give it their scaled state and right-hand side.
#pragma once

#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <functional>
#include <utility>

namespace repose::sim {

/// `State` is a std::array of the scaled variables; the right-hand side given to step() is dy/ds.
template <class State>
class DenseStepper {
 public:
  /// `time_unit` is T, `tolerance` the local error bound (absolute and relative) on the scaled state and
  /// `max_step` the longest step (time).
  DenseStepper(double time_unit, double tolerance, double max_step)
      : time_unit_(time_unit),
        dense_(boost::numeric::odeint::make_dense_output(tolerance, tolerance, max_step / time_unit,
                                                         Stepper())) {}

  /// Starts from `y` at time t with a trial step `first_step` (time).
  void start(const State& y, double t, double first_step) {
    dense_.initialize(y, t / time_unit_, first_step / time_unit_);
  }
  /// One accepted adaptive step of dy/ds = rhs(y); returns its interval [t0, t1] (time).
  template <class Rhs>
  std::pair<double, double> step(const Rhs& rhs) {
    const auto [s0, s1] = dense_.do_step(std::cref(rhs));
    return {s0 * time_unit_, s1 * time_unit_};
  }
  /// The scaled state at any time of the last step's interval.
  State state_at(double t) const {
    State y;
    dense_.calc_state(t / time_unit_, y);
    return y;
  }
  double time() const { return dense_.current_time() * time_unit_; }  ///< the end of the last step
  /// The size the error control proposes for the next step (time): a restart after an event starts there.
  double proposed_step() const { return dense_.current_time_step() * time_unit_; }
  double time_unit() const { return time_unit_; }

 private:
  using Stepper = boost::numeric::odeint::runge_kutta_dopri5<State>;
  using Dense = typename boost::numeric::odeint::result_of::make_dense_output<Stepper>::type;
  double time_unit_;
  Dense dense_;
};

}  // namespace repose::sim
