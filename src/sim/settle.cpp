// The settling engine's public API (paper §2.1-2.4): a thin wrapper of the engine (engine.hpp), the state
// machine over the phases of a run.
#include "repose/sim/settle.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine.hpp"
#include "repose/error.hpp"

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
    case ContactType::flight:
      return "flight";
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
  return sim::tol::kSampleInterval * std::sqrt(particle.length / params.gravity);
}

bool is_smooth_surface(const Particle& particle) {
  return particle.convex_surface && particle.max_dihedral_angle < std::numbers::pi / 6;
}

Settler::Settler(const Particle& particle, const SettleParams& params, const Quat& orientation)
    : engine_(std::make_unique<sim::Engine>(particle, params, orientation)) {}
Settler::~Settler() = default;
Settler::Settler(Settler&&) noexcept = default;
Settler& Settler::operator=(Settler&&) noexcept = default;

bool Settler::step() { return engine_->step(); }
bool Settler::advance_to(double time) { return engine_->advance_to(time); }
Sample Settler::sample() const { return engine_->sample(); }
Status Settler::status() const { return engine_->status(); }
SettleResult Settler::result() const { return engine_->result(); }

SettleResult Settler::run(const std::function<void(const Sample&)>& observer, double sample_dt) {
  if (!(std::isfinite(sample_dt) && sample_dt >= 0))
    throw Error("sample interval must be a finite number >= 0, got " + std::to_string(sample_dt));
  if (observer) observer(sample());
  if (sample_dt > 0) {
    for (long k = 1; engine_->status() == Status::running; ++k) {
      advance_to(static_cast<double>(k) * sample_dt);
      if (observer) observer(sample());
    }
    return result();
  }
  while (engine_->status() == Status::running) {
    const long steps_before = engine_->run().steps;
    const double t_before = engine_->run().t;
    step();
    if (observer && (engine_->run().steps != steps_before || engine_->run().t != t_before))
      observer(sample());
  }
  return result();
}

SettleResult settle(const Particle& particle, const SettleParams& params, const Quat& orientation,
                    const std::function<void(const Sample&)>& observer, double sample_dt) {
  Settler settler(particle, params, orientation);
  return settler.run(observer, sample_dt);
}

}  // namespace repose
