// The options `info`, `settle` and `poses` share for how a mesh file becomes a particle: its units or scale,
// the inertia model, repair.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "format.hpp"
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
