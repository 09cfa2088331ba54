// libFuzzer harness for the scenario-file reader (parse_scenario: JSON text).
//
// Oracle: the text is rejected with repose::Error, or it gives a scenario with a finite positive density, a
// finite unit orientation quaternion and parameters that pass validate(), and whose every field is the one
// the text gives (read here with nlohmann::json directly) or, when absent, the documented default
// (include/repose/model/scenario.hpp): numbers bit for bit, gravity 9.81 for "si" and 981 for "cgs", the
// orientation exactly parse_orientation of the spec, a relative mesh path resolved against "fuzz/". A field
// stored in the wrong member, or a default that drifts, is caught. The particle is not loaded (the
// shape-spec and mesh harnesses cover that); its mesh options are checked like the other fields.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>

#include "repose/error.hpp"
#include "repose/model/orientation.hpp"
#include "repose/model/params.hpp"
#include "repose/model/scenario.hpp"

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The scenario's fields against the text, read independently.
void require_fields_match(const repose::Scenario& s, const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text);
  const auto str = [&](const char* key, const char* fallback) {
    return j.contains(key) ? j[key].get<std::string>() : std::string(fallback);
  };
  const repose::SettleParams defaults;
  const auto num = [&](const char* key, double fallback) {
    return j.contains(key) ? j[key].get<double>() : fallback;
  };
  require(s.name == str("name", "scenario") && s.description == str("description", ""));
  require(s.note == str("note", ""));
  const std::string particle = j.at("particle").get<std::string>();
  require(s.particle == particle || s.particle == "fuzz/" + particle);
  require(same(s.density, num("density", 1.0)));
  const std::string units = str("units", "si");
  require((units == "si" && s.units == repose::UnitSystem::si && same(s.params.gravity, 9.81)) ||
          (units == "cgs" && s.units == repose::UnitSystem::cgs && same(s.params.gravity, 981.0)));
  require(s.orientation_spec == str("orientation", "identity"));
  const repose::Quat q = repose::parse_orientation(s.orientation_spec);
  require(same(s.orientation.w(), q.w()) && same(s.orientation.x(), q.x()) &&
          same(s.orientation.y(), q.y()) && same(s.orientation.z(), q.z()));
  const repose::SettleParams& p = s.params;
  require(same(p.damping, num("damping", defaults.damping)) && same(p.dt, num("dt", defaults.dt)));
  require(same(p.contact_threshold, num("contact_threshold", defaults.contact_threshold)));
  require(same(p.line_threshold, num("line_threshold", defaults.line_threshold)));
  require(same(p.drop_height, num("drop_height", defaults.drop_height)));
  require(same(p.drop_speed, num("drop_speed", defaults.drop_speed)));
  require(same(p.max_time, num("max_time", defaults.max_time)));
  const std::string smooth = str("smooth", "auto");
  require((smooth == "auto" && p.smooth == repose::SmoothMode::automatic) ||
          (smooth == "on" && p.smooth == repose::SmoothMode::on) ||
          (smooth == "off" && p.smooth == repose::SmoothMode::off));
  // The mesh fields: the unit's factor for the run's units (mm 1e-3 m or 0.1 cm, …), else the scale.
  const std::string mesh_units = str("mesh_units", "");
  require(s.mesh_units == mesh_units);
  const double per_metre = units == "cgs" ? 100.0 : 1.0;
  const double unit_factor = mesh_units == "mm"   ? 1e-3 * per_metre
                             : mesh_units == "cm" ? 1e-2 * per_metre
                             : mesh_units == "m"  ? per_metre
                                                  : 0.0254 * per_metre;
  require(same(s.mesh.scale, mesh_units.empty() ? num("scale", 1.0) : unit_factor));
  require(s.mesh.scale > 0 && std::isfinite(s.mesh.scale));
  require(std::string(repose::to_string(s.mesh.inertia)) == str("inertia", "exact"));
  require(s.mesh.repair == j.value("repair", false));
  require(s.mesh.largest_component == j.value("largest_component", false));
  require(s.mesh.center_of_mass.has_value() == j.contains("com"));
  if (j.contains("com"))
    for (int k = 0; k < 3; ++k) require(same((*s.mesh.center_of_mass)[k], j["com"][k].get<double>()));
  // Not settable from a scenario: must keep their defaults.
  require(p.max_steps == defaults.max_steps && same(p.quaternion_tolerance, defaults.quaternion_tolerance));
  require(p.max_iterations == defaults.max_iterations);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  repose::Scenario s;
  try {
    // A fixed origin: relative mesh paths resolve against its directory, and nothing is read from disk.
    s = repose::parse_scenario(text, "fuzz/scenario.json");
  } catch (const repose::Error&) {
    return 0;
  } catch (...) {
    __builtin_trap();
  }
  require(std::isfinite(s.density) && s.density > 0);
  require(s.orientation.coeffs().allFinite() && std::abs(s.orientation.norm() - 1.0) < 1e-12);
  require(!s.particle.empty());
  try {
    repose::validate(s.params);
    require_fields_match(s, text);
  } catch (...) {
    __builtin_trap();
  }
  return 0;
}
