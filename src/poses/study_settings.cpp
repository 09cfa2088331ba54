#include "study_settings.hpp"

#include <cmath>

#include "repose/error.hpp"
#include "repose/sim/settle.hpp"

namespace repose {

namespace {

using nlohmann::json;

const char* smooth_mode_name(SmoothMode mode) {
  return mode == SmoothMode::on ? "on" : mode == SmoothMode::off ? "off" : "auto";
}

SmoothMode parse_smooth_mode(const std::string& s) {
  if (s == "on") return SmoothMode::on;
  if (s == "off") return SmoothMode::off;
  if (s == "auto") return SmoothMode::automatic;
  throw Error("unknown smooth mode '" + s + "'");
}

}  // namespace

json settings_json(const PosesStudy& s) {
  const SettleParams& p = s.params;
  return {{"gravity", p.gravity},
          {"damping", p.damping},
          {"integrator", to_string(p.integrator)},
          {"dt", p.dt},
          {"tolerance", p.tolerance},
          {"contact_threshold", p.contact_threshold},
          {"line_threshold", p.line_threshold},
          {"smooth_mode", smooth_mode_name(p.smooth)},
          {"drop_height", p.drop_height},
          {"drop_speed", p.drop_speed},
          {"restitution", p.restitution},
          {"friction", std::isinf(p.friction) ? json(nullptr) : json(p.friction)},  // null: no slip
          {"velocity_max", s.toss.velocity_max},
          {"spin_max", s.toss.spin_max},
          {"max_time", p.max_time},
          {"max_steps", p.max_steps},
          {"decide_early", s.decide_early},
          {"persistence", s.catalog.persistence}};
}

void read_settings(const json& set, PosesStudy& s, const std::string& name) {
  SettleParams& p = s.params;
  p.gravity = set.at("gravity").get<double>();
  p.damping = set.at("damping").get<double>();
  p.dt = set.at("dt").get<double>();
  // Files written before the adaptive integrator existed were computed with the paper's.
  p.integrator = parse_integrator(set.value("integrator", std::string("paper")));
  p.tolerance = set.value("tolerance", p.tolerance);
  p.contact_threshold = set.at("contact_threshold").get<double>();
  p.line_threshold = set.at("line_threshold").get<double>();
  p.smooth = parse_smooth_mode(set.at("smooth_mode").get<std::string>());
  p.drop_height = set.at("drop_height").get<double>();
  p.drop_speed = set.at("drop_speed").get<double>();
  // Files written before tosses existed: drops from rest, no rebound.
  p.restitution = set.value("restitution", 0.0);
  p.friction =
      set.contains("friction") && !set.at("friction").is_null() ? set.at("friction").get<double>() : INFINITY;
  s.toss.velocity_max = set.value("velocity_max", 0.0);
  s.toss.spin_max = set.value("spin_max", 0.0);
  p.max_time = set.at("max_time").get<double>();
  // An integer, checked first: nlohmann converts a floating-point value with a plain cast, undefined
  // behaviour when it does not fit.
  if (!set.at("max_steps").is_number_integer())
    throw Error(name + ": malformed poses result file (expected an integer)");
  p.max_steps = set.at("max_steps").get<long>();
  s.decide_early = set.at("decide_early").get<bool>();
  s.catalog.persistence = set.at("persistence").get<double>();
}

}  // namespace repose
