// The options `info`, `settle` and `poses` share for how a mesh file becomes a particle: its units or scale,
// the inertia model, repair.
#pragma once

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "format.hpp"
#include "repose/model/params.hpp"
#include "repose/model/particle.hpp"

namespace repose::cli {

struct MeshCliOptions {
  double scale = 1;
  std::string mesh_units;  ///< empty: none given
  std::string inertia = "exact";
  bool repair = false;
  bool largest_component = false;
  std::string com;  ///< --com X,Y,Z; empty: none given

  /// The library's options; `cgs`: lengths of the run are centimetres (--units cgs), so --mesh-units
  /// converts to them.
  MeshOptions resolve(bool cgs) const {
    MeshOptions m;
    m.scale = mesh_units.empty() ? scale : mesh_unit_scale(mesh_units, cgs);
    m.inertia = parse_inertia_model(inertia);
    m.repair = repair;
    m.largest_component = largest_component;
    if (!com.empty()) m.center_of_mass = parse_vector("--com", com);
    return m;
  }
};

/// The sizes a particle's characteristic length L is expected within, in metres: from a fine powder grain to
/// a boulder. Outside, the file's unit was most likely not the run's (a part in mm read as m is 1000x).
inline constexpr double kPlausibleLengthMin = 1e-6, kPlausibleLengthMax = 10;

/// One line on stderr if `length` (a particle's L, in the run's unit) is outside the plausible range, naming
/// --mesh-units. Only a warning: nothing forbids simulating a 20 m block.
inline void warn_implausible_size(const std::string& name, double length, UnitSystem units) {
  const double metres = units == UnitSystem::cgs ? length / 100 : length;
  if (metres >= kPlausibleLengthMin && metres <= kPlausibleLengthMax) return;
  const char* unit = unit_names(units).length;
  std::cerr << "repose: warning: " << name << ": L = " << num(length) << " " << unit << " is "
            << (metres > kPlausibleLengthMax ? "larger than 10 m" : "smaller than 1 µm")
            << "; if the file is not in " << (units == UnitSystem::cgs ? "centimetres" : "metres")
            << ", give --mesh-units mm|cm|m|in (or --scale)\n";
}

inline void warn_implausible_size(const Particle& p, UnitSystem units) {
  warn_implausible_size(p.name, p.length, units);
}

/// Registers --scale, --mesh-units, --inertia, --repair and --largest-component on `sub`.
inline void add_mesh_options(CLI::App& sub, MeshCliOptions& o) {
  CLI::Option* scale =
      sub.add_option("--scale", o.scale,
                     "Multiply every mesh coordinate by this before anything else (default 1)")
          ->check(CLI::PositiveNumber);
  sub.add_option("--mesh-units", o.mesh_units,
                 "The mesh file's length unit: mm | cm | m | in, converted to the run's (m, or cm with "
                 "--units cgs)")
      ->check(CLI::IsMember({"mm", "cm", "m", "in"}))
      ->excludes(scale);
  sub.add_option("--inertia", o.inertia,
                 "Mass properties: exact (the closed solid; default) | convex (the solid convex hull: any "
                 "triangle soup or point cloud) | shell (mass on the surface, --density per unit area)")
      ->check(CLI::IsMember({"exact", "convex", "shell"}));
  sub.add_flag("--repair", o.repair,
               "Repair the surface first: stitch borders, fix winding, remove duplicate and degenerate "
               "faces, fill holes (CGAL)");
  sub.add_flag("--largest-component", o.largest_component,
               "Keep only the largest connected component (repairs as --repair does)");
  sub.add_option("--com", o.com,
                 "X,Y,Z: the centre of mass in the mesh file's coordinates, when known (a weighted or hollow "
                 "part); the inertia is then the uniform model's about that point");
}

}  // namespace repose::cli
