#include "repose/model/scenario.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "repose/error.hpp"
#include "repose/geometry/shapes.hpp"
#include "repose/model/orientation.hpp"

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
  static const std::set<std::string> known = {
      "name",        "description",       "note",     "particle",          "density",        "units",
      "orientation", "damping",           "dt",       "contact_threshold", "line_threshold", "drop_height",
      "drop_speed",  "max_time",          "smooth",   "integrator",        "tolerance",      "velocity",
      "spin",        "restitution",       "friction", "mesh_units",        "scale",          "inertia",
      "repair",      "largest_component", "com"};
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
  p.damping = number(j, "damping", p.damping, origin);
  p.dt = number(j, "dt", p.dt, origin);
  p.tolerance = number(j, "tolerance", p.tolerance, origin);
  try {
    p.integrator = parse_integrator(text(j, "integrator", to_string(p.integrator), origin));
  } catch (const Error& e) {
    throw Error(origin + ": " + e.what());
  }
  p.contact_threshold = number(j, "contact_threshold", p.contact_threshold, origin);
  p.line_threshold = number(j, "line_threshold", p.line_threshold, origin);
  p.drop_height = number(j, "drop_height", p.drop_height, origin);
  p.drop_speed = number(j, "drop_speed", p.drop_speed, origin);
  p.max_time = number(j, "max_time", p.max_time, origin);
  p.velocity = vector3(j, "velocity", p.velocity, origin);
  p.spin = vector3(j, "spin", p.spin, origin);
  p.restitution = number(j, "restitution", p.restitution, origin);
  p.friction = number(j, "friction", p.friction, origin);  // absent: no slip
  const std::string smooth = text(j, "smooth", "auto", origin);
  if (smooth != "auto" && smooth != "on" && smooth != "off")
    throw Error(origin + ": smooth must be \"auto\", \"on\" or \"off\", got \"" + smooth + "\"");
  p.smooth = smooth == "on" ? SmoothMode::on : smooth == "off" ? SmoothMode::off : SmoothMode::automatic;
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
