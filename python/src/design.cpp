// repose.design: the quasi-static inverse design (include/repose/design/design.hpp) from Python.
#include "repose/design/design.hpp"

#include <pybind11/stl.h>

#include <cmath>
#include <numbers>

#include "bindings.hpp"
#include "repose/design/design_json.hpp"
#include "repose/design/target.hpp"
#include "repose/error.hpp"

namespace repose::python {

namespace {

// DesignOptions from keyword arguments, under the command line's names (without the dashes); an unknown
// name or a value of the wrong type is a ValueError naming it.
DesignOptions design_options(const py::dict& kwargs) {
  DesignOptions o;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    auto number = [&]() {
      try {
        return value.cast<double>();
      } catch (const py::cast_error&) {
        throw Error("design: " + name + " must be a number");
      }
    };
    if (name == "vary") {
      o.freedom = parse_design_freedom(py::str(value));
    } else if (name == "mass") {
      const std::string m = py::str(value);
      if (m != "follows" && m != "fixed") throw Error("design: mass '" + m + "': expected follows or fixed");
      o.mass = m == "fixed" ? MassModel::fixed : MassModel::follows_shape;
    } else if (name == "outcome_angle") {
      const double degrees = number();
      if (!(degrees > 0 && degrees <= 180)) throw Error("design: outcome_angle must be in (0, 180] degrees");
      o.outcome_angle = degrees * std::numbers::pi / 180;
    } else if (name == "com_margin") {
      o.com_margin = number();
    } else if (name == "max_move") {
      o.max_vertex_move = number();
    } else if (name == "max_step") {
      o.max_step = number();
    } else if (name == "min_edge") {
      o.min_edge = number();
    } else if (name == "min_face") {
      o.min_face_area = number();
    } else if (name == "smoothing") {
      o.smoothing = number();
    } else if (name == "tolerance") {
      o.tolerance = number();
    } else if (name == "iterations") {
      const double n = number();
      if (!(n >= 0 && n == std::floor(n) && n < 1e9))
        throw Error("design: iterations must be an integer >= 0");
      o.max_iterations = static_cast<int>(n);
    } else {
      throw Error(
          "design: unknown option '" + name +
          "' (vary, mass, outcome_angle, com_margin, max_move, max_step, min_edge, min_face, smoothing, "
          "tolerance, iterations)");
    }
  }
  return o;
}

py::tuple design_run(const PyParticle& p, const std::string& target_json, const std::string& target_name,
                     const py::dict& kwargs) {
  const DesignOptions options = design_options(kwargs);
  const DesignTarget target = parse_design_target(target_json, target_name);
  DesignResult r;
  {
    py::gil_scoped_release release;
    r = design_quasi_static(*p.model, target, options);
  }
  std::vector<std::array<double, 3>> vertices;
  for (const Vec3& v : r.mesh.vertices) vertices.push_back({v.x(), v.y(), v.z()});
  std::vector<std::array<int, 3>> triangles;
  for (const Triangle& t : r.mesh.triangles) triangles.push_back({t[0], t[1], t[2]});
  return py::make_tuple(design_json(p.model->name, target, options, r), vertices, triangles);
}

}  // namespace

void bind_design(py::module_& m) {
  m.def("design", &design_run, py::arg("particle"), py::arg("target_json"), py::arg("target_name"),
        py::arg("options"));
}

}  // namespace repose::python
