// The settling stepper: free fall, contact detection, rotation phases, stability and rest (paper §2.1-2.4).
//
// Two sets of points drive the method, both over the convex hull's vertices (only they can touch a flat
// wall):
//   - the contact set (the paper's): vertices within ε of the wall; it gives the contact type (Algorithm 1),
//     the best-fit rotation axis, and the stability tests of §2.4;
//   - the touching set: vertices on the wall (within 1e-9·L). The rotation always keeps its support point on
//     the wall, and no vertex may pass below it: every new touch is located inside the step by bisection.
// When the paper's stability test fires, the run finishes the rotation on touching points alone until they
// hold the centre of mass, then sets the supporting hull face exactly flush: the rest is a true equilibrium.
#include "repose/sim/settle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <optional>

#include "contact.hpp"
#include "dynamics.hpp"
#include "impact_support.hpp"
#include "repose/error.hpp"
#include "rotation_integrator.hpp"
#include "stability.hpp"

namespace repose {

const char* to_string(ContactType type) {
  switch (type) {
    case ContactType::free_fall:
      return "free-fall";
    case ContactType::point:
      return "point";
    case ContactType::line:
      return "line";
    case ContactType::surface:
      return "surface";
  }
  return "?";
}

const char* to_string(Status status) {
  switch (status) {
    case Status::running:
      return "running";
    case Status::rest:
      return "rest";
    case Status::max_time:
      return "max-time";
    case Status::max_steps:
      return "max-steps";
  }
  return "?";
}

const char* to_string(RestKind kind) {
  switch (kind) {
    case RestKind::none:
      return "none";
    case RestKind::surface:
      return "surface";
    case RestKind::points:
      return "points";
    case RestKind::smooth:
      return "smooth";
  }
  return "?";
}

double default_sample_dt(const Particle& particle, const SettleParams& params) {
  if (params.integrator == Integrator::paper) return 0;
  return 1e-3 * std::sqrt(particle.length / params.gravity);
}

bool is_smooth_surface(const Particle& particle) {
  return particle.convex_surface && particle.max_dihedral_angle < std::numbers::pi / 6;
}

namespace {
constexpr int kBisections = 48;  // locates an event to 2^-48 of a step: far below 1e-9·L of motion
constexpr int kStallLimit = 20;  // after this many near-empty steps, contact choices stop second-guessing
// An edge balance (no motion, the centre of mass over the edge within 1e-9·L) is an unstable equilibrium,
// not a rest: the particle is turned about the edge until its centre of mass is this far (× L) beyond it and
// falls from there. Ten times the touching tolerance, so round-off never puts it back on the balance; the
// fall from an offset δ takes about ln(d/δ)/λ (d: centre of mass to edge, λ: the inverted pendulum's rate).
constexpr double kBalanceOffset = 1e-8;
// The adaptive integrator's automatic longest step (× sqrt(L/g)): contact decisions (line support, the
// paper's stability test, the balance check) are re-evaluated at the end of every step.
constexpr double kAdaptiveMaxStep = 0.05;
// The adaptive step is searched for events at this many evenly spaced instants of its dense output, so a
// vertex that dips below the wall and back up inside one step is still caught.
constexpr int kEventSamples = 8;
}  // namespace

struct Settler::Impl {
  const Particle& particle;
  SettleParams params;
  sim::Body body;
  double length = 0;         // L
  double band = 0;           // ε (length)
  double touch_tol = 0;      // a vertex this close to the wall is touching it
  double event_tol = 0;      // a vertex this far below the wall triggers a touch event
  double rss_threshold = 0;  // Algorithm 1 line/surface threshold (length²)
  double dt = 0;
  double max_time = 0;
  bool smooth = false;
  bool adaptive = false;  // Integrator::adaptive
  std::optional<sim::RotationIntegrator> integrator;
  double hull_radius = 0;   // largest distance of a hull vertex from the centre of mass
  double reach_radius = 0;  // largest distance of a hull vertex from the current support

  // Per-run state.
  double t = 0;
  double limit = INFINITY;  // advance_to(): no step goes past this time
  long steps = 0;
  Status status = Status::running;
  bool falling = false;
  double fall_speed = 0;          // downward
  double touch_time = 0;          // when the falling particle reaches the wall
  long fall_steps = 0;            // grid steps of the fall taken (it steps to multiples of dt)
  double lowest_body_height = 0;  // min over hull vertices of (R p).z, constant while falling
  Quat q = Quat::Identity();
  Vec3 com = Vec3::Zero();
  sim::Support support;
  sim::Rotation rot;
  int support_vertex = -1;
  bool restart = true;   // adaptive: the support or the motion changed, so the integrator starts afresh
  bool in_step = false;  // adaptive: inside an integrator step (stopped in it by advance_to())
  double step_start = 0, step_end = 0;  // adaptive: the current step: its start, its first event or end
  bool step_event = false, step_band_entered = false;
  bool finishing = false;
  bool trace = std::getenv("REPOSE_TRACE") != nullptr;  // debugging aid: one line per step on stderr
  bool band_entered = true;  // a point entered the ε band in the last step (or contact just began)
  int stalled_steps = 0;     // consecutive steps an event cut to (almost) nothing
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
  std::vector<char> in_contact;
  // Adaptive integrator: vertex sets come from walks over the hull's edge graph (ConvexHull::neighbors), so
  // a step costs about the vertices near the wall, not the hull's size; `z` is then valid only for the
  // vertices of the last walk (the contact set, the last step's candidates).
  std::vector<char> walk_visited, walk_member;  // scratch of hull size, all zero between uses
  std::vector<int> walk_out, walk_union;        // scratch
  int lowest_vertex = 0;                        // the lowest hull vertex at the last walk (its start)
  std::vector<std::vector<int>>
      first_vertex_faces;  // per hull vertex: the hull faces whose loop starts there
  std::vector<Phase> phases;
  double max_penetration = 0;
  double energy_start = 0;
  long unconverged = 0;
  RestKind rest = RestKind::none;
  int rest_face = -1;
  std::vector<Vec3> rest_points;

  Impl(const Particle& p, const SettleParams& prm, const Quat& orientation) : particle(p), params(prm) {
    validate(params);
    if (!std::isfinite(orientation.norm()) || orientation.norm() < 1e-12)
      throw Error("orientation must be a finite non-zero quaternion");
    body = {p.mass.mass, p.mass.inertia, params.gravity, params.damping};
    length = p.length;
    band = params.contact_threshold * length;
    touch_tol = 1e-9 * length;
    event_tol = 1e-12 * length;
    rss_threshold = params.line_threshold * length * length;
    const double time_scale = std::sqrt(length / params.gravity);
    adaptive = params.integrator == Integrator::adaptive;
    dt = params.dt > 0 ? params.dt : (adaptive ? kAdaptiveMaxStep : 1e-3) * time_scale;
    if (adaptive) integrator.emplace(body, length, params.tolerance, dt);
    const double fall_time =
        (std::sqrt(params.drop_speed * params.drop_speed + 2 * params.gravity * params.drop_height)) /
        params.gravity;
    max_time = params.max_time > 0 ? params.max_time : 2000 * time_scale + fall_time;
    smooth =
        params.smooth == SmoothMode::on || (params.smooth == SmoothMode::automatic && is_smooth_surface(p));

    q = orientation.normalized();
    const std::size_t n = p.hull.vertices.size();
    for (const Vec3& v : p.hull.vertices) hull_radius = std::max(hull_radius, v.norm());
    z.resize(n);
    in_contact.resize(n);
    walk_visited.resize(n);
    walk_member.resize(n);
    first_vertex_faces.resize(n);
    for (std::size_t f = 0; f < p.hull.faces.size(); ++f)
      first_vertex_faces[p.hull.faces[f].loop.front()].push_back(static_cast<int>(f));
    lowest_body_height = INFINITY;
    for (const Vec3& v : p.hull.vertices) lowest_body_height = std::min(lowest_body_height, (q * v).z());
    com = Vec3(0, 0, params.drop_height - lowest_body_height);
    energy_start = 0.5 * body.mass * params.drop_speed * params.drop_speed + potential_energy();
    if (params.drop_height > 0) {
      falling = true;
      fall_speed = params.drop_speed;
      touch_time =
          (-fall_speed + std::sqrt(fall_speed * fall_speed + 2 * params.gravity * params.drop_height)) /
          params.gravity;
      phases.push_back({ContactType::free_fall, 0, 0});
    } else {
      begin_contact(Vec3(0, 0, -params.drop_speed));
    }
  }

  double potential_energy() const { return body.mass * params.gravity * com.z(); }

  double kinetic_energy() const {
    if (falling) return 0.5 * body.mass * fall_speed * fall_speed;
    if (status == Status::rest) return 0;
    return sim::rotational_energy(body, support, rot.q, rot.omega);
  }

  Vec3 world_vertex(int k) const { return support.world + q * (particle.hull.vertices[k] - support.body); }

  // Heights of all hull vertices for orientation `qq` about the current support (only the third row of R).
  void heights(const Quat& qq, std::vector<double>& out) const {
    const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
    const auto& verts = particle.hull.vertices;
    for (std::size_t k = 0; k < verts.size(); ++k)
      out[k] = support.world.z() + r3.dot(verts[k] - support.body);
  }

  // The hull vertices at most `level` above the wall at orientation `qq` about the current support, appended
  // to `out` (in index order if `sorted`: the order of a contact list matters to its fit's round-off and
  // to ties): a walk from the lowest vertex over the hull's edge graph (a linear function's sublevel sets on a
  // convex polytope are connected), so the cost is the set and its border. The walk runs 1e-12·L beyond
  // `level` and the exact test (the same arithmetic as heights()) picks the members.
  void vertices_below(const Quat& qq, double level, std::vector<int>& out, bool sorted) {
    const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
    const Vec3 down = -r3;
    lowest_vertex = particle.hull.support_vertex_from(down, lowest_vertex);
    const double base = support.world.z() - r3.dot(support.body);  // height = base + r3·p
    walk_out.clear();
    particle.hull.vertices_at_least(down, -(level + event_tol - base), lowest_vertex, walk_out, walk_visited);
    const std::size_t first = out.size();
    for (int k : walk_out)
      if (support.world.z() + r3.dot(particle.hull.vertices[k] - support.body) <= level) out.push_back(k);
    if (sorted) std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
  }

  // The height of the lowest hull vertex at orientation q (a walk downhill from the last lowest vertex).
  double lowest_height() {
    const Vec3 r3 = q.toRotationMatrix().row(2).transpose();
    lowest_vertex = particle.hull.support_vertex_from(-r3, lowest_vertex);
    return support.world.z() + r3.dot(particle.hull.vertices[lowest_vertex] - support.body);
  }

  // ---- free fall
  // -------------------------------------------------------------------------------------------

  // The fall is exact: the closed form from its start, z(t) = z0 − v0·t − ½·g·t², to the touch time
  // (−v0 + sqrt(v0² + 2·g·h))/g. Steps end on the grid of multiples of dt (observers see the fall there); a
  // stop at the time limit or at advance_to() is not a step, so where a run is stopped never changes it.
  void fall_step() {
    const double g = params.gravity, v0 = params.drop_speed;
    const double grid = static_cast<double>(fall_steps + 1) * dt;
    const double end = std::min({grid, touch_time, max_time, limit});
    t = end;
    if (end == touch_time) {
      ++steps;
      com.z() = -lowest_body_height;  // exactly touching
      fall_speed = v0 + g * touch_time;
      begin_contact(Vec3(0, 0, -fall_speed));
      return;
    }
    if (end == grid) {
      ++fall_steps;
      ++steps;
    }
    com.z() = params.drop_height - lowest_body_height - (v0 * t + 0.5 * g * t * t);
    fall_speed = v0 + g * t;
  }

  // First touch (or the start of a run at drop height 0): translation stops and the particle pivots about its
  // lowest point; the impact conserves angular momentum about the new support.
  void begin_contact(const Vec3& com_velocity) {
    falling = false;
    int lowest = 0;
    for (std::size_t k = 0; k < particle.hull.vertices.size(); ++k)
      if ((q * particle.hull.vertices[k]).z() < (q * particle.hull.vertices[lowest]).z())
        lowest = static_cast<int>(k);
    const Vec3 p = particle.hull.vertices[lowest];
    support = {Vec3(com.x() + (q * p).x(), com.y() + (q * p).y(), 0.0), p, false, Vec3::UnitX()};
    support_vertex = lowest;
    reach_radius = hull_radius + support.body.norm();
    com = sim::com_position(support, q);
    rot = {q, Vec3::Zero(), Vec3::Zero()};
    restart = true;
    update_contacts(Vec3::Zero(), com_velocity);
  }

  // ---- rotation
  // --------------------------------------------------------------------------------------------

  // Whether vertex k, now at height zk, has (since the start of the step) passed below the wall, or entered
  // the ε band. Below-the-wall is measured from where the vertex started, so a vertex that already touches
  // within round-off does not re-trigger at once.
  bool pierces(std::size_t k, double zk) const {
    return zk < std::max(std::min(z[k], 0.0), -100 * event_tol) - event_tol;
  }
  bool enters_band(std::size_t k, double zk) const {
    return !smooth && !finishing && !in_contact[k] && zk <= band;
  }

  // Heights of the listed vertices after a rotation to `qq`; true if any of them pierced or entered the band.
  bool event_at(const Quat& qq, const std::vector<int>& candidates, bool& pierced) const {
    const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
    bool event = false;
    pierced = false;
    for (int k : candidates) {
      const double zk = support.world.z() + r3.dot(particle.hull.vertices[k] - support.body);
      pierced = pierced || pierces(k, zk);
      event = event || pierced || enters_band(k, zk);
    }
    return event;
  }

  void rotate() {
    if (adaptive) {
      rotate_adaptive();
      return;
    }
    sim::Rotation next;
    // The last step is shortened so a run never passes its time limit.
    const double h = std::min({dt, max_time - t, limit - t});
    int iterations =
        sim::rotate_step(body, support, rot, h, params.quaternion_tolerance, params.max_iterations, next);
    double taken = h;

    // Eq 2's idea, the bounding test that gates the exact distance query: a vertex can only cause an event
    // inside this step if it ends it, or starts it, within the arc length the step can sweep of the levels.
    std::vector<double>& zz = next_z;
    zz.resize(z.size());
    heights(next.q, zz);
    const double swept = 2 * std::acos(std::min(1.0, std::abs(rot.q.dot(next.q)))) * reach_radius;
    const double level = smooth ? 0.0 : band;
    std::vector<int>& candidates = event_candidates;
    candidates.clear();
    bool event = false;
    for (std::size_t k = 0; k < zz.size(); ++k) {
      if (std::min(z[k], zz[k]) <= level + swept + event_tol) candidates.push_back(static_cast<int>(k));
      event = event || pierces(k, zz[k]) || enters_band(k, zz[k]);
    }

    band_entered = false;
    if (event) {
      // Bisect for the earliest instant at which an event holds (to 2^-48 of the step).
      double lo = 0, hi = h;
      sim::Rotation lo_state = rot, hi_state = next;
      int lo_iterations = 0;
      bool hi_pierced = true, pierced = false;
      event_at(next.q, candidates, hi_pierced);
      for (int i = 0; i < kBisections; ++i) {
        const double mid = 0.5 * (lo + hi);
        sim::Rotation trial;
        const int it = sim::rotate_step(body, support, rot, mid, params.quaternion_tolerance,
                                        params.max_iterations, trial);
        if (event_at(trial.q, candidates, pierced)) {
          hi = mid;
          hi_state = trial;
          hi_pierced = pierced;
          iterations = it;
        } else {
          lo = mid;
          lo_state = trial;
          lo_iterations = it;
        }
      }
      // A vertex entering the band: take the instant just after (it is then inside). A vertex reaching the
      // wall: take the instant just before, so it touches from above (within event_tol) and never pierces.
      band_entered = !hi_pierced;
      next = hi_pierced ? lo_state : hi_state;
      taken = hi_pierced ? lo : hi;
      if (hi_pierced) iterations = lo_iterations;
    }
    if (iterations >= params.max_iterations) ++unconverged;
    stalled_steps = taken < 1e-9 * dt ? stalled_steps + 1 : 0;
    const Vec3 omega_before = next.omega;
    rot = next;
    q = rot.q;
    com = sim::com_position(support, q);
    t += taken;
    ++steps;
    // Without an event the step ends at next.q, whose heights are already known.
    if (!event) z.swap(next_z);
    update_contacts(omega_before, omega_before.cross(com - support.world), /*heights_known=*/!event);
  }

  // One adaptive step, or the part of it before its first event, then the contact update at its end. The
  // step and its first event are found once, over the whole step, so advance_to() can stop inside it (the
  // state there is only interpolated, with no contact decision) without changing the run.
  void rotate_adaptive() {
    if (restart) {
      integrator->start(support, rot, t, std::min(dt, 1e-3 * std::sqrt(length / params.gravity)));
      restart = false;
      in_step = false;
    }
    if (!in_step) begin_adaptive_step();
    const double end = std::min({step_end, max_time, limit});
    if (end < step_end) {  // stopped inside the step by advance_to() or the time limit
      rot = integrator->state_at(end);
      q = rot.q;
      com = sim::com_position(support, q);
      t = end;
      return;
    }
    in_step = false;
    band_entered = step_band_entered;
    if (step_event) restart = true;
    rot = integrator->state_at(step_end);
    stalled_steps = step_end - step_start < 1e-9 * dt ? stalled_steps + 1 : 0;
    q = rot.q;
    com = sim::com_position(support, q);
    t = step_end;
    ++steps;
    update_contacts(rot.omega, rot.omega.cross(com - support.world));
  }

  // Takes one integrator step from t and finds its first event (step_end: the event, or the step's end).
  void begin_adaptive_step() {
    integrator->step();
    in_step = true;
    step_start = t;
    const double t0 = t, t1 = integrator->time();
    // The dense output at evenly spaced instants: the swept arc bounds which vertices can cause an event, and
    // the first instant at which one holds brackets it.
    std::array<Quat, kEventSamples + 1> at;
    std::array<double, kEventSamples + 1> times;
    double arc = 0;
    for (int i = 0; i <= kEventSamples; ++i) {
      times[i] = i == kEventSamples ? t1 : t0 + (t1 - t0) * i / kEventSamples;
      at[i] = i == 0 ? rot.q : integrator->orientation_at(times[i]);
      if (i > 0) arc += 2 * std::acos(std::min(1.0, std::abs(at[i - 1].dot(at[i]))));
    }
    // The chord sum under-estimates the arc by O(h²) of it: a factor 2 covers that with room.
    const double swept = 2 * arc * reach_radius;
    const double level = smooth ? 0.0 : band + touch_tol;
    // Candidates: the vertices within reach of an event at the start or at the end of the step, by two walks;
    // their start heights (the baseline of the pierce test) are refreshed.
    std::vector<int>& candidates = event_candidates;
    candidates.clear();
    walk_union.clear();
    vertices_below(at[0], level + swept + event_tol, walk_union, false);
    vertices_below(at[kEventSamples], level + swept + event_tol, walk_union, false);
    for (int k : walk_union)
      if (!walk_member[k]) {
        walk_member[k] = 1;
        candidates.push_back(k);
      }
    for (int k : candidates) walk_member[k] = 0;
    const Vec3 r3 = at[0].toRotationMatrix().row(2).transpose();
    for (int k : candidates) z[k] = support.world.z() + r3.dot(particle.hull.vertices[k] - support.body);

    bool pierced = false;
    int first = -1;
    for (int i = 1; i <= kEventSamples && first < 0; ++i)
      if (adaptive_event_at(at[i], candidates, pierced)) first = i;
    step_end = t1;
    step_event = first > 0;
    step_band_entered = false;
    if (!step_event) return;
    // Bisect the bracketing interval on the dense output (to 2^-48 of it), over the candidates within reach
    // of an event inside that interval alone.
    const double sub_swept = 4 * std::acos(std::min(1.0, std::abs(at[first - 1].dot(at[first])))) * reach_radius;
    const Vec3 r3_lo = at[first - 1].toRotationMatrix().row(2).transpose();
    const Vec3 r3_hi = at[first].toRotationMatrix().row(2).transpose();
    std::vector<int>& near = walk_out;
    near.clear();
    for (int k : candidates) {
      const Vec3 d = particle.hull.vertices[k] - support.body;
      const double z_lo = support.world.z() + r3_lo.dot(d), z_hi = support.world.z() + r3_hi.dot(d);
      if (std::min(z_lo, z_hi) <= level + sub_swept + event_tol) near.push_back(k);
    }
    double lo = times[first - 1], hi = times[first];
    bool hi_pierced = pierced;
    for (int i = 0; i < kBisections; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (adaptive_event_at(integrator->orientation_at(mid), near, pierced)) {
        hi = mid;
        hi_pierced = pierced;
      } else {
        lo = mid;
      }
    }
    // As in the fixed step: just after a band event, just before a vertex reaches the wall.
    step_band_entered = !hi_pierced;
    step_end = hi_pierced ? lo : hi;
  }

  // The adaptive integrator's events: those of the fixed step, and a contact leaving the ε band (Algorithm
  // 1's contact set shrinks: a line or surface contact may become a point).
  bool adaptive_event_at(const Quat& qq, const std::vector<int>& candidates, bool& pierced) const {
    const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
    bool event = false;
    pierced = false;
    for (int k : candidates) {
      const double zk = support.world.z() + r3.dot(particle.hull.vertices[k] - support.body);
      pierced = pierced || pierces(k, zk);
      event = event || pierced || enters_band(k, zk) || leaves_band(k, zk);
    }
    return event;
  }
  bool leaves_band(std::size_t k, double zk) const {
    return !smooth && !finishing && in_contact[k] && zk > band + touch_tol;
  }

  // ---- contacts, stability and supports
  // --------------------------------------------------------------------

  // Recomputes the contact and touching sets, checks for rest, and switches the support if the contacts call
  // for another one. `omega` and `com_velocity` are the motion just before (for the impact law).
  void update_contacts(const Vec3& omega, const Vec3& com_velocity, bool heights_known = false) {
    // A margin of 1e-9·L: points that reach the band together (mirror images) join together, and a point
    // sitting on the band's edge (on a rotation axis) does not flicker in and out with round-off.
    const double contact_level = band + touch_tol;
    if (adaptive) {
      // Only the vertices near the wall, by a walk (the lowest vertex is among them).
      for (int k : contact) in_contact[k] = 0;
      contact.clear();
      vertices_below(q, contact_level, contact, true);
      const Vec3 r3 = q.toRotationMatrix().row(2).transpose();
      for (int k : contact) {
        z[k] = support.world.z() + r3.dot(particle.hull.vertices[k] - support.body);
        in_contact[k] = 1;
      }
    } else {
      if (!heights_known) heights(q, z);
      contact.clear();
      for (std::size_t k = 0; k < z.size(); ++k) {
        in_contact[k] = z[k] <= contact_level;
        if (in_contact[k]) contact.push_back(static_cast<int>(k));
      }
    }
    touching.clear();
    double lowest = INFINITY;
    for (int k : contact) {
      lowest = std::min(lowest, z[k]);
      if (z[k] <= touch_tol) touching.push_back(k);
    }
    max_penetration = std::max(max_penetration, -lowest);

    // The regression of Algorithm 1 is done on the contact points' footprints on the wall, so the fitted
    // contact line lies in the wall plane: a hinge tilted by the ε band would make the particle swing about
    // an unphysical equilibrium above the wall.
    contact_points.clear();
    footprints.clear();
    for (int k : contact) {
      contact_points.push_back(world_vertex(k));
      footprints.emplace_back(contact_points.back().x(), contact_points.back().y(), 0.0);
    }
    sim::LineFit fit;
    const ContactType new_type =
        smooth ? ContactType::point : sim::classify_contact(footprints, rss_threshold, &fit);
    set_type(new_type);

    const Vec2 g(com.x(), com.y());
    if (smooth) {
      // Three or more points on the wall around the centre of mass: the discretised surface has landed on a
      // face and the inelastic impact leaves no motion (this also ends the ever-faster rocking between the
      // corners of the bottom face). That landing is the only rest: a damped particle creeps onto its facet.
      if (touching.size() >= 3 && touching_points_hold(g) && come_to_rest()) return;
    } else {
      if (touching_points_hold(g) && come_to_rest()) return;
      if (!finishing && paper_stability_test(contact_points, g)) finishing = true;
    }
    choose_support(fit, g, omega, com_velocity);
    if (!smooth && kinetic_energy() < 1e-9 * body.mass * params.gravity * length) tip_off_edge_balance(g);
    if (trace)
      std::fprintf(stderr,
                   "t=%.9g type=%s contact=%zu touching=%zu finishing=%d support=%d line=%d axis=%g,%g,%g "
                   "omega=%g,%g,%g\n",
                   t, to_string(type), contact.size(), touching.size(), finishing, support_vertex,
                   support.line, support.axis.x(), support.axis.y(), support.axis.z(), rot.omega.x(),
                   rot.omega.y(), rot.omega.z());
  }

  void set_type(ContactType new_type) {
    if (!phases.empty() && phases.back().contact == new_type) return;
    if (!phases.empty()) phases.back().t1 = t;
    phases.push_back({new_type, t, t});
    type = new_type;
  }

  std::vector<Vec2> touching_polygon() const {
    std::vector<Vec2> pts;
    for (int k : touching) {
      const Vec3 w = world_vertex(k);
      pts.emplace_back(w.x(), w.y());
    }
    return sim::convex_hull_2d(pts, touch_tol);
  }

  // Static equilibrium on the wall: the touching points surround the centre of mass's projection.
  bool touching_points_hold(const Vec2& g) const {
    if (touching.size() < 3) return false;
    const std::vector<Vec2> poly = touching_polygon();
    return poly.size() >= 3 && sim::polygon_margin(poly, g) > -touch_tol;
  }

  // With no motion left on a segment of touching points (an edge) whose line passes within touch_tol of the
  // centre of mass's projection, the particle is balanced: the weight's moment is round-off. That is an
  // unstable equilibrium, not a rest. Rule (docs/method.md): turn the particle about the edge until its
  // centre of mass is kBalanceOffset·L beyond it, on the side it leans to by round-off (the left of the
  // edge's direction when exactly on it), with no motion; the run then integrates the fall, and its time.
  void tip_off_edge_balance(const Vec2& g) {
    const std::vector<Vec2> poly = touching_polygon();
    if (poly.size() != 2) return;
    const Vec2 a = poly[0], edge = poly[1] - poly[0];
    const Vec2 e = edge.normalized();
    const double along = (g - a).dot(e);
    const double lean = e.x() * (g.y() - a.y()) - e.y() * (g.x() - a.x());  // left of the edge: positive
    if (along < -touch_tol || along > edge.norm() + touch_tol || std::abs(lean) > touch_tol) return;
    const int pivot_vertex = nearest_touching(a);
    const Vec3 pivot = world_vertex(pivot_vertex);
    const Vec3 axis(e.x(), e.y(), 0.0);
    const double height = com.z() - pivot.z();
    const double d = std::hypot(height, lean);
    const double target = (lean < 0 ? -1.0 : 1.0) * kBalanceOffset * length;
    // A rotation by −α about the edge direction moves the centre of mass to the left by d·sin α.
    const double alpha = std::asin(target / d) - std::atan2(lean, height);
    const Quat turn(Eigen::AngleAxisd(-alpha, axis));
    q = (turn * q).normalized();
    support = {pivot, particle.hull.vertices[pivot_vertex], true, axis};
    support_vertex = pivot_vertex;
    reach_radius = hull_radius + support.body.norm();
    com = sim::com_position(support, q);
    rot = {q, Vec3::Zero(), Vec3::Zero()};
    restart = true;
    note_penetration();
    remember_axis(rot.omega);
  }

  // §2.4: a contact element (a hull face all of whose vertices are contacts) hit by the downward ray from the
  // centre of mass, or the centre of mass's projection inside the polygon of contact points. Either suffices.
  bool paper_stability_test(const std::vector<Vec3>& contact_points, const Vec2& g) const {
    if (contact.size() < 3) return false;
    const Vec3 down(0, 0, -1);
    // Only faces whose first vertex is a contact can be contact elements; visiting just those keeps this
    // check proportional to the contacts, not to the hull (thousands of faces for a scanned grain).
    for (int first : contact)
      for (int f : first_vertex_faces[first]) {
        const HullFace& face = particle.hull.faces[f];
        bool element = true;
        for (int k : face.loop) element = element && in_contact[k];
        if (!element) continue;
        const Vec3 a = world_vertex(face.loop[0]);
        for (std::size_t i = 1; i + 1 < face.loop.size(); ++i)
          if (sim::ray_hits_triangle(com, down, a, world_vertex(face.loop[i]),
                                     world_vertex(face.loop[i + 1])))
            return true;
      }
    // The polygon of the contact points' footprints; collinear contacts give a segment, whose margin is minus
    // the distance to it (never positive): a line of contacts holds nothing by itself.
    std::vector<Vec2> plan;
    for (const Vec3& p : contact_points) plan.emplace_back(p.x(), p.y());
    return sim::polygon_margin(sim::convex_hull_2d(plan, touch_tol), g) > 0;
  }

  // The support the contacts call for (see the file comment), and the switch to it if it is new.
  void choose_support(const sim::LineFit& fit, const Vec2& g, const Vec3& omega, const Vec3& com_velocity) {
    sim::Support next;
    int next_vertex = support_vertex;
    auto point_at = [&](int k) {
      next = {world_vertex(k), particle.hull.vertices[k], false, Vec3::UnitX()};
      next_vertex = k;
    };
    auto line_at = [&](int k, const Vec3& axis) {
      point_at(k);
      next.line = true;
      next.axis = axis.normalized();
    };

    // Several points on the wall: the support that lets the others lift off (impact_support.hpp).
    const sim::Impact impact{body, q, com, omega, com_velocity, length, touch_tol, dt};
    touches.clear();
    for (int k : touching) touches.push_back({k, world_vertex(k), particle.hull.vertices[k], z[k]});
    auto take = [&](const sim::SupportChoice& c) {
      next = c.support;
      next_vertex = c.vertex;
    };
    const bool second_guess = stalled_steps < kStallLimit;

    if (smooth) {
      const sim::Touch current{support_vertex, world_vertex(support_vertex),
                               particle.hull.vertices[support_vertex], z[support_vertex]};
      take(sim::choose_smooth(impact, touches, current, g, second_guess));
    } else if (touching.size() <= 1) {
      // One point on the wall: the paper's kinematics from the contact set (Algorithm 1), a rotation about
      // the best-fit line for a line contact, about the previous axis for a surface contact.
      const int o = touching.empty() ? support_vertex : touching[0];
      // The best-fit line is taken when the contact becomes a line and kept while the same point touches:
      // refitting as hovering points enter and leave the band makes the axis flip back and forth between
      // two lines, a cycle in which the particle never settles.
      // A pivot chosen from the touching points is kept until a new point enters the band: switching straight
      // back to the band's line would drive the point that just lifted into the wall again, a rocking cycle.
      const bool keep_line = support.line && support_vertex == o;
      const bool keep_point = !support.line && support_vertex == o && !band_entered;
      Vec3 axis = fit.direction;
      const bool line = type != ContactType::point && !keep_point;
      if (keep_line)
        axis = support.axis;
      else if (type == ContactType::surface && has_prev_axis)
        axis = prev_axis;
      if (line && line_is_supported(o, axis)) {
        line_at(o, axis);
      } else {
        point_at(o);
      }
    } else {
      take(sim::choose_from_touching(impact, touches, g, second_guess));
    }

    const bool same = next_vertex == support_vertex && next.line == support.line &&
                      (!next.line || std::abs(next.axis.dot(support.axis)) > 1 - 1e-14);
    if (same) {
      remember_axis(omega);
      return;
    }
    // Keep a consistent axis sign across switches so momentum signs read naturally.
    if (next.line && support.line && next.axis.dot(support.axis) < 0) next.axis = -next.axis;
    const Vec3 momentum = sim::momentum_after_switch(body, q, com, omega, com_velocity, next);
    // A new support that has sunk by round-off (≤ 1e-12·L) is lifted exactly onto the wall; one that touches
    // from above (within 1e-9·L) stays where it is, so the switch never lowers the particle.
    next.world.z() = std::max(next.world.z(), 0.0);
    support = next;
    support_vertex = next_vertex;
    reach_radius = hull_radius + support.body.norm();
    com = sim::com_position(support, q);
    note_penetration();
    rot.q = q;
    rot.momentum = momentum;
    rot.omega = sim::omega_from_momentum(body, support, q, momentum);
    restart = true;
    remember_axis(rot.omega);
  }

  // The points of a contact line other than the touching point O hover up to ε above the wall; they can only
  // push up. The line holds only if upward forces at them can take the part of the weight's moment about O
  // that the line constraint removes (the component normal to the axis); otherwise the particle would tip
  // about O away from them, and it rotates about the point instead. Without this, a line tilted by up to ε
  // would act as a frictionless hinge on which the particle swings like a pendulum for ever.
  bool line_is_supported(int o, const Vec3& axis) const {
    const Vec3 origin = world_vertex(o);
    const Vec3 e = axis.normalized();
    const Vec3 moment = (com - origin).cross(Vec3(0, 0, -body.mass * params.gravity));
    const Vec3 normal_part = moment - moment.dot(e) * e;
    if (normal_part.norm() <= 1e-9 * moment.norm()) return true;
    bool ahead = false, behind = false;
    Vec3 lever = Vec3::Zero();
    for (int k : contact) {
      const Vec3 d = world_vertex(k) - origin;
      if (k == o || d.norm() <= touch_tol) continue;
      const double s = d.dot(e);
      ahead = ahead || s > touch_tol;
      behind = behind || s < -touch_tol;
      lever += d;
    }
    if (ahead && behind) return true;  // hovering points on both sides of O: either sense can be held
    const Vec3 arm = lever.cross(Vec3::UnitZ());
    if (arm.squaredNorm() == 0) return false;
    return -normal_part.dot(arm) >= 0;  // the force needed at the hovering points is upward
  }

  // After the support or the pose changed: the lowest vertex's depth, if any, counts as penetration. The
  // paper's integrator refreshes every height (its next step reads them); the adaptive one walks to the
  // lowest vertex.
  void note_penetration() {
    if (adaptive) {
      max_penetration = std::max(max_penetration, -lowest_height());
      return;
    }
    heights(q, z);
    max_penetration = std::max(max_penetration, -*std::min_element(z.begin(), z.end()));
  }

  void remember_axis(const Vec3& omega) {
    if (support.line) {
      prev_axis = support.axis;
      has_prev_axis = true;
    } else if (omega.norm() > 1e-12 * std::sqrt(params.gravity / length)) {
      prev_axis = omega.normalized();
      has_prev_axis = true;
    }
  }

  int nearest_touching(const Vec2& p) const {
    int best = touching[0];
    double best_d = INFINITY;
    for (int k : touching) {
      const Vec3 w = world_vertex(k);
      const double d = (Vec2(w.x(), w.y()) - p).norm();
      if (d < best_d) {
        best_d = d;
        best = k;
      }
    }
    return best;
  }

  // ---- rest
  // ------------------------------------------------------------------------------------------------

  // Finds the hull face under the centre of mass; if it is a statically stable face, sets it exactly flush on
  // the wall and ends the run. Returns false (and changes nothing) otherwise.
  bool come_to_rest() {
    const Vec3 down(0, 0, -1);
    int best = -1;
    double best_down = -INFINITY;
    for (std::size_t f = 0; f < particle.hull.faces.size(); ++f) {
      const HullFace& face = particle.hull.faces[f];
      const Vec3 n = q * face.normal;
      if (n.z() >= 0 || -n.z() <= best_down) continue;
      const Vec3 a = world_vertex(face.loop[0]);
      for (std::size_t i = 1; i + 1 < face.loop.size(); ++i) {
        if (sim::ray_hits_triangle(com, down, a, world_vertex(face.loop[i]),
                                   world_vertex(face.loop[i + 1]))) {
          best = static_cast<int>(f);
          best_down = -n.z();
          break;
        }
      }
    }
    if (best < 0 || particle.face_stability_margin[best] <= 0) return false;

    // Rotate the face flush about the support point, then lift or lower it onto the wall exactly.
    const HullFace& face = particle.hull.faces[best];
    const Quat align = Quat::FromTwoVectors(q * face.normal, down);
    q = (align * q).normalized();
    const Vec3 pivot = support.world;
    com = pivot + align * (com - pivot);
    support.world = com + q * support.body;
    double lowest = INFINITY;
    for (int k : face.loop) lowest = std::min(lowest, (com + q * particle.hull.vertices[k]).z());
    com.z() -= lowest;
    support.world.z() -= lowest;

    rest_points.clear();
    double deepest = 0;
    for (const Vec3& v : particle.hull.vertices) deepest = std::min(deepest, (com + q * v).z());
    max_penetration = std::max(max_penetration, -deepest);
    for (int k : face.loop) rest_points.push_back(com + q * particle.hull.vertices[k]);
    rest_face = best;
    rest = smooth ? RestKind::smooth : (particle.face_is_flat[best] ? RestKind::surface : RestKind::points);
    rot = {q, Vec3::Zero(), Vec3::Zero()};
    status = Status::rest;
    // Whatever the band looked like on the way down, the particle now rests on a face: a surface contact.
    if (!smooth) set_type(ContactType::surface);
    if (!phases.empty()) phases.back().t1 = t;
    return true;
  }

  bool advance_to(double time) {
    limit = time;
    while (status == Status::running && t < time) step();
    limit = INFINITY;
    return status == Status::running;
  }

  bool step() {
    if (status != Status::running) return false;
    if (t >= max_time) {
      status = Status::max_time;
    } else if (steps >= params.max_steps) {
      status = Status::max_steps;
    } else if (falling) {
      fall_step();
    } else {
      rotate();
    }
    if (!phases.empty()) phases.back().t1 = t;
    return status == Status::running;
  }

  Sample sample() const {
    Sample s;
    s.t = t;
    s.orientation = q;
    s.omega = (falling || status == Status::rest) ? Vec3::Zero() : rot.omega;
    s.com = com;
    s.contact = falling ? ContactType::free_fall : type;
    s.contact_count = falling ? 0 : static_cast<int>(contact.size());
    s.kinetic_energy = kinetic_energy();
    s.potential_energy = potential_energy();
    return s;
  }

  SettleResult result() const {
    SettleResult r;
    r.status = status;
    r.time = t;
    r.steps = steps;
    r.max_penetration = max_penetration;
    r.orientation = q;
    r.com = com;
    r.rest = rest;
    r.rest_face = rest_face;
    r.contact_points = rest_points;
    r.down_normal_body = q.conjugate() * Vec3(0, 0, -1);
    r.phases = phases;
    r.energy_start = energy_start;
    r.energy_end = kinetic_energy() + potential_energy();
    r.smooth = smooth;
    r.dt = dt;
    r.unconverged_steps = unconverged;
    return r;
  }
};

Settler::Settler(const Particle& particle, const SettleParams& params, const Quat& orientation)
    : impl_(std::make_unique<Impl>(particle, params, orientation)) {}
Settler::~Settler() = default;
Settler::Settler(Settler&&) noexcept = default;
Settler& Settler::operator=(Settler&&) noexcept = default;

bool Settler::step() { return impl_->step(); }
bool Settler::advance_to(double time) { return impl_->advance_to(time); }
Sample Settler::sample() const { return impl_->sample(); }
Status Settler::status() const { return impl_->status; }
SettleResult Settler::result() const { return impl_->result(); }

SettleResult Settler::run(const std::function<void(const Sample&)>& observer, double sample_dt) {
  if (!(std::isfinite(sample_dt) && sample_dt >= 0))
    throw Error("sample interval must be a finite number >= 0, got " + std::to_string(sample_dt));
  if (observer) observer(sample());
  if (sample_dt > 0) {
    for (long k = 1; impl_->status == Status::running; ++k) {
      advance_to(static_cast<double>(k) * sample_dt);
      if (observer) observer(sample());
    }
    return result();
  }
  while (impl_->status == Status::running) {
    const long steps_before = impl_->steps;
    const double t_before = impl_->t;
    step();
    if (observer && (impl_->steps != steps_before || impl_->t != t_before)) observer(sample());
  }
  return result();
}

SettleResult settle(const Particle& particle, const SettleParams& params, const Quat& orientation,
                    const std::function<void(const Sample&)>& observer, double sample_dt) {
  Settler settler(particle, params, orientation);
  return settler.run(observer, sample_dt);
}

}  // namespace repose
