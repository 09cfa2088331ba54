// repose info MESH|SHAPE: geometry, mass properties and validation report of a particle.
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "format.hpp"
#include "repose/io/mesh_io.hpp"
#include "repose/model/particle.hpp"

namespace repose::cli {

namespace {

struct InfoOptions {
  std::string source;
  double density = 1.0;
  bool json = false;
  std::string write_stl;
};

nlohmann::json info_json(const Particle& p, double density) {
  const Aabb box{p.bounds.min + p.input_offset, p.bounds.max + p.input_offset};
  nlohmann::json j;
  j["source"] = p.name;
  j["density"] = density;
  j["vertices"] = p.mesh.vertices.size();
  j["triangles"] = p.mesh.triangles.size();
  j["volume"] = p.mass.volume;
  j["mass"] = p.mass.mass;
  j["center_of_mass"] = to_json(p.input_offset);
  j["inertia"] = to_json(p.mass.inertia);
  j["principal_moments"] = to_json(p.mass.principal_moments);
  j["principal_axes"] = to_json(Mat3(p.mass.principal_axes.transpose()));  // one row per axis
  j["bounding_box"] = {{"min", to_json(box.min)}, {"max", to_json(box.max)}};
  j["characteristic_length"] = p.length;
  j["hull"] = {{"vertices", p.hull.vertices.size()}, {"faces", p.hull.faces.size()}};
  j["warnings"] = p.report.warnings;
  return j;
}

void print_info(const Particle& p, double density) {
  const Aabb box{p.bounds.min + p.input_offset, p.bounds.max + p.input_offset};
  const Mat3 axes = p.mass.principal_axes;
  std::cout << "particle            " << p.name << "\n"
            << "surface             " << p.mesh.vertices.size() << " vertices, " << p.mesh.triangles.size()
            << " triangles\n"
            << "density             " << num(density) << "\n"
            << "volume              " << num(p.mass.volume) << "\n"
            << "mass                " << num(p.mass.mass) << "\n"
            << "centre of mass      " << vec(p.input_offset) << "\n"
            << "inertia about COM   " << vec(p.mass.inertia.row(0)) << "\n"
            << "                    " << vec(p.mass.inertia.row(1)) << "\n"
            << "                    " << vec(p.mass.inertia.row(2)) << "\n"
            << "principal moments   " << vec(p.mass.principal_moments) << "\n"
            << "principal axes      " << vec(axes.col(0)) << "\n"
            << "                    " << vec(axes.col(1)) << "\n"
            << "                    " << vec(axes.col(2)) << "\n"
            << "bounding box        " << vec(box.min) << " .. " << vec(box.max) << "\n"
            << "characteristic L    " << num(p.length) << "  (volume-equivalent sphere diameter)\n"
            << "convex hull         " << p.hull.vertices.size() << " vertices, " << p.hull.faces.size()
            << " planar faces\n";
  for (const std::string& w : p.report.warnings) std::cout << "warning             " << w << "\n";
}

}  // namespace

Command add_info_command(CLI::App& app) {
  auto opts = std::make_shared<InfoOptions>();
  CLI::App* sub = app.add_subcommand("info", "Mass properties, hull and validation report of a particle");
  sub->add_option("particle", opts->source,
                  "Mesh file (STL, OBJ, PLY, OFF) or shape spec, e.g. box:x=1,y=2,z=3")
      ->required();
  sub->add_option("--density", opts->density, "Density, mass per unit volume (default 1)");
  sub->add_flag("--json", opts->json, "Print JSON instead of text");
  sub->add_option("--write-stl", opts->write_stl,
                  "Also write the validated surface as binary STL (input frame)");
  return {sub, [opts]() {
            check_positive("--density", opts->density);
            const Particle p = load_particle(opts->source, opts->density);
            if (!opts->write_stl.empty()) {
              TriangleMesh out = p.mesh;
              for (Vec3& v : out.vertices) v += p.input_offset;
              write_stl(out, opts->write_stl);
            }
            if (opts->json)
              std::cout << info_json(p, opts->density).dump(2) << "\n";
            else
              print_info(p, opts->density);
            return 0;
          }};
}

}  // namespace repose::cli
