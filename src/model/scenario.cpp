#include "repose/model/scenario.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "repose/error.hpp"
#include "repose/geometry/shapes.hpp"
#include "repose/model/orientation.hpp"
#include "repose/model/param_table.hpp"

namespace repose {

namespace {

using nlohmann::json;

double number(const json& j, const char* key, double fallback, const std::string& origin) {
  if (!j.contains(key)) return fallback;
  if (!j[key].is_number()) throw Error(origin + ": field '" + key + "' must be a number");
  return j[key].get<double>();
}

Vec3 vector3(const json& j, const char* key, const Vec3& fallback, const std::string& origin) {
  if (!j.contains(key)) return fallback;
  const json& a = j[key];
  if (!a.is_array() || a.size() != 3 || !a[0].is_number() || !a[1].is_number() || !a[2].is_number())
    throw Error(origin + ": field '" + key + "' must be an array of three numbers [x, y, z]");
  return Vec3(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
}

std::string text(const json& j, const char* key, const std::string& fallback, const std::string& origin) {
  if (!j.contains(key)) return fallback;
  if (!j[key].is_string()) throw Error(origin + ": field '" + key + "' must be a string");
  return j[key].get<std::string>();
}

// A whole number that fits Int, checked before nlohmann's plain cast (max_steps is no scenario key, but a
// whole-number parameter may become one).
template <class Int>
Int whole_number(const json& j, const char* key, const std::string& origin) {
  const json& v = j[key];
  if (!v.is_number_integer() || v.get<double>() < static_cast<double>(std::numeric_limits<Int>::min()) ||
      v.get<double>() > static_cast<double>(std::numeric_limits<Int>::max()))
    throw Error(origin + ": field '" + key + "' must be a whole number");
  return v.get<Int>();
}

bool boolean(const json& j, const char* key, const std::string& origin) {
  if (!j.contains(key)) return false;
  if (!j[key].is_boolean()) throw Error(origin + ": field '" + key + "' must be true or false");
  return j[key].get<bool>();
}

// The mesh fields: how the particle's mesh file is read (as the CLI's mesh options).
MeshOptions mesh_options(const json& j, const Scenario& s, const std::string& origin) {
  MeshOptions m;
  if (j.contains("mesh_units") && j.contains("scale"))
    throw Error(origin + ": give 'mesh_units' or 'scale', not both");
  m.scale = number(j, "scale", 1.0, origin);
  if (!(m.scale > 0) || !std::isfinite(m.scale))
    throw Error(origin + ": scale must be a finite positive number");
  try {
    if (!s.mesh_units.empty()) m.scale = mesh_unit_scale(s.mesh_units, s.units == UnitSystem::cgs);
    m.inertia = parse_inertia_model(text(j, "inertia", "exact", origin));
  } catch (const Error& e) {
    throw Error(origin + ": " + e.what());
  }
  m.repair = boolean(j, "repair", origin);
  m.largest_component = boolean(j, "largest_component", origin);
  if (j.contains("com")) m.center_of_mass = vector3(j, "com", Vec3::Zero(), origin);
  return m;
}

// The parameter `info` from its key, which `j` has: a number, [x, y, z] or a choice's name.
void read_param(const json& j, const ParamInfo& info, SettleParams& p, const std::string& origin) {
  std::visit(Overloaded{[&](double SettleParams::*m) { p.*m = number(j, info.name, p.*m, origin); },
                        [&](long SettleParams::*m) { p.*m = whole_number<long>(j, info.name, origin); },
                        [&](int SettleParams::*m) { p.*m = whole_number<int>(j, info.name, origin); },
                        [&](Vec3 SettleParams::*m) { p.*m = vector3(j, info.name, p.*m, origin); },
                        [&](const ParamChoice& c) {
                          const std::string name = text(j, info.name, "", origin);
                          try {
                            c.set(p, name);
                          } catch (const Error& e) {
                            throw Error(origin + ": " + e.what());
                          }
                        }},
             info.member);
}

}  // namespace

Scenario parse_scenario(const std::string& json_text, const std::string& origin) {
  json j;
  try {
    j = json::parse(json_text);
  } catch (const json::exception& e) {
    // Not only parse_error: a number too large for a double throws out_of_range (found by fuzz_scenario).
    throw Error(origin + ": invalid JSON: " + e.what());
  }
  if (!j.is_object()) throw Error(origin + ": a scenario must be a JSON object");
  // The scenario's own fields, then the parameters' (param_table.cpp).
  static const std::set<std::string> known = [] {
    std::set<std::string> keys = {"name",   "description",       "note",       "particle", "density",
                                  "units",  "orientation",       "mesh_units", "scale",    "inertia",
                                  "repair", "largest_component", "com"};
    for (const ParamInfo& info : param_table())
      if (info.uses & in_scenario) keys.insert(info.name);
    return keys;
  }();
  for (const auto& [key, value] : j.items())
    if (!known.count(key)) throw Error(origin + ": unknown field '" + key + "'");
  if (!j.contains("particle")) throw Error(origin + ": missing field 'particle'");

  Scenario s;
  s.name = text(j, "name", std::filesystem::path(origin).stem().string(), origin);
  s.description = text(j, "description", "", origin);
  s.note = text(j, "note", "", origin);
  s.particle = text(j, "particle", "", origin);
  if (!is_shape_spec(s.particle) && std::filesystem::path(s.particle).is_relative())
    s.particle = (std::filesystem::path(origin).parent_path() / s.particle).string();
  s.density = number(j, "density", 1.0, origin);
  const std::string units = text(j, "units", "si", origin);
  if (units != "si" && units != "cgs")
    throw Error(origin + ": units must be \"si\" or \"cgs\", got \"" + units + "\"");
  s.units = units == "cgs" ? UnitSystem::cgs : UnitSystem::si;
  s.mesh_units = text(j, "mesh_units", "", origin);
  if (j.contains("mesh_units") && s.mesh_units.empty())
    throw Error(origin + ": mesh_units must be mm, cm, m or in, got \"\"");
  s.mesh = mesh_options(j, s, origin);
  s.orientation_spec = text(j, "orientation", "identity", origin);
  try {
    s.orientation = parse_orientation(s.orientation_spec);
  } catch (const Error& e) {
    throw Error(origin + ": " + e.what());
  }

  SettleParams& p = s.params;
  p.gravity = standard_gravity(s.units);
  for (const ParamInfo& info : param_table())  // absent: the default (friction: no slip)
    if ((info.uses & in_scenario) && j.contains(info.name)) read_param(j, info, p, origin);
  if (!(s.density > 0) || !std::isfinite(s.density))
    throw Error(origin + ": density must be a finite positive number");
  try {
    validate(p);
  } catch (const Error& e) {
    throw Error(origin + ": " + e.what());
  }
  return s;
}

Scenario load_scenario(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open scenario file");
  std::stringstream ss;
  ss << in.rdbuf();
  // A scenario is a few hundred bytes; refuse anything absurd before parsing it.
  if (ss.str().size() > (1u << 20)) throw Error(path + ": scenario file larger than 1 MiB");
  return parse_scenario(ss.str(), path);
}

}  // namespace repose
