// A parameter's value as JSON, for the echoes and files written from the parameter table (report.cpp,
// study_settings.cpp). Internal to the library: nlohmann is not part of its interface.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>

#include "repose/model/param_table.hpp"

namespace repose {

/// A number (null for infinity, which JSON lacks: friction's no slip), a whole number, [x, y, z] or the
/// choice's name.
inline nlohmann::json param_json(const ParamInfo& info, const SettleParams& p) {
  using nlohmann::json;
  return std::visit(
      Overloaded{[&](double SettleParams::*m) { return std::isinf(p.*m) ? json(nullptr) : json(p.*m); },
                 [&](long SettleParams::*m) { return json(p.*m); },
                 [&](int SettleParams::*m) { return json(p.*m); },
                 [&](Vec3 SettleParams::*m) {
                   const Vec3& v = p.*m;
                   return json{v.x(), v.y(), v.z()};
                 },
                 [&](const ParamChoice& c) { return json(c.get(p)); }},
      info.member);
}

/// The units of a result's numbers, written beside them so that a file says what its numbers mean.
inline nlohmann::json units_json(const UnitNames& u) {
  return {{"system", u.system},
          {"length", u.length},
          {"mass", u.mass},
          {"time", u.time},
          {"energy", u.energy},
          {"speed", u.speed},
          {"angular_speed", u.angular_speed},
          {"inertia", u.inertia},
          {"damping", u.damping}};
}

}  // namespace repose
