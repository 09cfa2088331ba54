// Internal: the contact phase with finite friction (issue 34; docs/method.md, "Friction after the landing").
//
// The body is free (six degrees of freedom) with unilateral contacts at its hull vertices on the wall: each
// pressed point sticks or slides by Coulomb's law (contact_forces.hpp); a point whose normal force would turn
// negative opens and lifts; a body whose points all leave the wall ends the phase (a lift-off: the engine's
// flight takes the hop, and its touch starts this phase again, docs/method.md "Phases"). Between events the
// rule of each point is fixed — sliding along its slip, or at rest on the wall (stick, or start to slide on
// the cone) — and the motion is integrated with dense output (body_integrator.hpp). Events, located on the
// dense output: a vertex reaching the wall (an impact by the impact laws, plastic when too slow to leave
// the band again; a landing's impacts are resolved at the phase's first segment start the same way) and a
// point's rule ending (a slip stopping or reversing, a point at rest starting to slip, a point lifting out
// of the band): the points' rules are chosen again. Painlevé's
// inconsistent case is an impact without collision at the point. The phase ends in the flush rest of a stable
// face, reached when nothing moves and nothing accelerates.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <span>
#include <utility>
#include <variant>
#include <vector>

#include "../events/wall_crossing.hpp"
#include "../integrate/body_integrator.hpp"
#include "../run.hpp"
#include "../solver/contact_forces.hpp"
#include "rest.hpp"

namespace repose::sim {

class FrictionalContact {
 public:
  /// Starts at run.t from the run's pose with the centre of mass's `motion` (world frame).
  FrictionalContact(Run& run, const Motion& motion);
  FrictionalContact(const FrictionalContact&) = delete;  // the integrator's callback points at this
  FrictionalContact& operator=(const FrictionalContact&) = delete;

  /// Every point leaves the wall: the body flies from its pose with `motion`, its lowest point `height` above
  /// the wall (within the band).
  struct LiftOff {
    Motion motion;
    double height = 0;
  };
  /// How the phase ends: at rest, or lifted off the wall.
  using End = std::variant<RestPose, LiftOff>;
  /// Advances one step (shorter at an event, the time limit or advance_to's); the phase's end, once reached.
  std::optional<End> step();

  const Vec3& velocity() const { return velocity_; }
  /// When the run first took this phase (its hops between landings count in its time).
  double start_time() const { return run_.record.frictional_start; }
  /// Segments kept ending at once even with every point taken as at rest: the engine hands over.
  bool stalled() const;
  const Vec3& omega() const { return omega_; }
  double kinetic_energy() const;
  /// The points pressed on the wall and their modes, as of the current segment; before the first segment
  /// (a run started on the wall, sampled at t = 0) the points within the band, sliding where they slip.
  int contact_count() const;
  int sticking() const;
  int sliding() const;
  /// The contact type by the points on the wall (flight when none).
  ContactType contact_type() const;
  /// Each point of the current segment with its velocity and the force on it now, by the segment's rules
  /// (world frame): for white-box tests of the forces along a run.
  struct PointForce {
    Vec3 point, velocity, force;
  };
  std::vector<PointForce> point_forces() const;

 private:
  // The start of a segment at run.t: the pose projected onto the wall, the points on it classified, impacts
  // and Painlevé's case resolved, the lift-off and rest tests, and the integrator started.
  std::optional<End> begin_segment();
  void classify();
  bool resolve_impacts();
  bool hold_unresolved_hops();
  bool resolve_painleve();
  std::vector<std::pair<Vec3, bool>> resting_points() const;
  bool stop_landed_points();
  void undo_drift();
  // The least-norm velocity change that brings the points `arms` to rest (`along`: in every direction, else
  // only across the wall), its kinetic energy in drift_corrections.
  void project_to_rest(const std::vector<Vec3>& arms, bool along);
  bool tip_off_balance(const Support& support);
  bool face_on_wall(int face) const;
  bool tip_onto_face(const std::vector<int>& band, int face);
  void turn_past_line(const Vec3& pivot, const Vec2& outward);
  // The least-norm impulses at `arms` that bring them to rest (`along`: in every direction, else only across
  // the wall).
  Eigen::VectorXd stopping_impulses(const std::vector<Vec3>& arms, bool along) const;
  Eigen::VectorXd stopping_impulses_pushing(const std::vector<Vec3>& arms) const;
  const std::vector<int>& within_band() const;
  BodyRates rates(const BodyState& s) const;
  void count_fallbacks(const ContactForces& f) const;
  ContactForces forces_at(const BodyState& s) const;  // at the segment's points, by their rules
  ContactForces forces_at(const BodyState& s, const std::vector<int>& points,
                          std::span<const PointCondition> conditions, std::span<const Vec3> warm = {}) const;
  // The first event in (a, b], or +∞.
  double locate_event(double a, double b);
  // Before the first segment: the points within the band, and how many of them slip.
  std::pair<int, int> points_before_start() const;
  void move_to(double t);

  Run& run_;
  BodyIntegrator integrator_;
  Vec3 velocity_, omega_;
  BodyLedger ledger_;
  std::vector<int> active_;                 // hull vertices on the wall and not leaving it
  std::vector<PointCondition> conditions_;  // their rules for this segment
  std::vector<int> leaving_slowly_;         // in the band, leaving slower than the separation speed
  std::vector<int> at_rest_before_;         // the points at rest in the segment before (hull vertices)
  std::vector<int> sliding_before_;         // and those sliding
  ContactForces forces_;                    // at the segment's start
  PointList<Vec3> warm_start_;              // forces_' forces, where the sweeps of the rates start
  WallCrossing wall_;                       // the touch search, its working memory kept from step to step
  std::vector<char> on_wall_;  // by hull vertex: in active_ (its level: the drift it may sink by)
  double step_end_ = -INFINITY;
  double event_ = INFINITY;
  bool started_ = false;
  double segment_start_ = 0;
  int stalls_ = 0;  // segments in a row that ended at once
};

}  // namespace repose::sim
