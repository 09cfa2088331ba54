// Internal: adaptive integration of a free rigid body's six degrees of freedom under given forces, with dense
// output (the frictional contact phase, phases/frictional_contact.hpp).
//
// The state is the centre of mass and its velocity, the orientation and the angular velocity (world frame);
// the accelerations come from a callback (gravity, the damping moment, the gyroscopic term and the contact
// forces of the phase's current modes), which also gives the powers the energy ledger integrates: friction's
// and the damping moment's, and the rate at which the contact slides. The engine's one dense stepper
// (dense_stepper.hpp) with error control on scaled variables (length in L, time in T = sqrt(L/g)), as the
// rotation about a support (rotation_integrator.hpp), so one tolerance means the same at any scale.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <utility>

#include "repose/geometry/types.hpp"

namespace repose::sim {

struct BodyState {
  Vec3 com = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Quat q = Quat::Identity();  ///< body → world
  Vec3 omega = Vec3::Zero();  ///< world frame
};

struct BodyRates {
  Vec3 acceleration = Vec3::Zero();
  Vec3 angular_acceleration = Vec3::Zero();
  double friction_power = 0;  ///< the contact forces' power (≤ 0)
  double damping_power = 0;   ///< the damping moment's (≤ 0)
  double normal_power = 0;    ///< the normal forces' (their points' drift across the wall: ~0)
  double slip_rate = 0;       ///< the contact's sliding speed (the ledger's sliding distance grows by it)
};

/// What the phase's forces took, integrated along with the motion: positive amounts.
struct BodyLedger {
  double friction_work = 0;
  double damping_work = 0;
  double sliding_distance = 0;
  double normal_work = 0;  ///< done on the body (signed)
};

class BodyIntegrator {
 public:
  using Rates = std::function<BodyRates(const BodyState&)>;
  /// `mass` is m, `length` L, `gravity` g, `tolerance` the local error bound (absolute and relative) on the
  /// scaled state (works in m·g·L), `max_step` the longest step (time).
  BodyIntegrator(double mass, double length, double gravity, double tolerance, double max_step);
  ~BodyIntegrator();
  BodyIntegrator(BodyIntegrator&&) noexcept;
  BodyIntegrator& operator=(BodyIntegrator&&) noexcept;

  /// Starts from `state` and `ledger` at time t with a trial step `first_step` (time); `rates` is called
  /// with every trial state until the next start.
  void start(const BodyState& state, const BodyLedger& ledger, double t, double first_step, Rates rates);
  /// One accepted adaptive step; returns its interval [t0, t1].
  std::pair<double, double> step();
  /// The state and the ledger at any time of the last step's interval (dense output; q normalised).
  BodyState state_at(double t) const;
  BodyLedger ledger_at(double t) const;
  /// The size the error control proposes for the next step (time).
  double proposed_step() const;

  using State = std::array<double, 17>;  ///< x/L, v/(L/T), q (x, y, z, w), ω·T, the ledger scaled

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace repose::sim
