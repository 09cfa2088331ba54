// Scenario files: a named, reproducible settling setup (particle, density, units, orientation, parameters),
// in JSON. The paper's cases live in scenarios/paper/ and are shared by `repose settle --scenario`,
// `repose paper`, the tests and the benchmarks, so each case has exactly one definition.
//
// Fields (only "particle" is required; unknown fields are an error, so a typo never goes unnoticed):
//   name, description        strings
//   particle                 mesh file (relative to the scenario file) or shape spec
//   density                  mass / length³ (default 1)
//   units                    "si" | "cgs" (default "si"): sets gravity 9.81 m/s² or 981 cm/s²
//   orientation              orientation spec, e.g. "axis-angle:1,0,0,1.106" (default "identity")
//   the parameters           each entry of param_table.hpp marked in_scenario, under its name: numbers
//                            (damping, dt, ..., friction), [x, y, z] (velocity, spin: a toss) or names
//                            (integrator, smooth); absent: the default (friction: no slip)
//   mesh_units | scale       the mesh file's length unit ("mm" | "cm" | "m" | "in", converted to the run's
//                            units) or a factor on every coordinate (default 1); not both
//   inertia                  "exact" | "convex" | "shell" (default "exact")
//   repair, largest_component  booleans (default false)
//   com                      [x, y, z]: the centre of mass in the mesh file's coordinates, when known
//   note                     free text: why this input was chosen (shown in the reproduction report)
#pragma once

#include <string>

#include "repose/geometry/types.hpp"
#include "repose/model/params.hpp"
#include "repose/model/particle.hpp"

namespace repose {

struct Scenario {
  std::string name;
  std::string description;
  std::string note;
  std::string particle;  ///< shape spec, or mesh path resolved against the scenario's directory
  double density = 1.0;
  UnitSystem units = UnitSystem::si;
  std::string orientation_spec = "identity";
  Quat orientation = Quat::Identity();
  SettleParams params;  ///< gravity set from `units`
  /// How the mesh file becomes a particle; with `mesh_units`, mesh.scale is its factor for `units`.
  MeshOptions mesh;
  std::string mesh_units;  ///< "mm", "cm", "m" or "in"; empty: mesh.scale is the file's "scale"
};

/// Parses scenario JSON text; `origin` names it in errors and its directory resolves relative mesh paths.
/// Throws repose::Error ("ORIGIN: problem") for malformed JSON, a missing or mistyped field, an unknown
/// field, or an invalid value.
Scenario parse_scenario(const std::string& json_text, const std::string& origin);

/// Reads and parses a scenario file.
Scenario load_scenario(const std::string& path);

}  // namespace repose
