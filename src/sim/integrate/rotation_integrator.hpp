// Internal: adaptive integration of a rotation about a fixed support (Eqs 4-18) with dense output.
//
// Between contact events the paper's motion is a smooth ODE in the orientation q and the angular momentum L
// about the support: dL/dt = r × W − C·ω (Eq 4; projected on the axis for a line, Eq 17), dq/dt = ½ ω ⊗ q
// (Eq 9), ω = R I_O⁻¹ Rᵀ L (Eq 15). It is integrated by the engine's one dense stepper (dense_stepper.hpp:
// Dormand–Prince 5(4) with dense output) with error control on scaled variables: time in T = sqrt(L/g),
// momentum in m·L²/T, so one tolerance means the same for a grain and a boulder.
#pragma once

#include <array>
#include <memory>
#include <utility>

#include "../body/dynamics.hpp"

namespace repose::sim {

class RotationIntegrator {
 public:
  /// `length` is L, `tolerance` the local error bound (absolute and relative) on the scaled state, and
  /// `max_step` the longest step (time).
  RotationIntegrator(const Body& body, double length, double tolerance, double max_step);
  ~RotationIntegrator();
  RotationIntegrator(RotationIntegrator&&) noexcept;
  RotationIntegrator& operator=(RotationIntegrator&&) noexcept;

  /// Starts integrating from `state` at time `t` about `support`; `first_step` is the trial size (time).
  void start(const Support& support, const Rotation& state, double t, double first_step);
  /// One accepted adaptive step; returns its interval [t0, t1].
  std::pair<double, double> step();
  /// The state at any time of the last step's interval (dense output): q normalised, ω from L.
  Rotation state_at(double t) const;
  /// The orientation alone at a time of the last step's interval (cheaper: no ω).
  Quat orientation_at(double t) const;
  double time() const;  ///< the end of the last step (or the start time)
  /// The size the error control proposes for the next step (time): a restart after an event starts there.
  double proposed_step() const;

  using State = std::array<double, 7>;  ///< q (w, x, y, z), L / (m·L²/T)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace repose::sim
