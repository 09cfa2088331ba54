// Internal: the settling engine's per-run state (Settler::Impl) and its methods, defined by concept:
//   settle.cpp          construction, step(), advance_to(), samples and results, the public API
//   fall.cpp            flights (the centre of mass's parabola, torque-free rotation) and their touch
//   touch.cpp           what a touch does: the paper's (translation stops) or rigid impacts, rebound or not
//   paper_step.cpp      the paper's fixed step with bisection of events
//   adaptive_step.cpp   the adaptive integrator's steps, its events on the dense output, vertex walks
//   decisions.cpp       the contact decisions at any instant of a step, and where they change
//   contact_update.cpp  the contact set, Algorithm 1, the paper's stability test, the support's choice
//   rest.cpp            static equilibrium on touching points, the flush rest, edge balances
// The Particle is shared read-only; an Impl is one run's state (MuJoCo's mjModel / mjData split).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "contact.hpp"
#include "dynamics.hpp"
#include "impact_support.hpp"
#include "repose/sim/settle.hpp"
#include "rigid_impact.hpp"
#include "rotation_integrator.hpp"
#include "stability.hpp"

namespace repose {

struct Settler::Impl {
  static constexpr int kBisections = 48;  // locates an event to 2^-48 of a step: far below 1e-9·L of motion
  // An edge balance (no motion, the centre of mass over the edge within 1e-9·L) is an unstable equilibrium,
  // not a rest: the particle is turned about the edge until its centre of mass is this far (× L) beyond it
  // and falls from there. Ten times the touching tolerance, so round-off never puts it back on the balance;
  // the fall from an offset δ takes about ln(d/δ)/λ (d: centre of mass to edge, λ: the inverted pendulum's
  // rate).
  static constexpr double kBalanceOffset = 1e-8;
  // The adaptive integrator's automatic longest step (× sqrt(L/g)): contact decisions (line support, the
  // paper's stability test, the balance check) are re-evaluated at the end of every step.
  static constexpr double kAdaptiveMaxStep = 0.2;
  // The adaptive integrator's first trial step from rest (× sqrt(L/g)).
  static constexpr double kFirstStep = 0.05;
  // The adaptive integrator's time scale for the impact rule's rebound test (× sqrt(L/g)), in place of a
  // step.
  static constexpr double kReboundWindow = 0.05;
  // The adaptive step is searched for events at this many evenly spaced instants of its dense output, so a
  // vertex that dips below the wall and back up inside one step is still caught.
  static constexpr int kEventSamples = 8;
  // Contact decisions are also checked at every kDecisionStride-th of those instants inside a step.
  static constexpr std::size_t kDecisionStride = 2;
  // The search for a brief pass of the stability test within a step evaluates its margin at most this many
  // times (a bound that only a tangency within ~1e-9 of the margin's scale could reach).
  static constexpr int kStabilityEvaluations = 4096;
  // A support chosen from several touching points is chosen again at once, at most this many times.
  static constexpr int kRedecisions = 2;

  const Particle& particle;
  SettleParams params;
  sim::Body body;
  double length = 0;         // L
  double band = 0;           // ε (length)
  double touch_tol = 0;      // a vertex this close to the wall is touching it
  double event_tol = 0;      // a vertex this far below the wall triggers a touch event
  double rss_threshold = 0;  // Algorithm 1 line/surface threshold (length²)
  double dt = 0;
  double rebound_window = 0;  // the impact rule's step (impact_support.hpp): dt, or 0.05·τ (adaptive)
  double max_time = 0;
  bool smooth = false;
  bool adaptive = false;  // Integrator::adaptive
  std::optional<sim::RotationIntegrator> integrator;
  double hull_radius = 0;   // largest distance of a hull vertex from the centre of mass
  double reach_radius = 0;  // largest distance of a hull vertex from the current support
  double min_moment = 1;    // adaptive: the smallest moment of inertia about the current support

  // Per-run state.
  double t = 0;
  double limit = INFINITY;  // advance_to(): no step goes past this time
  long steps = 0;
  Status status = Status::running;
  bool falling = false;               // off the wall: the first descent or a flight (fall.cpp)
  Vec3 fall_origin = Vec3::Zero();    // the centre of mass at the flight's start
  Vec3 fall_velocity = Vec3::Zero();  // its velocity then
  double fall_t0 = 0;                 // the flight's start
  double touch_time = 0;              // when a flight without rotation reaches the wall (closed form)
  long fall_steps = 0;                // grid steps of that flight taken (it steps to multiples of dt)
  double lowest_body_height = 0;      // min over hull vertices of (R p).z, constant while not rotating
  // A flight with rotation: torque-free, integrated about the centre of mass (damping 0), its touch located
  // on the dense output of each step (fall.cpp).
  bool spinning = false;
  sim::Body free_body;  // the body without damping (off the wall); the integrator keeps a pointer to it
  std::optional<sim::RotationIntegrator> flight_rotation;
  Vec3 flight_omega = Vec3::Zero();
  double flight_step_end = -INFINITY;  // the end of the current integrator step
  double flight_touch = INFINITY;      // the touch located in it, if any
  double flight_inertia_min = 0;  // the body's smallest principal moment (locate_touch's bound; 0: unset)
  // locate_touch's working memory, kept from search to search (a fresh allocation per sample made the heap
  // grow and shrink by megabytes a drop): the intervals to examine and a few cached samples.
  static constexpr std::size_t kTouchCached = 4;
  std::vector<std::pair<double, double>> touch_stack;
  std::vector<std::size_t> touch_candidates;  // the hull vertices that may reach the wall in the step
  std::vector<double> touch_samples;  // kTouchCached slots of 2·(candidates): heights, then vertical speeds
  std::array<double, kTouchCached> touch_sample_time{};
  bool rigid_impacts = false;  // uses_impacts(params): touches while airborne are impacts
  sim::ImpactLaw impact_law;
  std::vector<ImpactRecord> impacts;
  int bounces = 0;
  Quat q = Quat::Identity();
  Vec3 com = Vec3::Zero();
  sim::Support support;
  sim::Rotation rot;
  int support_vertex = -1;
  bool restart = true;      // adaptive: the support or the motion changed, so the integrator starts afresh
  bool in_step = false;     // adaptive: inside an integrator step (stopped in it by advance_to())
  bool resume = false;      // adaptive: the next step resumes the integrator's last one (after an event)
  double restart_step = 0;  // adaptive: the first trial step of a restart (0: from rest, a short one)
  double step_start = 0, step_end = 0;  // adaptive: the current step: its start, its first event or end
  bool step_event = false, step_band_entered = false;
  bool finishing = false;  // the paper's stability test has passed (at stable_time)
  double stable_time = -1;
  bool trace = std::getenv("REPOSE_TRACE") != nullptr;  // debugging aid: one line per step on stderr
  bool band_entered = true;  // a point entered the ε band in the last step (or contact just began)
  bool has_prev_axis = false;
  Vec3 prev_axis = Vec3::UnitX();
  ContactType type = ContactType::free_fall;
  std::vector<double> z;            // world heights of the hull vertices
  std::vector<int> contact;         // hull vertices within ε
  std::vector<int> touching;        // hull vertices on the wall
  std::vector<sim::Touch> touches;  // scratch, the touching vertices for the impact rule
  std::vector<Vec3>
      contact_points;  // scratch, world coordinates of `contact` (kept to avoid allocating per step)
  std::vector<Vec3> footprints;       // scratch, their projections on the wall
  std::vector<double> next_z;         // scratch, heights at the end of a trial step
  std::vector<int> event_candidates;  // scratch, vertices that may cause an event within a step
  std::vector<char> in_contact;  // per hull vertex: 0, or in the contact set (1), or touching the wall (2)
  static constexpr char kTouchingPoint = 2;
  // Adaptive integrator: vertex sets come from walks over the hull's edge graph (ConvexHull::neighbors), so
  // a step costs about the vertices near the wall, not the hull's size; `z` is then valid only for the
  // vertices of the last walk (the contact set, the last step's candidates).
  std::vector<char> walk_visited;  // scratch of hull size, all zero between uses
  std::vector<int> walk_out;       // scratch: a walk's vertices, then a step's reachable vertices
  std::vector<std::uint64_t>
      id_bits;  // scratch of hull size in bits, all zero between uses (sort_vertex_ids)
  // Set for the contact update that ends an adaptive step: the step's event candidates hold every vertex
  // that can be in the band until the step's end, about the same support; the update picks its band there.
  bool band_in_candidates = false;
  int lowest_vertex = 0;  // the lowest hull vertex at the last walk (its start)
  std::vector<Phase> phases;
  double max_penetration = 0;
  double energy_start = 0;
  long unconverged = 0;
  RestKind rest = RestKind::none;
  int rest_face = -1;
  std::vector<Vec3> rest_points;

  // ---- life cycle and output (settle.cpp)
  Impl(const Particle& p, const SettleParams& prm, const Quat& orientation);
  bool step();
  bool advance_to(double time);
  Sample sample() const;
  SettleResult result() const;
  double potential_energy() const { return body.mass * params.gravity * com.z(); }
  double kinetic_energy() const;

  // ---- geometry of the pose
  Vec3 world_vertex(int k) const { return support.world + q * (particle.hull.vertices[k] - support.body); }
  void heights(const Quat& qq, std::vector<double>& out) const;  // every hull vertex (contact_update.cpp)
  void vertices_below(const Quat& qq, double level, std::vector<int>& out, bool sorted);  // adaptive_step.cpp
  void vertices_below_among(const Quat& qq, double level, const std::vector<int>& among,
                            std::vector<int>& out);                      // adaptive_step.cpp
  void sort_vertex_ids(std::vector<int>& ids);                           // adaptive_step.cpp
  bool band_matches_walk(double level, const std::vector<int>& picked);  // adaptive_step.cpp (debug check)
  double lowest_height();                                                // adaptive_step.cpp
  double smallest_moment() const;                                        // adaptive_step.cpp
  std::array<double, 2> rate_coefficients() const;  // |ω|² ≤ a + b·θ after turning by θ   adaptive_step.cpp
  double arc_bound(double h) const;                 // adaptive_step.cpp
  double rate_bound(double h) const;                // adaptive_step.cpp

  // ---- flights (fall.cpp) and touches (touch.cpp)
  Vec3 flight_velocity() const;  // the centre of mass's velocity at t
  void begin_flight(const Vec3& velocity, const Vec3& omega, double height);
  void fall_step();
  void spin_step();
  double locate_touch(double a, double b);
  void touch(const Vec3& velocity, const Vec3& omega);
  void begin_contact(const Vec3& com_velocity, const Vec3& omega = Vec3::Zero(), bool carry = false);

  // ---- rotation steps and their events (paper_step.cpp, adaptive_step.cpp)
  // Whether vertex k, now at height zk, has (since the start of the step) passed below the wall, or entered
  // (left) the ε band. Below-the-wall is measured from where the vertex started, so a vertex that already
  // touches within round-off does not re-trigger at once.
  double pierce_level(std::size_t k) const {
    return std::max(std::min(z[k], 0.0), -100 * event_tol) - event_tol;
  }
  // Entering and leaving the ε band count as events (they change the contact set) until the stability test
  // has passed. The contact set still decides the type and a line's support while the particle turns onto
  // its face: the adaptive integrator then takes the crossings into its contact decisions instead
  // (decision_at), so that they are located where they change a decision.
  bool band_events() const { return !smooth && !finishing; }
  bool band_crossings_in_decisions() const { return adaptive && !smooth && finishing; }
  // The height above the wall of hull vertex k at the orientation whose rotation matrix has third row r3,
  // about the current support (the one expression every height test uses, so that they agree to the bit).
  double height_of(const Vec3& r3, int k) const {
    return support.world.z() + r3.dot(particle.hull.vertices[static_cast<std::size_t>(k)] - support.body);
  }
  bool pierces(std::size_t k, double zk) const { return zk < pierce_level(k); }
  bool enters_band(std::size_t k, double zk) const { return band_events() && !in_contact[k] && zk <= band; }
  // The adaptive integrator's events upward: a contact leaving the ε band, a touching point lifting off the
  // wall (either changes the sets the contact decisions are taken on).
  double rise_level(std::size_t k) const {
    if (adaptive && !smooth && in_contact[k] == kTouchingPoint) return touch_tol;
    return band_events() && in_contact[k] ? band + touch_tol : INFINITY;
  }
  bool rises(std::size_t k, double zk) const { return zk > rise_level(k); }
  // The lowest height vertex k may reach in a step without an event: the band for a vertex outside it, the
  // pierce level otherwise.
  double event_level(std::size_t k) const { return band_events() && !in_contact[k] ? band : pierce_level(k); }
  bool event_at(const Quat& qq, const std::vector<int>& candidates, bool& pierced) const;
  void rotate();
  void rotate_adaptive();
  void begin_adaptive_step();
  bool adaptive_event_at(const Quat& qq, const std::vector<int>& candidates, bool& pierced,
                         bool& entered) const;
  double event_margin(const Quat& qq, const std::vector<int>& candidates) const;
  std::pair<double, double> locate_event(double lo, double hi, bool& pierced, bool& entered);
  struct Decision {
    ContactType type = ContactType::point;
    bool hold = false, stable = false, line_holds = false;
    // With decision_at(…, true), for each of the four above in turn: the angle (rad) the particle can turn
    // about its support before it can change, for the contact set it was taken on (0: unknown). Not part of
    // the decision.
    std::array<double, 4> reach_of{};
    double reach() const { return std::min({reach_of[0], reach_of[1], reach_of[2], reach_of[3]}); }
    bool operator==(const Decision& o) const {
      return type == o.type && hold == o.hold && stable == o.stable && line_holds == o.line_holds;
    }
  };
  // A margin within this much (× L) of its threshold gives no reach: the 2-D hull's tolerances and round-off
  // act there.
  static constexpr double kReachSlack = 1e-6;
  Decision decision_at(const Quat& qq, bool with_reach = false);  // decisions.cpp, as the four below
  bool contact_set_holds(double arc) const;
  Decision cached_decision;         // the decisions at the current step's start, if decision_cached
  bool decision_cached = false;     // (set when the last update changed nothing they depend on)
  bool end_decision_known = false;  // the last step ended without an event, its end decisions known
  std::vector<int> decision_contact, decision_touching;  // scratch: the sets before an update
  std::vector<int> decision_set;                         // scratch: the contact set at a decision's pose
  void locate_decision_change(double t0, double t_end, std::span<const double> inner);
  double stability_margin_at(const Quat& qq);
  double brief_stability_pass(double t0, double t1);
  struct StabilityInterval {
    double a, b, ma, mb;  // an interval of time and the margins at its ends
  };
  std::vector<StabilityInterval> stability_intervals;  // scratch of brief_stability_pass

  // ---- contacts, stability and supports (contact_update.cpp)
  void update_contacts(const Vec3& omega, const Vec3& com_velocity, bool heights_known = false);
  std::vector<int> next_contact;  // scratch of update_contacts: the new contact set, swapped in
  void quiet_update();
  void trace_update() const;
  void set_type(ContactType new_type);
  double stability_margin(const std::vector<Vec3>& contact_points, const Vec2& g) const;
  void choose_support(const sim::LineFit& fit, const Vec2& g, const Vec3& omega, const Vec3& com_velocity);
  struct LineSupport {
    bool holds = false;
    double reach = 0;  // the angle (rad) about the line before `holds` can change (decisions.cpp)
  };
  LineSupport line_support(int o, const Vec3& axis) const;  // on contact_points, filled for `contact`
  void note_penetration();
  void remember_axis(const Vec3& omega);
  int nearest_touching(const Vec2& p) const;

  // ---- static equilibrium and rest (rest.cpp)
  std::vector<Vec2> touching_polygon() const;
  bool touching_points_hold(const Vec2& g) const;
  void tip_off_edge_balance(const Vec2& g);
  bool come_to_rest();
};

}  // namespace repose
