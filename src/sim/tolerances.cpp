#include "tolerances.hpp"

#include <algorithm>
#include <cmath>

namespace repose::sim {

Tolerances make_tolerances(const Particle& particle, const SettleParams& params) {
  Tolerances t;
  const double length = particle.length, mass = particle.mass.mass, g = params.gravity;
  const bool adaptive = params.integrator == Integrator::adaptive;
  t.length = length;
  t.time_scale = std::sqrt(length / g);
  t.band = params.contact_threshold * length;
  t.touch = tol::kTouch * length;
  t.event = tol::kEvent * length;
  t.rss_threshold = params.line_threshold * length * length;
  t.speed = tol::kSpeed * std::sqrt(g * length);
  t.frictional_band = tol::kFrictionalBand * length;
  t.separation_speed = std::sqrt(2 * g * t.frictional_band);
  t.slip_speed = tol::kSlipSpeed * std::sqrt(g * length);
  t.rest_energy = mass * g * t.frictional_band;
  t.still_acceleration = tol::kAccel * g;
  t.still_energy = tol::kStill * mass * g * length;
  t.axis_rate = tol::kAxisRate * std::sqrt(g / length);
  t.balance_offset = tol::kBalanceOffset * length;
  t.reach_slack = tol::kReachSlack * length;
  t.energy_margin = tol::kEnergyErrorMargin * params.tolerance * mass * g * length;
  t.dt = params.dt > 0 ? params.dt : (adaptive ? tol::kAdaptiveMaxStep : tol::kPaperStep) * t.time_scale;
  t.first_step = tol::kFirstStep * t.time_scale;
  t.flight_max_step = tol::kAdaptiveMaxStep * t.time_scale;
  t.frictional_time = tol::kFrictionalTime * t.time_scale;
  t.rebound_window = adaptive ? tol::kReboundWindow * t.time_scale : t.dt;
  double fall_time = (std::sqrt(params.drop_speed * params.drop_speed + 2 * g * params.drop_height)) / g;
  if (uses_impacts(params) || params.velocity != Vec3::Zero()) {
    // A toss rises first, and its bounces take at most (1 + E)/(1 − E) times its first fall.
    const double up = params.velocity.z() - params.drop_speed;
    const double bounces =
        std::min(tol::kMaxBounceFactor,
                 (1 + params.restitution) / std::max(tol::kMinOneMinusE, 1 - params.restitution));
    fall_time = (std::abs(up) + std::sqrt(up * up + 2 * g * params.drop_height)) / g * bounces;
  }
  t.max_time = params.max_time > 0 ? params.max_time : tol::kMaxTime * t.time_scale + fall_time;
  return t;
}

}  // namespace repose::sim
