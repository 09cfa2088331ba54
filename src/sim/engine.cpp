// The engine's transitions (engine.hpp): every change of phase happens here.
#include "engine.hpp"

namespace repose::sim {

namespace {
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;  // (clang 14 has no aggregate deduction)
}  // namespace

Engine::Engine(const Particle& particle, const SettleParams& params, const Quat& orientation)
    : run_(particle, params, orientation), phase_(std::in_place_type<Stopped>) {
  // start → flight: dropped from a height, or tossed; start → contact: on the wall at t = 0.
  const SettleParams& p = run_.params;
  const Vec3 velocity = p.velocity - Vec3(0, 0, p.drop_speed);
  if (frictional() && p.drop_height == 0)
    start_frictional({velocity, p.spin});  // on the wall, with whatever motion it was given
  else if (p.drop_height > 0 || p.velocity != Vec3::Zero() || p.spin != Vec3::Zero() ||
           (p.drop_speed > 0 && uses_impacts(p)))  // thrown down from the wall: the impact law, at once
    start_flight(velocity, p.spin, p.drop_height);
  else
    start_contact(Vec3(0, 0, -p.drop_speed), Vec3::Zero(), false);
}

// The transition table of docs/method.md ("Phases"), row by row: each phase's step reports the event that
// ends it, if any, and the branch below for that phase takes the transition.
bool Engine::step() {
  if (status() != Status::running) return false;
  if (run_.t >= run_.tol.max_time) {
    stop(Status::max_time);
  } else if (run_.steps >= run_.params.max_steps) {
    stop(Status::max_steps);
  } else if (auto* flight = std::get_if<Flight>(&phase_)) {
    if (const auto touch = flight->step()) {
      if (frictional()) {
        // The frictional phase resolves the landing's impacts at its first segment start, by the laws of
        // its impacts in contact (Zeno's captures among them); a rebound lifts off again.
        start_frictional({touch->velocity, touch->omega});
      } else if (!uses_impacts(run_.params)) {
        start_contact(touch->velocity, Vec3::Zero(), false);
      } else {
        const Impact::Outcome out = Impact(run_).resolve({touch->velocity, touch->omega});
        if (out.rebound)
          start_flight(out.motion.velocity, out.motion.omega, 0.0);
        else
          start_contact(out.motion.velocity, out.motion.omega, true);
      }
    }
  } else if (auto* contact = std::get_if<Contact>(&phase_)) {
    if (auto rest = contact->step()) {
      const int count = contact->contact_count();
      phase_.emplace<Rest>(Rest{std::move(*rest), count});
    }
  } else if (auto* sliding = std::get_if<FrictionalContact>(&phase_)) {
    if (run_.t - sliding->start_time() >= run_.tol.frictional_time || sliding->stalled()) {
      // A fallback, counted with its cause; what the paper's phase then takes is in the ledger.
      FrictionalAccount& account = run_.record.account;
      ++(sliding->stalled() ? account.handovers_stalled : account.handovers_timed_out);
      if (std::isnan(run_.record.handover_energy))
        run_.record.handover_energy = sliding->kinetic_energy() + run_.potential_energy();
      const Vec3 velocity = sliding->velocity(), omega = sliding->omega();
      start_contact(velocity, omega, true);
    } else if (auto end = sliding->step()) {
      if (const auto* lift = std::get_if<FrictionalContact::LiftOff>(&*end)) {
        start_flight(lift->motion.velocity, lift->motion.omega, lift->height);
      } else {
        const int count = sliding->contact_count();
        phase_.emplace<Rest>(Rest{std::move(std::get<RestPose>(*end)), count});
      }
    }
  }
  if (!run_.record.phases.empty()) run_.record.phases.back().t1 = run_.t;
  return status() == Status::running;
}

void Engine::start_flight(const Vec3& velocity, const Vec3& omega, double height) {
  phase_.emplace<Flight>(run_, velocity, omega, height);
}

void Engine::start_contact(const Vec3& com_velocity, const Vec3& omega, bool carry) {
  Contact& contact = phase_.emplace<Contact>(run_);
  if (auto rest = contact.begin(com_velocity, omega, carry)) {
    const int count = contact.contact_count();
    phase_.emplace<Rest>(Rest{std::move(*rest), count});
  }
}

void Engine::start_frictional(const Motion& motion) { phase_.emplace<FrictionalContact>(run_, motion); }

void Engine::stop(Status why) {
  const Sample now = sample();  // the motion it had, as the phase it stops reports it
  phase_.emplace<Stopped>(Stopped{why, now.omega, now.contact_count, now.kinetic_energy, now.velocity});
}

bool Engine::advance_to(double time) {
  run_.limit = time;
  while (status() == Status::running && run_.t < time) step();
  run_.limit = INFINITY;
  return status() == Status::running;
}

Status Engine::status() const {
  if (const Stopped* stopped = std::get_if<Stopped>(&phase_)) return stopped->why;
  return std::holds_alternative<Rest>(phase_) ? Status::rest : Status::running;
}

double Engine::kinetic_energy() const {
  return std::visit(
      Overloaded{[](const Flight& f) { return f.kinetic_energy(); },
                 [](const Contact& c) { return c.kinetic_energy(); },
                 [](const FrictionalContact& c) { return c.kinetic_energy(); },
                 [](const Rest&) { return 0.0; }, [](const Stopped& s) { return s.kinetic_energy; }},
      phase_);
}

Sample Engine::sample() const {
  Sample s;
  s.t = run_.t;
  s.orientation = run_.q;
  s.com = run_.com;
  s.contact = run_.record.type();
  std::visit(Overloaded{[&](const Flight& f) {
                          s.omega = f.omega();
                          s.velocity = f.velocity();
                        },
                        [&](const Contact& c) {
                          s.omega = c.omega();  // a rotation about the support: v = ω × (com − pivot)
                          s.velocity = c.omega().cross(run_.com - c.support().world);
                          s.contact_count = c.contact_count();
                        },
                        [&](const FrictionalContact& c) {
                          s.contact = c.contact_type();  // its first segment may not have begun yet
                          s.omega = c.omega();
                          s.velocity = c.velocity();
                          s.contact_count = c.contact_count();
                          s.sticking = c.sticking();
                          s.sliding = c.sliding();
                        },
                        [&](const Rest& r) { s.contact_count = r.contact_count; },
                        [&](const Stopped& st) {
                          s.omega = st.omega;
                          s.velocity = st.velocity;
                          s.contact_count = st.contact_count;
                        }},
             phase_);
  s.kinetic_energy = kinetic_energy();
  s.potential_energy = run_.potential_energy();
  return s;
}

SettleResult Engine::result() const {
  const Recorder& rec = run_.record;
  SettleResult r;
  r.status = status();
  r.time = run_.t;
  r.stable_time = rec.stable_time;
  r.steps = run_.steps;
  r.max_penetration = rec.max_penetration;
  r.orientation = run_.q;
  r.com = run_.com;
  if (const Rest* rest = std::get_if<Rest>(&phase_)) {
    r.rest = rest->pose.kind;
    r.rest_face = rest->pose.face;
    r.contact_points = rest->pose.points;
  }
  r.down_normal_body = run_.q.conjugate() * Vec3(0, 0, -1);
  r.phases = rec.phases;
  r.impacts = rec.impacts;
  r.bounces = rec.bounces;
  r.energy_start = rec.energy_start;
  r.energy_end = kinetic_energy() + run_.potential_energy();
  r.smooth = run_.surface.kind() == SurfaceModel::Kind::smooth;
  r.dt = run_.tol.dt;
  r.unconverged_steps = rec.unconverged;
  r.friction_work = rec.friction_work;
  r.damping_work = rec.damping_work;
  r.sliding_distance = rec.sliding_distance;
  r.painleve = rec.painleve;
  if (frictional()) {
    r.frictional = rec.account;
    if (!std::isnan(rec.handover_energy))
      r.frictional->paper_phase_losses = rec.handover_energy - r.energy_end;
  }
  return r;
}

}  // namespace repose::sim
