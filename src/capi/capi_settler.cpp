// The C API's settles: a DEM code's hand-over state in, the run stepped or run to rest, the state and the
// result out, all in the world frame of the caller's floor.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "capi_support.hpp"

using repose::Quat;
using repose::Vec3;
using repose::capi::CodedError;
using repose::capi::guarded;
using repose::capi::require;

// The C codes are the enumerators' positions.
static_assert(static_cast<int>(repose::Status::running) == REPOSE_RUNNING &&
              static_cast<int>(repose::Status::rest) == REPOSE_REST &&
              static_cast<int>(repose::Status::max_time) == REPOSE_MAX_TIME &&
              static_cast<int>(repose::Status::max_steps) == REPOSE_MAX_STEPS);
static_assert(static_cast<int>(repose::ContactType::free_fall) == REPOSE_CONTACT_FREE_FALL &&
              static_cast<int>(repose::ContactType::point) == REPOSE_CONTACT_POINT &&
              static_cast<int>(repose::ContactType::line) == REPOSE_CONTACT_LINE &&
              static_cast<int>(repose::ContactType::surface) == REPOSE_CONTACT_SURFACE &&
              static_cast<int>(repose::ContactType::flight) == REPOSE_CONTACT_FLIGHT);
static_assert(static_cast<int>(repose::RestKind::none) == REPOSE_REST_NONE &&
              static_cast<int>(repose::RestKind::surface) == REPOSE_REST_SURFACE &&
              static_cast<int>(repose::RestKind::points) == REPOSE_REST_POINTS &&
              static_cast<int>(repose::RestKind::smooth) == REPOSE_REST_SMOOTH);

namespace {

Vec3 vec(const double (&v)[3]) { return {v[0], v[1], v[2]}; }
void put(const Vec3& v, double (&out)[3]) {
  for (int k = 0; k < 3; ++k) out[k] = v[k];
}
void put(const Quat& q, double (&out)[4]) {
  out[0] = q.w();
  out[1] = q.x();
  out[2] = q.y();
  out[3] = q.z();
}

void check_finite(const double* x, int n, const char* what) {
  for (int k = 0; k < n; ++k)
    if (!std::isfinite(x[k]))
      throw CodedError(REPOSE_ERROR_BAD_STATE, std::string("start: ") + what + " is not finite");
}

// The start state as the engine takes it: the lowest point's height above the floor and the motion. The
// engine places the centre of mass above the origin; `offset` takes its frame back to the caller's world.
void begin(repose_settler& s, const repose_state& start, double floor_height) {
  check_finite(start.position, 3, "position");
  check_finite(start.orientation, 4, "orientation");
  check_finite(start.velocity, 3, "velocity");
  check_finite(start.angular_velocity, 3, "angular_velocity");
  if (!std::isfinite(floor_height)) throw CodedError(REPOSE_ERROR_BAD_STATE, "floor_height is not finite");
  const Quat raw(start.orientation[0], start.orientation[1], start.orientation[2], start.orientation[3]);
  const double norm = raw.norm();
  if (!std::isfinite(norm) || norm < 1e-8)
    throw CodedError(REPOSE_ERROR_BAD_STATE, "start: orientation must be a nonzero quaternion (w, x, y, z)");
  const Quat q = raw.normalized();

  const repose::Particle& p = *s.model;
  double lowest = INFINITY;  // the lowest hull vertex's height above the centre of mass
  for (const Vec3& v : p.hull.vertices) lowest = std::min(lowest, (q * v).z());
  const double height = start.position[2] - floor_height + lowest;
  const double band = s.params.contact_threshold * p.length;
  if (height < -band)
    throw CodedError(REPOSE_ERROR_BAD_STATE,
                     "start: the particle's lowest point is " + std::to_string(-height) +
                         " below the floor (more than the contact band, contact_threshold * L = " +
                         std::to_string(band) + ")");
  s.lift = height < 0 ? -height : 0.0;
  s.params.drop_height = std::max(height, 0.0);
  s.params.drop_speed = 0;
  s.params.velocity = vec(start.velocity);
  s.params.spin = vec(start.angular_velocity);
  s.settler.emplace(*s.model, s.params, q);
  const Vec3 com = s.settler->sample().com;
  s.offset = Vec3(start.position[0] - com.x(), start.position[1] - com.y(),
                  height < 0 ? floor_height : start.position[2] - com.z());
}

const repose_settler& valid(const repose_settler* settler) {
  require(settler, "settler");
  return *settler;
}

}  // namespace

extern "C" {

int repose_settler_new(const repose_particle* particle, const repose_params* params,
                       const repose_state* start, double floor_height, repose_settler** settler) {
  return guarded("repose_settler_new", REPOSE_ERROR_BAD_PARAMETER, [&] {
    require(particle, "particle");
    require(params, "params");
    require(start, "start");
    require(settler, "settler");
    auto out = std::make_unique<repose_settler>();
    out->model = particle->model;
    out->params = params->params;
    begin(*out, *start, floor_height);
    *settler = out.release();
  });
}

void repose_settler_free(repose_settler* settler) { delete settler; }

int repose_settler_step(repose_settler* settler, int* running) {
  return guarded("repose_settler_step", REPOSE_ERROR_INTERNAL, [&] {
    require(settler, "settler");
    const bool more = settler->settler->step();
    if (running != nullptr) *running = more ? 1 : 0;
  });
}

int repose_settler_advance_to(repose_settler* settler, double time, int* running) {
  return guarded("repose_settler_advance_to", REPOSE_ERROR_INTERNAL, [&] {
    require(settler, "settler");
    if (!std::isfinite(time))
      throw CodedError(REPOSE_ERROR_BAD_PARAMETER, "time must be finite, got " + std::to_string(time));
    const bool more = settler->settler->advance_to(time);
    if (running != nullptr) *running = more ? 1 : 0;
  });
}

int repose_settler_run(repose_settler* settler) {
  return guarded("repose_settler_run", REPOSE_ERROR_INTERNAL, [&] {
    require(settler, "settler");
    while (settler->settler->step()) {
    }  // bounded: the engine stops at max_time and max_steps
  });
}

int repose_settler_state(const repose_settler* settler, repose_state* state, double* time) {
  return guarded("repose_settler_state", REPOSE_ERROR_INTERNAL, [&] {
    const repose_settler& s = valid(settler);
    require(state, "state");
    const repose::Sample now = s.settler->sample();
    repose_state out{};
    put(Vec3(now.com + s.offset), out.position);
    put(now.orientation, out.orientation);
    put(now.velocity, out.velocity);
    put(now.omega, out.angular_velocity);
    *state = out;
    if (time != nullptr) *time = now.t;
  });
}

int repose_settler_status(const repose_settler* settler, int* status) {
  return guarded("repose_settler_status", REPOSE_ERROR_INTERNAL, [&] {
    const repose_settler& s = valid(settler);
    require(status, "status");
    *status = static_cast<int>(s.settler->status());  // the enumerators' order is the codes'
  });
}

int repose_settler_contact(const repose_settler* settler, int* contact_type, int* contact_count) {
  return guarded("repose_settler_contact", REPOSE_ERROR_INTERNAL, [&] {
    const repose_settler& s = valid(settler);
    const repose::Sample now = s.settler->sample();
    if (contact_type != nullptr) *contact_type = static_cast<int>(now.contact);
    if (contact_count != nullptr) *contact_count = now.contact_count;
  });
}

int repose_settler_contact_points(const repose_settler* settler, double* points, size_t capacity,
                                  size_t* count) {
  return guarded("repose_settler_contact_points", REPOSE_ERROR_INTERNAL, [&] {
    const repose_settler& s = valid(settler);
    require(count, "count");
    if (capacity > 0) require(points, "points");
    std::vector<Vec3> found;
    if (s.settler->status() == repose::Status::rest) {
      found = s.settler->result().contact_points;
    } else {
      const repose::Sample now = s.settler->sample();
      const double band = s.params.contact_threshold * s.model->length;
      for (const Vec3& v : s.model->hull.vertices) {
        const Vec3 world = now.com + now.orientation * v;
        if (world.z() <= band) found.push_back(world);
      }
    }
    *count = found.size();
    for (size_t i = 0; i < std::min(capacity, found.size()); ++i)
      for (int k = 0; k < 3; ++k) points[3 * i + static_cast<size_t>(k)] = found[i][k] + s.offset[k];
    if (capacity < found.size())
      throw CodedError(REPOSE_ERROR_BUFFER_TOO_SMALL, "points has room for " + std::to_string(capacity) +
                                                          " points, there are " +
                                                          std::to_string(found.size()));
  });
}

int repose_settler_result(const repose_settler* settler, repose_result* result) {
  return guarded("repose_settler_result", REPOSE_ERROR_INTERNAL, [&] {
    const repose_settler& s = valid(settler);
    require(result, "result");
    const repose::SettleResult r = s.settler->result();
    repose_result out{};
    out.status = static_cast<int>(r.status);
    out.rest_kind = static_cast<int>(r.rest);
    out.rest_face = r.rest_face;
    out.bounces = r.bounces;
    out.steps = r.steps;
    out.time = r.time;
    put(Vec3(r.com + s.offset), out.position);
    put(r.orientation, out.orientation);
    put(r.down_normal_body, out.down_normal_body);
    out.max_penetration = r.max_penetration;
    out.lift = s.lift;
    out.energy_start = r.energy_start;
    out.energy_end = r.energy_end;
    *result = out;
  });
}

int repose_settler_friction_account(const repose_settler* settler, repose_friction_account* account) {
  return guarded("repose_settler_friction_account", REPOSE_ERROR_INTERNAL, [&] {
    const repose_settler& s = valid(settler);
    require(account, "account");
    const repose::SettleResult r = s.settler->result();
    repose_friction_account out{};
    out.friction_work = r.friction_work;
    out.damping_work = r.damping_work;
    for (const repose::ImpactRecord& i : r.impacts) out.impact_losses += i.energy_before - i.energy_after;
    out.painleve = r.painleve;
    if (const auto& f = r.frictional) {
      out.normal_work = f->normal_work;
      out.stopping_losses = f->stopping_losses;
      out.drift_corrections = f->drift_corrections;
      out.repositioning = f->repositioning;
      out.rest_losses = f->rest_losses;
      out.paper_phase_losses = f->paper_phase_losses;
      out.frictionless_motion = f->frictionless_motion;
      out.handovers_stalled = f->handovers_stalled;
      out.handovers_timed_out = f->handovers_timed_out;
      out.bounded_rounds = f->bounded_rounds;
      out.pyramid_forces = f->pyramid_forces;
      out.unsolved_forces = f->unsolved_forces;
      out.unresolved_forces = f->unresolved_forces;
      out.zeno_captures = f->zeno_captures;
      out.tip_offs = f->tip_offs;
    } else {
      out = repose_friction_account{};  // friction infinite: every field zero, as documented
    }
    *account = out;
  });
}

int repose_settle(const repose_particle* particle, const repose_params* params, const repose_state* start,
                  double floor_height, repose_result* result) {
  repose_settler* settler = nullptr;
  int code = repose_settler_new(particle, params, start, floor_height, &settler);
  if (code == REPOSE_OK && result == nullptr)
    code = repose::capi::fail(REPOSE_ERROR_NULL_POINTER, "repose_settle", "result is NULL");
  if (code == REPOSE_OK) code = repose_settler_run(settler);
  if (code == REPOSE_OK) code = repose_settler_result(settler, result);
  repose_settler_free(settler);
  return code;
}

}  // extern "C"
