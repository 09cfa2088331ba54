// Internal: the settling engine — a state machine over named phases. Its transitions are drawn once, with
// their events, in docs/method.md ("Phases"); Engine::step() holds every one of them. The engine holds
// what every phase shares (Run) and the current phase; a phase owns its own state and lives in its own file
// (phases/).
#pragma once

#include <variant>

#include "phases/contact.hpp"
#include "phases/flight.hpp"
#include "phases/frictional_contact.hpp"
#include "phases/impact.hpp"
#include "phases/rest.hpp"
#include "run.hpp"

namespace repose::sim {

class Engine {
 public:
  /// Starts a run with the particle at `orientation` (body → world), its lowest point at the drop height
  /// above the wall, directly above the origin. Throws repose::Error for invalid parameters.
  Engine(const Particle& particle, const SettleParams& params, const Quat& orientation);
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  /// One step of the current phase, and the transition it calls for. False once the run has ended.
  bool step();
  /// Steps until `time` (no step goes past it) or the end.
  bool advance_to(double time);

  Status status() const;
  Sample sample() const;
  SettleResult result() const;

  const Run& run() const { return run_; }
  /// The current phase (for white-box tests that check a phase's own work as the run goes).
  using AnyPhase = std::variant<Flight, Contact, FrictionalContact, Rest, Stopped>;
  AnyPhase& phase() { return phase_; }

 private:
  void start_flight(const Vec3& velocity, const Vec3& omega, double height);
  void start_contact(const Vec3& com_velocity, const Vec3& omega, bool carry);
  /// Finite friction: the contact phase of a free body with Coulomb's law at every point on the wall.
  void start_frictional(const Motion& motion);
  bool frictional() const { return std::isfinite(run_.params.friction); }
  void stop(Status why);
  double kinetic_energy() const;

  Run run_;
  AnyPhase phase_;
};

}  // namespace repose::sim
