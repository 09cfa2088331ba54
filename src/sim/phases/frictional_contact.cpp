// The frictional contact phase (frictional_contact.hpp).
#include "frictional_contact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../body/kinematics.hpp"
#include "impact.hpp"

namespace repose::sim {

namespace {
// The contact type by the number of points on the wall (flight when none).
ContactType type_of(int points) {
  return points == 0   ? ContactType::flight
         : points == 1 ? ContactType::point
         : points == 2 ? ContactType::line
                       : ContactType::surface;
}
}  // namespace

FrictionalContact::FrictionalContact(Run& run, const Motion& motion)
    : run_(run),
      integrator_(run.body.mass, run.tol.length, run.params.gravity, run.params.tolerance,
                  run.tol.flight_max_step),
      velocity_(motion.velocity),
      omega_(motion.omega),
      ledger_{run.record.friction_work, run.record.damping_work, run.record.sliding_distance,
              run.record.account.normal_work} {
  if (std::isnan(run.record.frictional_start)) run.record.frictional_start = run.t;
}

double FrictionalContact::kinetic_energy() const {
  const Mat3 R = run_.q.toRotationMatrix();
  return sim::kinetic_energy(run_.body.mass, world_inertia(R, run_.body.inertia), {velocity_, omega_});
}

bool FrictionalContact::stalled() const { return stalls_ >= tol::kStalls; }

// The hull vertices within the band (by walks: wall/near_wall.hpp), in index order.
const std::vector<int>& FrictionalContact::within_band() const {
  const Run& run = run_;
  const auto& verts = run.particle.hull.vertices;
  return run.near_wall.vertices_below(run.q, run.com.z(), run.tol.frictional_band, run.tol.event, [&](int k) {
    return !(run.com.z() + (run.q * verts[static_cast<std::size_t>(k)]).z() > run.tol.frictional_band);
  });
}

std::pair<int, int> FrictionalContact::points_before_start() const {
  const Run& run = run_;
  const auto& verts = run.particle.hull.vertices;
  int on = 0, slipping = 0;
  for (int k : within_band()) {
    const Vec3 arm = run.q * verts[static_cast<std::size_t>(k)];
    ++on;
    slipping += (point_velocity(velocity_, omega_, arm)).head<2>().norm() > run.tol.slip_speed;
  }
  return {on, slipping};
}

int FrictionalContact::contact_count() const {
  return started_ ? static_cast<int>(active_.size()) : points_before_start().first;
}
int FrictionalContact::sticking() const {
  if (!started_) {
    const auto [on, slipping] = points_before_start();
    return on - slipping;
  }
  return static_cast<int>(std::count(forces_.modes.begin(), forces_.modes.end(), ContactMode::stick));
}
int FrictionalContact::sliding() const {
  if (!started_) return points_before_start().second;
  return static_cast<int>(std::count(forces_.modes.begin(), forces_.modes.end(), ContactMode::slide));
}

ContactType FrictionalContact::contact_type() const {
  if (started_) return run_.record.type();
  return type_of(contact_count());
}

std::optional<FrictionalContact::End> FrictionalContact::step() {
  Run& run = run_;
  if (run.t >= step_end_) {
    segment_start_ = run.t;
    if (auto end = begin_segment()) return end;
    const auto [a, b] = integrator_.step();
    step_end_ = b;
    event_ = locate_event(a, b);
    ++run.steps;
  }
  const double end = std::min({event_, step_end_, run.tol.max_time, run.limit});
  move_to(end);
  if (end == event_) step_end_ = end;  // a new segment starts at the event
  // Segments that end at once, one after another (a slip that stops as soon as it is taken as sliding, an
  // event found again at once), are bounded: after tol::kStalls of them the engine hands the run to the
  // paper's phase (stalled(), counted).
  stalls_ = end - segment_start_ <= tol::kStallTime * run.tol.time_scale ? stalls_ + 1 : 0;
  return std::nullopt;
}

void FrictionalContact::move_to(double t) {
  const BodyState s = integrator_.state_at(t);
  run_.t = t;
  run_.q = s.q;
  run_.com = s.com;
  velocity_ = s.velocity;
  omega_ = s.omega;
  ledger_ = integrator_.ledger_at(t);
  run_.record.friction_work = ledger_.friction_work;
  run_.record.damping_work = ledger_.damping_work;
  run_.record.sliding_distance = ledger_.sliding_distance;
  run_.record.account.normal_work = ledger_.normal_work;
}

// The points on the wall: within the band and not leaving it; each slides along its slip or is at rest.
void FrictionalContact::classify() {
  const Run& run = run_;
  const auto& verts = run.particle.hull.vertices;
  active_.clear();
  conditions_.clear();
  leaving_slowly_.clear();
  for (int k : within_band()) {
    const Vec3 arm = run.q * verts[static_cast<std::size_t>(k)];
    const double z = run.com.z() + arm.z();
    const Vec3 u = point_velocity(velocity_, omega_, arm);
    if (u.z() > run.tol.speed) {  // leaving: it lifts (a slow one comes back as a Zeno capture)
      if (u.z() <= run.tol.separation_speed) leaving_slowly_.push_back(k);
      continue;
    }
    // Approaching, not yet at the wall: it strikes where it reaches it (an event), not early in the band.
    if (u.z() < -run.tol.speed && z > tol::kPierceFloor * run.tol.event) continue;
    active_.push_back(k);
    PointCondition c;
    const Vec2 slip = u.head<2>();
    const bool slid = std::find(sliding_before_.begin(), sliding_before_.end(), k) != sliding_before_.end();
    if (slip.norm() > (slid ? tol::kSlipHysteresis : 1.0) * run.tol.slip_speed) {
      c.rule = PointRule::sliding;
      c.direction = slip.normalized();
    }
    conditions_.push_back(c);
  }
}

std::optional<FrictionalContact::End> FrictionalContact::begin_segment() {
  Run& run = run_;
  warm_start_.clear();  // the segment's own forces, found cold, start the sweeps of its rate evaluations
  const auto& verts = run.particle.hull.vertices;
  // Nothing below the wall: the integrator's drift is undone by lifting the body (its depth is recorded);
  // a lowest point that drifted up within the band while not leaving is set back on the wall.
  double lowest = INFINITY;
  Vec3 lowest_arm = Vec3::Zero();
  for (int k : run.near_wall.near_lowest(run.q, run.tol.event)) {
    const Vec3 arm = run.q * verts[static_cast<std::size_t>(k)];
    if (run.com.z() + arm.z() < lowest) {
      lowest = run.com.z() + arm.z();
      lowest_arm = arm;
    }
  }
  if (lowest < 0 || (lowest <= run.tol.frictional_band &&
                     std::abs((point_velocity(velocity_, omega_, lowest_arm)).z()) <= run.tol.speed)) {
    if (lowest < 0) run.record.note_depth(-lowest);
    run.com.z() -= lowest;
    run.record.account.repositioning -= run.body.mass * run.params.gravity * lowest;  // in the ledger
  }
  bool settled = false;
  for (int round = 0; round < tol::kSegmentRounds && !settled; ++round) {
    classify();
    if (resolve_impacts()) continue;
    forces_ = forces_at({run.com, velocity_, run.q, omega_});
    count_fallbacks(forces_);
    if (hold_unresolved_hops()) continue;
    settled = !resolve_painleve();
  }
  if (!settled) {  // the rounds' bound: the points as they are now
    ++run.record.account.bounded_rounds;
    classify();
    forces_ = forces_at({run.com, velocity_, run.q, omega_});
  }
  undo_drift();
  // Points newly at rest driven into the wall: stopped by the plastic law; a point at rest that the impulses
  // set slipping faster than slip_speed slides from here (its friction against its slip, not its
  // acceleration).
  if (stop_landed_points()) {
    for (std::size_t i = 0; i < active_.size(); ++i) {
      const Vec3 arm = run.q * verts[static_cast<std::size_t>(active_[i])];
      const Vec2 slip = (point_velocity(velocity_, omega_, arm)).head<2>();
      if (conditions_[i].rule == PointRule::unilateral &&
          slip.norm() > tol::kSlipHysteresis * run.tol.slip_speed)
        conditions_[i] = {PointRule::sliding, slip.normalized(), 0.0};
    }
    forces_ = forces_at({run.com, velocity_, run.q, omega_});
    count_fallbacks(forces_);
  }
  const std::size_t n = active_.size();
  if (forces_.forces.size() == n) warm_start_ = forces_.forces;
  if (run.trace)
    std::fprintf(stderr,
                 "t=%.12g frictional points=%zu stick=%d slide=%d painleve=%d v=%g,%g,%g omega=%g,%g,%g\n",
                 run.t, n, sticking(), sliding(), run.record.painleve, velocity_.x(), velocity_.y(),
                 velocity_.z(), omega_.x(), omega_.y(), omega_.z());
  // Every point leaves the wall (none pressed after the impacts, captures and holds): the engine's flight
  // takes the hop from here.
  if (n == 0) return LiftOff{{velocity_, omega_}, std::max(run.com.z() + run.lowest_offset(run.q), 0.0)};
  run.record.set_type(type_of(static_cast<int>(n)), run.t);
  // Rest: on the wall with too little energy to lift it out of the band (a rocking block's impacts would
  // otherwise accumulate without end, as Housner's do), nothing accelerating with the velocities at zero,
  // over a stable face. The energy dropped is at most m·g·band.
  // Without friction nothing ever stops the centre of mass's horizontal velocity nor the spin about the
  // vertical (the wall's forces are vertical: no horizontal force, no vertical moment): the rest is judged
  // in the frame that moves and turns with them (the same pose), and the motion the body keeps is in the
  // ledger (FrictionalAccount::frictionless_motion).
  const bool frictionless = run.params.friction == 0;
  double translation = 0;
  if (frictionless) {
    const Mat3 R = run.q.toRotationMatrix();
    translation = sim::kinetic_energy(run.body.mass, world_inertia(R, run.body.inertia),
                                      {Vec3(velocity_.x(), velocity_.y(), 0), Vec3(0, 0, omega_.z())});
  }
  const bool slides =
      !frictionless && std::any_of(conditions_.begin(), conditions_.end(),
                                   [](const PointCondition& c) { return c.rule == PointRule::sliding; });
  if (!slides && kinetic_energy() - translation <= run.tol.rest_energy) {
    // Every point within the band, leaving or not: the body cannot leave it.
    const std::vector<int> band = within_band();
    const ContactForces still = forces_at({run.com, Vec3::Zero(), run.q, Vec3::Zero()}, band,
                                          std::vector<PointCondition>(band.size()));
    if (still.acceleration.norm() <= run.tol.still_acceleration &&
        still.angular_acceleration.norm() * run.tol.length <= run.tol.still_acceleration) {
      const Vec3 body_point = verts[static_cast<std::size_t>(active_[0])];
      const Support support{run.com + run.q * body_point, body_point, false, Vec3::UnitX()};
      // A rest lays the face under the centre of mass flush, if it is on the wall (all its points within the
      // band). Still on fewer points of it, the body balances on an edge (a rocking grain at the turning
      // point of its swing with its centre of mass over the edge): the paper's rule for an edge balance tips
      // it towards that face.
      const int face = face_under_com(run, support);
      const double potential_before = run.potential_energy();  // a flush rest lays the face down
      if (face >= 0 && !face_on_wall(face)) {
        if (run.record.account.tip_offs < tol::kTipOffs && band.size() >= 2 && tip_onto_face(band, face)) {
          ++run.record.account.tip_offs;
          return begin_segment();
        }
      } else if (auto rest = flush_rest(run, support)) {
        run.record.account.repositioning += run.potential_energy() - potential_before;
        run.record.account.frictionless_motion += translation;
        run.record.account.rest_losses += kinetic_energy() - translation;
        velocity_ = omega_ = Vec3::Zero();
        return rest;
      } else if (run.record.account.tip_offs < tol::kTipOffs && tip_off_balance(support)) {
        // Still, on a face the paper's test calls unstable: balanced on its boundary to round-off (a designed
        // die's face whose margin is 0 to 1e-12·L). Left by the paper's rule for an edge balance.
        ++run.record.account.tip_offs;
        return begin_segment();
      }
    }
  }
  const double first = started_ ? integrator_.proposed_step() : run.tol.first_step;
  started_ = true;
  integrator_.start({run.com, velocity_, run.q, omega_}, ledger_, run.t, first,
                    [this](const BodyState& s) { return rates(s); });
  return std::nullopt;
}

}  // namespace repose::sim
