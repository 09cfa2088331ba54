#include "repose/model/params.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "repose/error.hpp"

namespace repose {

double standard_gravity(UnitSystem units) { return units == UnitSystem::si ? 9.81 : 981.0; }

namespace {
void require(bool ok, const char* name, double value, const char* what) {
  if (ok) return;
  char shown[32];
  std::snprintf(shown, sizeof shown, "%.10g", value);
  throw Error(std::string("parameter ") + name + " must be " + what + ", got " + shown);
}
}  // namespace

const char* to_string(Integrator integrator) {
  return integrator == Integrator::adaptive ? "adaptive" : "paper";
}

Integrator parse_integrator(const std::string& name) {
  if (name == "adaptive") return Integrator::adaptive;
  if (name == "paper") return Integrator::paper;
  throw Error("unknown integrator '" + name + "' (expected paper or adaptive)");
}

bool uses_impacts(const SettleParams& p) {
  return p.restitution > 0 || p.spin != Vec3::Zero() || p.velocity.x() != 0 || p.velocity.y() != 0;
}

void validate(const SettleParams& p) {
  require(std::isfinite(p.gravity) && p.gravity > 0, "gravity", p.gravity, "a finite positive number");
  require(std::isfinite(p.damping) && p.damping >= 0, "damping", p.damping, "a finite number >= 0");
  require(std::isfinite(p.dt) && p.dt >= 0, "dt", p.dt, "a finite positive number (or 0 for automatic)");
  require(std::isfinite(p.contact_threshold) && p.contact_threshold > 0 && p.contact_threshold < 1,
          "contact-threshold", p.contact_threshold, "a fraction of L in (0, 1)");
  require(std::isfinite(p.line_threshold) && p.line_threshold > 0, "line-threshold", p.line_threshold,
          "a finite positive fraction of L^2");
  require(std::isfinite(p.drop_height) && p.drop_height >= 0, "drop-height", p.drop_height,
          "a finite number >= 0");
  require(std::isfinite(p.drop_speed) && p.drop_speed >= 0, "drop-speed", p.drop_speed,
          "a finite number >= 0");
  for (int i = 0; i < 3; ++i) {
    require(std::isfinite(p.velocity[i]), "velocity", p.velocity[i], "finite in every component");
    require(std::isfinite(p.spin[i]), "spin", p.spin[i], "finite in every component");
  }
  if (p.drop_speed != 0 && p.velocity.z() != 0)
    throw Error("give the initial downward speed once: --drop-speed or the z of --velocity, not both");
  require(std::isfinite(p.restitution) && p.restitution >= 0 && p.restitution <= 1, "restitution",
          p.restitution, "in [0, 1]");
  require(!std::isnan(p.friction) && p.friction >= 0, "friction", p.friction, "a number >= 0 (or inf)");
  require(std::isfinite(p.max_time) && p.max_time >= 0, "max-time", p.max_time,
          "a finite positive number (or 0 for automatic)");
  require(p.max_steps > 0, "max-steps", static_cast<double>(p.max_steps), "positive");
  require(std::isfinite(p.quaternion_tolerance) && p.quaternion_tolerance > 0, "quaternion-tolerance",
          p.quaternion_tolerance, "a finite positive number");
  require(std::isfinite(p.tolerance) && p.tolerance >= 1e-14 && p.tolerance <= 1e-3, "tolerance", p.tolerance,
          "in [1e-14, 1e-3]");
  require(p.max_iterations > 0, "max-iterations", p.max_iterations, "positive");
}

}  // namespace repose
