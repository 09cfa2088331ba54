// Internal: the contact phase — the paper's kinematics (sections 2.2-2.4). Translation has stopped; the
// particle turns about a support on the wall (a point, or a line for line contacts; a surface contact turns
// about the previous axis), driven by its weight's moment minus damping, until its touching points hold the
// centre of mass over a stable hull face. The files:
//   contact.cpp                 the phase's start and step, its energy
//   contact_paper_step.cpp      the paper's fixed step (Eqs 10-16), its events bracketed by halving
//   contact_adaptive_step.cpp   the adaptive integrator's step: energy bounds, candidates, event samples
//   contact_step_events.cpp     the step's first event on the dense output
//   contact_decisions.cpp       the contact decisions at any instant of a step, and where they change
//   contact_update.cpp          after a step: the contact set, Algorithm 1, the paper's stability test
//   contact_support.cpp         the support the contacts call for, a line's support test, edge balances
//   contact_walks.cpp           the vertex sets near the wall by walks over the hull's edge graph
// The two steppers are types (PaperStepper, AdaptiveStepper below), one chosen when the phase is built; how
// the surface meets the wall is the run's SurfaceModel (wall/surface_model.hpp).
//
// Two sets of points drive the method, both over the convex hull's vertices (only they can touch a flat
// wall):
//   - the contact set (the paper's): vertices within ε of the wall; it gives the contact type (Algorithm 1),
//     the best-fit rotation axis, and the stability tests of §2.4;
//   - the touching set: vertices on the wall (within 1e-9·L). The rotation always keeps its support point on
//     the wall, and no vertex may pass below it: every new touch is located inside the step.
// When the paper's stability test fires, the phase finishes the rotation on touching points alone until they
// hold the centre of mass, then the rest phase sets the supporting hull face exactly flush.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include "../impact/impact_support.hpp"
#include "../integrate/rotation_integrator.hpp"
#include "../run.hpp"
#include "../wall/contact_type.hpp"
#include "rest.hpp"
#include "step_vertices.hpp"

namespace repose::sim {

/// A pose about the current support: the orientation and the centre of mass it puts where.
struct Pose {
  Quat q;
  Vec3 com;
};

class Contact {
 public:
  explicit Contact(Run& run);
  Contact(const Contact&) = delete;  // the integrator keeps a pointer to the run's body
  Contact& operator=(const Contact&) = delete;

  /// The start of the rotation (a touch, or a run that starts on the wall): the particle pivots about its
  /// lowest point. The paper's touch (`carry` false) starts it from rest; after rigid impacts it starts with
  /// the angular momentum about the pivot that `omega` and `com_velocity` have. A rest if it rests at once.
  std::optional<RestPose> begin(const Vec3& com_velocity, const Vec3& omega, bool carry);
  /// One step, or the part of it before its first event, then the contact update; a rest ends the phase.
  std::optional<RestPose> step();

  const Vec3& omega() const { return rot_.omega; }
  int contact_count() const { return static_cast<int>(contact_.size()); }
  double kinetic_energy() const;  ///< of the rotation about the support, ½ ωᵀ I_O ω
  const Support& support() const { return support_; }
  /// Stopped inside an adaptive step (advance_to).
  bool inside_step() const {
    const auto* adaptive = std::get_if<AdaptiveStepper>(&stepper_);
    return adaptive != nullptr && adaptive->next == AdaptiveStepper::Next::inside;
  }

  /// What the contact update decides from a pose for the current contact and touching sets: the contact
  /// type (Algorithm 1), whether the touching points hold the centre of mass, whether the paper's stability
  /// test passes, whether a line support still holds. With `with_reach`, also the angle (rad) the particle
  /// can turn about its support before each can change (0: unknown), which is not part of the decision.
  struct Decision {
    ContactType type = ContactType::point;
    bool hold = false, stable = false, line_holds = false;
    std::array<double, 4> reach_of{};
    double reach() const { return std::min({reach_of[0], reach_of[1], reach_of[2], reach_of[3]}); }
    bool operator==(const Decision& o) const {
      return type == o.type && hold == o.hold && stable == o.stable && line_holds == o.line_holds;
    }
  };
  /// The decisions at orientation qq about the current support. Once the stability test has passed the
  /// contact set is the pose's own, picked among `candidates` (a superset of the vertices in the band).
  Decision decision_at(const Quat& qq, bool with_reach, std::span<const int> candidates);
  /// A bound (rad) of the angle the particle can turn about its support in the next time h from now, from
  /// energy (contact_adaptive_step.cpp); the adaptive steps' event candidates and decision checks rest on it
  /// (adaptive runs only).
  double arc_bound(double h) const;
  /// Whether the decisions take the pose's own contact set (the stability test has passed, adaptive).
  bool decisions_use_own_set() const {
    return std::holds_alternative<AdaptiveStepper>(stepper_) && run_.surface.has_band_events() && finishing_;
  }
  /// The height above the wall of hull vertex k at the orientation whose rotation matrix has third row r3,
  /// about the current support (the one expression every height test uses, so that they agree to the bit).
  double height_of(const Vec3& r3, int k) const {
    return support_.world.z() +
           r3.dot(run_.particle.hull.vertices[static_cast<std::size_t>(k)] - support_.body);
  }

 private:
  // ---- geometry of a pose (contact.cpp)
  Vec3 world_vertex(const Quat& q, int k) const {
    return support_.world + q * (run_.particle.hull.vertices[static_cast<std::size_t>(k)] - support_.body);
  }
  Pose pose_at(const Quat& q) const { return {q, com_position(support_, q)}; }
  void heights(const Quat& qq, std::vector<double>& out) const;

  // ---- events of a step (contact_paper_step.cpp, contact_adaptive_step.cpp)
  // Whether vertex k, now at height zk, has (since the start of the step) passed below the wall, or entered
  // (left) the ε band. Below-the-wall is measured from where the vertex started.
  double pierce_level(std::size_t k) const {
    return std::max(std::min(z_[k], 0.0), -tol::kPierceFloor * run_.tol.event) - run_.tol.event;
  }
  // Entering and leaving the ε band count as events (they change the contact set) until the stability test
  // has passed. The adaptive integrator then takes the crossings into its contact decisions instead.
  bool band_events() const { return run_.surface.has_band_events() && !finishing_; }
  bool pierces(std::size_t k, double zk) const { return zk < pierce_level(k); }
  bool enters_band(std::size_t k, double zk) const {
    return band_events() && !in_contact_[k] && zk <= run_.tol.band;
  }
  // The adaptive integrator's events upward: a contact leaving the ε band, a touching point lifting off (the
  // paper's support rules follow the touching set). Adaptive steps only.
  double rise_level(std::size_t k) const {
    if (run_.surface.has_contact_types() && in_contact_[k] == kTouchingPoint) return run_.tol.touch;
    return band_events() && in_contact_[k] ? run_.tol.band + run_.tol.touch : INFINITY;
  }
  // The lowest height vertex k may reach in a step without an event.
  double event_level(std::size_t k) const {
    return band_events() && !in_contact_[k] ? run_.tol.band : pierce_level(k);
  }
  struct EventFlags {
    bool any = false, pierced = false, entered = false;
  };
  EventFlags paper_event_at(const Quat& qq) const;
  EventFlags adaptive_event_at(const Quat& qq, const StepVertices& v) const;
  double event_margin(const Quat& qq, const StepVertices& v) const;
  void select_event_vertices(const StepVertices& from, const Quat& q_lo, double turn, StepVertices& out);

  // ---- the steppers: one is chosen from SettleParams::integrator when the phase is built (stepper_)
  // The paper's fixed step (Eqs 10-16): every event bracketed by halving; after a step every vertex's
  // height is known (z_), and the vertex sets are found by scans.
  struct PaperStepper {};
  // The adaptive Dormand–Prince step: events located on its dense output, the vertex sets found by walks over
  // the hull. It owns its integrator and where its stepping stands.
  struct AdaptiveStepper {
    AdaptiveStepper(const Body& body, double length, double tolerance, double max_step)
        : integrator(body, length, tolerance, max_step) {}
    RotationIntegrator integrator;
    // What the next call does: start the integrator afresh (the support or the motion changed), take a new
    // integrator step, resume the last one after an event that changed no support, or go on inside the
    // current one (stopped in it by advance_to()).
    enum class Next { restart, new_step, resume, inside } next = Next::restart;
    // What ends the current step: the integrator's step, an event, or an event at which a point entered the
    // ε band (which lets the update choose a new support, contact_support.cpp).
    enum class End { step, event, band_entry } ends = End::step;
    // The current step ends where a vertex crosses the ε band (entering or leaving it, no other event), and
    // `before` holds the contact decisions in force up to there (quiet_crossing).
    bool crossing = false;
    Decision before;
    // After a quiet crossing the next search reuses the step's candidates (a superset of those a walk from
    // the crossing would find: the particle turns by less in the rest of the step than in all of it).
    bool keep_candidates = false;
    double end = 0;           // the current step's first event, or its end
    double restart_step = 0;  // the first trial step of a restart (0: from rest, a short one)
    double min_moment = 1;    // the smallest moment of inertia about the current support (arc_bound)
    // The contact decisions at the last step's end when they are known (it ended without an event); kept for
    // the next step's start while the update changes nothing they depend on.
    std::optional<Decision> decision;
  };
  void paper_step();
  void adaptive_step(AdaptiveStepper& step);
  void begin_adaptive_step(AdaptiveStepper& step);
  double locate_step_event(AdaptiveStepper& step, double lo, double hi, const EventFlags& at_hi);
  // The support or the motion changed: the adaptive integrator starts afresh (from rest: with its short first
  // trial step).
  void restart_motion(bool from_rest);
  double smallest_moment() const;
  std::array<double, 2> rate_coefficients() const;
  double rate_bound(double h) const;

  // ---- decisions (contact_decisions.cpp)
  bool contact_set_holds(double arc) const;
  void locate_decision_change(AdaptiveStepper& step, double t0, double t_end, std::span<const double> inner);
  double stability_margin_at(const Quat& qq);
  double brief_stability_pass(const AdaptiveStepper& step, double t0, double t1);

  // ---- the update after a step (contact_update.cpp)
  // Where the update finds the band: by a walk, or among the step's event candidates (which hold every
  // vertex that can be in the band until the step's end, about the same support).
  enum class BandSource { walk, step_candidates };
  // What the update did: kept the support, switched to another (or tipped off an edge balance: the motion
  // restarts), or found the rest (rest_ holds where).
  enum class Outcome { same_support, new_support, rest };
  Outcome update(const Vec3& omega, const Vec3& com_velocity, bool heights_known = false,
                 BandSource band_source = BandSource::walk);
  void quiet_update();
  bool quiet_crossing(AdaptiveStepper& step);
  void trace_update() const;
  double stability_margin(const std::vector<Vec3>& points, const Vec2& g) const;
  void note_penetration();

  // ---- supports (contact_support.cpp)
  bool choose_support(const LineFit& fit, const Vec2& g, const Vec3& omega, const Vec3& com_velocity);
  void set_support(const Support& next, int vertex);
  struct LineSupport {
    bool holds = false;
    double reach = 0;  // the angle (rad) about the line before `holds` can change
  };
  LineSupport line_support(const Pose& pose, std::span<const int> set, const std::vector<Vec3>& points, int o,
                           const Vec3& axis) const;
  void remember_axis(const Vec3& omega);
  std::vector<Vec2> touching_polygon(const Quat& q) const;
  bool touching_points_hold(const Vec2& g) const;
  bool tip_off_edge_balance(const Vec2& g);

  // ---- vertex walks (contact_walks.cpp)
  void vertices_below(const Quat& qq, double level, std::vector<int>& out, bool sorted);
  void vertices_below_among(const Quat& qq, double level, std::span<const int> among, std::vector<int>& out);
  bool band_matches_walk(double level, const std::vector<int>& picked);
  bool candidates_cover(const Quat& qq, double level);
  double lowest_height();

  Run& run_;
  std::optional<RestPose> rest_;  // set by the update that finds the rest (the phase's end)
  // The support and the motion about it.
  Support support_;
  int support_vertex_ = -1;
  Rotation rot_;
  double reach_radius_ = 0;        // largest distance of a hull vertex from the current support
  bool finishing_ = false;         // the paper's stability test has passed (at record.stable_time)
  bool band_entered_ = true;       // a point entered the ε band in the last step (or contact just began)
  std::optional<Vec3> prev_axis_;  // the last rotation axis (a surface contact turns about it), once known
  std::variant<PaperStepper, AdaptiveStepper> stepper_;
  // The vertex sets. `z_` holds heights of the vertices of the last walk or scan only (the contact set, the
  // last step's candidates; every vertex with the paper's integrator).
  static constexpr char kTouchingPoint = 2;
  std::vector<double> z_;
  std::vector<int> contact_;      // hull vertices within ε (the contact set)
  std::vector<int> touching_;     // hull vertices on the wall
  std::vector<char> in_contact_;  // per hull vertex: 0, or in the contact set (1), or touching the wall (2)
  std::vector<int> event_candidates_;  // vertices that may cause an event within the step
  // Scratch, kept to avoid allocating per step.
  std::vector<Vec3> contact_points_, footprints_;
  std::vector<WallVertex> touches_;
  std::vector<double> next_z_;
  std::vector<int> next_contact_, decision_contact_, decision_touching_, decision_set_;
  std::vector<std::pair<double, double>> margin_samples_;  // brief_stability_pass's margins by time
  // The step's reachable vertices packed for the event tests made at every instant of its event search
  // (step_vertices.hpp).
  StepVertices step_vertices_;
  // Of those, the ones that can decide the search of an event's bracket, and of the narrower brackets of the
  // root finder, alternately (select_event_vertices).
  StepVertices bracket_vertices_;
  std::array<StepVertices, 2> narrow_vertices_;
  std::vector<double> margin_scratch_;  // select_event_vertices' lower bounds of the margins
  NearWall walks_;                      // the walks of the vertex sets near the wall (contact_walks.cpp)
};

}  // namespace repose::sim
