// repose._repose.Particle: a particle model from a file, a shape spec or NumPy arrays, and its properties.
// Lengths are in the mesh's units after scaling, masses in density × volume.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "repose/error.hpp"
#include "repose/geometry/types.hpp"
#include "repose/output/report.hpp"
#include "repose/sim/settle.hpp"

namespace repose::python {
namespace {

MeshOptions mesh_options(double scale, const std::optional<std::string>& units, const std::string& inertia,
                         bool repair, bool largest_component, const std::optional<std::vector<double>>& com) {
  if (!std::isfinite(scale) || scale <= 0)
    throw Error("scale must be a finite number > 0, got " + std::to_string(scale));
  if (units && scale != 1)  // as --mesh-units and --scale at the command line: one way to give the factor
    throw Error("units and scale: give one of them (units=\"" + *units + "\" is the factor " +
                std::to_string(mesh_unit_scale(*units)) + ")");
  MeshOptions o;
  o.scale = units ? mesh_unit_scale(*units) : scale;
  o.inertia = parse_inertia_model(inertia);
  o.repair = repair || largest_component;
  o.largest_component = largest_component;
  if (com) {
    if (com->size() != 3) throw Error("com must be three numbers x, y, z (the centre of mass)");
    o.center_of_mass = Vec3((*com)[0], (*com)[1], (*com)[2]);
  }
  return o;
}

void check_density(double density) {
  if (!std::isfinite(density) || density <= 0)
    throw Error("density must be a finite number > 0, got " + std::to_string(density));
}

PyParticle load(const std::string& source, double density, const std::optional<std::string>& units,
                double scale, const std::string& inertia, bool repair, bool largest_component,
                const std::optional<std::vector<double>>& com) {
  check_density(density);
  const MeshOptions options = mesh_options(scale, units, inertia, repair, largest_component, com);
  py::gil_scoped_release release;  // a large scan takes seconds
  return {std::make_shared<const Particle>(load_particle(source, density, options)), density};
}

PyParticle from_arrays(const py::array_t<double, py::array::c_style | py::array::forcecast>& vertices,
                       const py::array_t<long long, py::array::c_style | py::array::forcecast>& faces,
                       double density, const std::optional<std::string>& units, double scale,
                       const std::string& inertia, bool repair, bool largest_component,
                       const std::string& name, const std::optional<std::vector<double>>& com) {
  check_density(density);
  if (vertices.ndim() != 2 || vertices.shape(1) != 3)
    throw Error(name + ": vertices must be an array of shape (N, 3)");
  if (faces.size() > 0 && (faces.ndim() != 2 || faces.shape(1) != 3))
    throw Error(name + ": faces must be an array of shape (M, 3) of vertex indices");
  TriangleMesh mesh;
  const auto v = vertices.unchecked<2>();
  for (py::ssize_t i = 0; i < v.shape(0); ++i) mesh.vertices.emplace_back(v(i, 0), v(i, 1), v(i, 2));
  if (faces.size() > 0) {
    const auto f = faces.unchecked<2>();
    const auto n = static_cast<long long>(mesh.vertices.size());
    for (py::ssize_t i = 0; i < f.shape(0); ++i) {
      Triangle t;
      for (int k = 0; k < 3; ++k) {
        const long long index = f(i, k);
        if (index < 0 || index >= n)
          throw Error(name + ": face " + std::to_string(i) + " refers to vertex " + std::to_string(index) +
                      " of " + std::to_string(n));
        t[static_cast<std::size_t>(k)] = static_cast<int>(index);
      }
      mesh.triangles.push_back(t);
    }
  }
  const MeshOptions options = mesh_options(scale, units, inertia, repair, largest_component, com);
  py::gil_scoped_release release;
  return {std::make_shared<const Particle>(make_particle(std::move(mesh), name, density, options)), density};
}

py::array_t<double> points(const std::vector<Vec3>& p) {
  py::array_t<double> out({static_cast<py::ssize_t>(p.size()), py::ssize_t{3}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int k = 0; k < 3; ++k) o(static_cast<py::ssize_t>(i), k) = p[i][k];
  return out;
}

// What the file held (MeshReport) and what --repair did (RepairReport): the library's JSON, as `repose info
// --json` prints it ("file", "repair"), parsed into dicts.
py::object json_dict(const std::string& text) { return py::module_::import("json").attr("loads")(text); }
py::object file_report(const MeshReport& r) { return json_dict(file_report_json(r)); }
py::object repair_report(const std::optional<RepairReport>& repair) {
  return repair ? json_dict(repair_report_json(*repair)) : py::none();
}

}  // namespace

void bind_particle(py::module_& m) {
  py::class_<PyParticle>(m, "Particle")
      .def_static("load", &load, py::arg("source"), py::arg("density") = 1.0, py::arg("units") = py::none(),
                  py::arg("scale") = 1.0, py::arg("inertia") = "exact", py::arg("repair") = false,
                  py::arg("largest_component") = false, py::arg("com") = py::none())
      .def_static("from_arrays", &from_arrays, py::arg("vertices"), py::arg("faces"),
                  py::arg("density") = 1.0, py::arg("units") = py::none(), py::arg("scale") = 1.0,
                  py::arg("inertia") = "exact", py::arg("repair") = false,
                  py::arg("largest_component") = false, py::arg("name") = "arrays",
                  py::arg("com") = py::none())
      .def_property_readonly("name", [](const PyParticle& p) { return p.model->name; })
      .def_property_readonly("density", [](const PyParticle& p) { return p.density; })
      .def_property_readonly("mass", [](const PyParticle& p) { return p.model->mass.mass; })
      .def_property_readonly("volume", [](const PyParticle& p) { return p.model->mass.volume; })
      .def_property_readonly("length", [](const PyParticle& p) { return p.model->length; })
      .def_property_readonly("com", [](const PyParticle& p) { return Vec3(p.model->input_offset); })
      .def_property_readonly("inertia", [](const PyParticle& p) { return Mat3(p.model->mass.inertia); })
      .def_property_readonly("principal_moments",
                             [](const PyParticle& p) { return Vec3(p.model->mass.principal_moments); })
      .def_property_readonly("principal_axes",
                             [](const PyParticle& p) { return Mat3(p.model->mass.principal_axes); })
      .def_property_readonly(
          "inertia_model",
          [](const PyParticle& p) { return std::string(to_string(p.model->options.inertia)); })
      .def_property_readonly("vertices", [](const PyParticle& p) { return points(p.model->mesh.vertices); })
      .def_property_readonly("triangles",
                             [](const PyParticle& p) {
                               const auto& t = p.model->mesh.triangles;
                               py::array_t<int> out({static_cast<py::ssize_t>(t.size()), py::ssize_t{3}});
                               auto o = out.mutable_unchecked<2>();
                               for (std::size_t i = 0; i < t.size(); ++i)
                                 for (int k = 0; k < 3; ++k)
                                   o(static_cast<py::ssize_t>(i), k) = t[i][static_cast<std::size_t>(k)];
                               return out;
                             })
      .def_property_readonly("hull_vertices",
                             [](const PyParticle& p) { return points(p.model->hull.vertices); })
      .def_property_readonly("hull_faces",
                             [](const PyParticle& p) {
                               std::vector<std::vector<int>> loops;
                               for (const HullFace& f : p.model->hull.faces) loops.push_back(f.loop);
                               return loops;
                             })
      .def_property_readonly("hull_normals",
                             [](const PyParticle& p) {
                               std::vector<Vec3> n;
                               for (const HullFace& f : p.model->hull.faces) n.push_back(f.normal);
                               return points(n);
                             })
      .def_property_readonly("bounds",
                             [](const PyParticle& p) {
                               return points({p.model->bounds.min, p.model->bounds.max});
                             })
      .def_property_readonly("smooth", [](const PyParticle& p) { return is_smooth_surface(*p.model); })
      .def_property_readonly("scale", [](const PyParticle& p) { return p.model->options.scale; })
      .def_property_readonly("surface_is_hull", [](const PyParticle& p) { return p.model->surface_is_hull; })
      .def_property_readonly("file_report", [](const PyParticle& p) { return file_report(p.model->report); })
      .def_property_readonly("repair_report",
                             [](const PyParticle& p) { return repair_report(p.model->repair); });
}

}  // namespace repose::python
