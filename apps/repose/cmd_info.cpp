// repose info MESH|SHAPE: geometry, mass properties and validation report of a particle.
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "format.hpp"
#include "mesh_options.hpp"
#include "repose/io/mesh_io.hpp"
#include "repose/model/particle.hpp"
#include "repose/output/files.hpp"
#include "repose/output/report.hpp"

namespace repose::cli {

namespace {

struct InfoOptions {
  std::string source;
  double density = 1.0;
  std::string units = "si";
  MeshCliOptions mesh;
  bool json = false;
  std::string write_stl;
};

nlohmann::json info_json(const Particle& p, double density, const UnitNames& u) {
  const Aabb box{p.bounds.min + p.input_offset, p.bounds.max + p.input_offset};
  nlohmann::json j;
  j["source"] = p.name;
  j["density"] = density;
  j["inertia_model"] = to_string(p.options.inertia);
  j["scale"] = p.options.scale;
  j["length_unit"] = u.length;
  j["units"] = {{"system", u.system},
                {"length", u.length},
                {"mass", u.mass},
                {"area", u.area},
                {"volume", u.volume},
                {"inertia", u.inertia},
                {"density", p.options.inertia == InertiaModel::shell ? u.area_density : u.density}};
  j["surface_is_hull"] = p.surface_is_hull;
  j["vertices"] = p.mesh.vertices.size();
  j["triangles"] = p.mesh.triangles.size();
  j["volume"] = p.mass.volume;
  j["area"] = p.mass.area;
  j["mass"] = p.mass.mass;
  j["center_of_mass"] = to_json(p.input_offset);
  j["inertia"] = to_json(p.mass.inertia);
  j["principal_moments"] = to_json(p.mass.principal_moments);
  j["principal_axes"] = to_json(Mat3(p.mass.principal_axes.transpose()));  // one row per axis
  j["bounding_box"] = {{"min", to_json(box.min)}, {"max", to_json(box.max)}};
  j["characteristic_length"] = p.length;
  j["hull"] = {{"vertices", p.hull.vertices.size()}, {"faces", p.hull.faces.size()}};
  j["file"] = nlohmann::json::parse(file_report_json(p.report));
  if (p.repair) j["repair"] = nlohmann::json::parse(repair_report_json(*p.repair));
  j["warnings"] = p.report.warnings;
  return j;
}

void print_info(const Particle& p, double density, bool density_given, const UnitNames& u) {
  const std::string unit = u.length, m = std::string(" ") + u.length;
  const Aabb box{p.bounds.min + p.input_offset, p.bounds.max + p.input_offset};
  const Mat3 axes = p.mass.principal_axes;
  const bool shell = p.options.inertia == InertiaModel::shell;
  std::cout << "particle            " << p.name << "\n";
  if (p.options.scale != 1) std::cout << "scale               " << num(p.options.scale) << "\n";
  std::cout << "length unit         " << unit
            << (p.options.scale == 1
                    ? " (the coordinates as given; --mesh-units converts a file in mm, cm or in)"
                    : "")
            << "\n";
  std::cout << "surface             " << p.mesh.vertices.size() << " vertices, " << p.mesh.triangles.size()
            << " triangles" << (p.surface_is_hull ? " (the convex hull of the file's points)" : "") << "\n"
            << "inertia model       " << to_string(p.options.inertia)
            << (shell                                       ? " (mass on the surface)"
                : p.options.inertia == InertiaModel::convex ? " (the solid convex hull)"
                                                            : " (the closed solid)")
            << "\n"
            << "density             " << num(density) << " " << (shell ? u.area_density : u.density)
            << (density_given ? ""
                              : " (the default; --density sets it: it scales mass, inertia and energies, "
                                "not rest poses)")
            << "\n";
  std::cout << "surface area        " << num(p.mass.area) << " " << u.area << "\n";
  if (!shell) std::cout << "volume              " << num(p.mass.volume) << " " << u.volume << "\n";
  std::cout << "mass                " << num(p.mass.mass) << " " << u.mass << "\n"
            << "centre of mass      " << vec(p.input_offset) << m
            << (p.options.center_of_mass ? " (given, --com; inertia: the model's about it)" : "") << "\n"
            << "inertia about COM   " << vec(p.mass.inertia.row(0)) << " " << u.inertia << "\n"
            << "                    " << vec(p.mass.inertia.row(1)) << "\n"
            << "                    " << vec(p.mass.inertia.row(2)) << "\n"
            << "principal moments   " << vec(p.mass.principal_moments) << " " << u.inertia << "\n"
            << "principal axes      " << vec(axes.col(0)) << "\n"
            << "                    " << vec(axes.col(1)) << "\n"
            << "                    " << vec(axes.col(2)) << "\n"
            << "bounding box        " << vec(box.min) << " .. " << vec(box.max) << m << "\n"
            << "characteristic L    " << num(p.length) << m << " (volume-equivalent sphere diameter"
            << (p.options.inertia == InertiaModel::exact ? "" : " of the convex hull") << ")\n"
            << "convex hull         " << p.hull.vertices.size() << " vertices, " << p.hull.faces.size()
            << " planar faces\n";
  if (p.repair) {
    const RepairReport& r = *p.repair;
    std::cout << "repair              " << r.holes_filled << " holes filled (" << num(100 * r.area_added)
              << " % of the area added), " << r.flipped_faces << " faces flipped, " << r.stitched_edges
              << " edges stitched, " << r.duplicate_faces << " duplicate and " << r.degenerate_faces
              << " degenerate faces removed, components " << r.input_components << " -> " << r.kept_components
              << ", volume change " << num(100 * r.volume_change) << " %\n";
    for (const std::string& n : r.notes) std::cout << "repaired            " << n << "\n";
  }
  for (const std::string& w : p.report.warnings) std::cout << "warning             " << w << "\n";
}

}  // namespace

Command add_info_command(CLI::App& app) {
  auto opts = std::make_shared<InfoOptions>();
  CLI::App* sub = app.add_subcommand("info", "Mass properties, hull and validation report of a particle");
  sub->add_option("particle", opts->source,
                  "Mesh file (STL, OBJ, PLY, OFF; XYZ point cloud) or shape spec, e.g. box:x=1,y=2,z=3")
      ->required();
  sub->add_option("--density", opts->density,
                  "Density, mass per unit volume (per unit area with --inertia shell; default 1)");
  sub->add_option("--units", opts->units,
                  "si (m) or cgs (cm): the unit --mesh-units converts to (default si)")
      ->check(CLI::IsMember({"si", "cgs"}));
  add_mesh_options(*sub, opts->mesh);
  sub->add_flag("--json", opts->json, "Print JSON instead of text");
  sub->add_option("--write-stl", opts->write_stl,
                  "Also write the validated surface as binary STL (input frame)");
  return {sub, [opts, sub]() {
            check_positive("--density", opts->density);
            if (!opts->write_stl.empty()) {
              // An STL beside others is not a run's output directory: it is not created.
              const std::filesystem::path parent = std::filesystem::path(opts->write_stl).parent_path();
              if (!parent.empty() && !std::filesystem::is_directory(parent))
                throw Error(opts->write_stl + ": cannot write: " + parent.string() + " is not a directory");
              ensure_output_file(opts->write_stl);
            }
            const Particle p =
                load_particle(opts->source, opts->density, opts->mesh.resolve(opts->units == "cgs"));
            if (!opts->write_stl.empty()) {
              TriangleMesh out = p.mesh;
              for (Vec3& v : out.vertices) v += p.input_offset;
              write_stl(out, opts->write_stl);
            }
            // Lengths are read in the run's unit (m, or cm with --units cgs): --mesh-units converts to it,
            // and without it (or with --scale) the coordinates are taken to be in it.
            const UnitSystem units = opts->units == "cgs" ? UnitSystem::cgs : UnitSystem::si;
            warn_implausible_size(p, units);
            if (opts->json)
              std::cout << info_json(p, opts->density, unit_names(units)).dump(2) << "\n";
            else
              print_info(p, opts->density, sub->count("--density") > 0, unit_names(units));
            return 0;
          }};
}

}  // namespace repose::cli
