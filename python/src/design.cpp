// repose.design: the inverse design (include/repose/design/design.hpp, toss_design.hpp) from Python.
#include "repose/design/design.hpp"

#include <pybind11/stl.h>

#include <cmath>
#include <numbers>

#include "bindings.hpp"
#include "interruptible.hpp"
#include "repose/design/design_json.hpp"
#include "repose/design/design_report.hpp"
#include "repose/design/target.hpp"
#include "repose/design/toss_design.hpp"
#include "repose/error.hpp"
#include "repose/output/files.hpp"

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
    } else if (name == "outcome_normals") {
      const std::string m = py::str(value);
      if (m != "fixed" && m != "follow")
        throw Error("design: outcome_normals '" + m + "': expected fixed or follow");
      o.follow_outcome_normals = m == "follow";
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
    } else if (name == "min_margin") {
      o.min_margin = number();
    } else if (name == "smoothing") {
      o.smoothing = number();
    } else if (name == "keep_faces_flat") {
      if (!py::isinstance<py::bool_>(value)) throw Error("design: keep_faces_flat must be True or False");
      o.keep_faces_flat = value.cast<bool>();
    } else if (name == "tolerance") {
      o.tolerance = number();
    } else if (name == "iterations") {
      const double n = number();
      if (!(n >= 0 && n == std::floor(n) && n < 1e9))
        throw Error("design: iterations must be an integer >= 0");
      o.max_iterations = static_cast<int>(n);
    } else {
      throw Error("design: unknown option '" + name +
                  "' (vary, mass, outcome_angle, outcome_normals, com_margin, max_move, max_step, min_edge, "
                  "min_face, min_margin, smoothing, keep_faces_flat, tolerance, iterations)");
    }
  }
  return o;
}

// The tossed model from the `toss` dict: drops, check_drops, seed, threads, iterations, velocity_max,
// spin_max, damping_ratio, and the settle parameters (drop_height, restitution, friction, ...).
TossDesignOptions toss_options(const py::dict& toss, const DesignOptions& shape) {
  TossDesignOptions o;
  o.shape = shape;
  StudySettings& s = o.model.settings;
  py::dict params;
  for (const auto& [key, value] : toss) {
    const std::string name = py::str(key);
    auto whole = [&](double min) {
      double x = NAN;
      try {
        x = value.cast<double>();
      } catch (const py::cast_error&) {
      }
      if (!(x >= min && x == std::floor(x) && x < 1.8e19))
        throw Error("design: toss " + name + " must be a whole number >= " + std::to_string(int(min)));
      return x;
    };
    auto number = [&]() {
      double x = NAN;
      try {
        x = value.cast<double>();
      } catch (const py::cast_error&) {
      }
      if (!(std::isfinite(x) && x >= 0))
        throw Error("design: toss " + name + " must be a finite number >= 0");
      return x;
    };
    if (name == "drops") {
      o.model.drops = static_cast<std::uint64_t>(whole(1));
    } else if (name == "check_drops") {
      o.model.check_drops = static_cast<std::uint64_t>(whole(1));
    } else if (name == "seed") {
      s.seed = static_cast<std::uint64_t>(whole(0));
    } else if (name == "threads") {
      o.model.threads = static_cast<int>(whole(0));
    } else if (name == "iterations") {
      o.max_iterations = static_cast<int>(whole(0));
    } else if (name == "velocity_max") {
      s.toss.velocity_max = number();
    } else if (name == "spin_max") {
      s.toss.spin_max = number();
    } else if (name == "damping_ratio") {
      s.damping_ratio = number();
    } else {
      params[key] = value;
    }
  }
  s.damping_given = params.contains("damping");
  s.params = params_from(params, "design toss");
  if (!s.damping_given) s.params.damping = 0;  // from the ratio, once each design's particle is known
  return o;
}

py::tuple design_run(const PyParticle& p, const std::string& target_json, const std::string& target_name,
                     py::dict kwargs) {
  std::string model = "quasi-static";
  py::dict toss;
  if (kwargs.contains("model")) {
    model = py::str(kwargs["model"]);
    if (model != "quasi-static" && model != "tossed")
      throw Error("design: model '" + model + "': expected quasi-static or tossed");
    kwargs.attr("pop")("model");
  }
  if (kwargs.contains("toss")) {
    if (model != "tossed") throw Error("design: toss is the tossed model's: add model=\"tossed\"");
    toss = kwargs["toss"].cast<py::dict>();
    kwargs.attr("pop")("toss");
  }
  std::string html;  // the report's path, if any (the CLI's --html)
  if (kwargs.contains("html")) {
    html = py::str(kwargs["html"]);
    if (html.empty()) throw Error("design: html must be a file path");
    kwargs.attr("pop")("html");
  }
  const DesignOptions options = design_options(kwargs);
  const DesignTarget target = parse_design_target(target_json, target_name);
  const std::shared_ptr<const Particle> particle = p.model;
  DesignResult r;
  std::string json;
  if (model == "tossed") {
    TossDesignOptions o = toss_options(toss, options);
    const TossDesignResult tr = interruptible<TossDesignResult>([&](const std::atomic<bool>& cancel) {
      o.model.cancel = &cancel;
      return design_for_toss(*particle, target, o);
    });
    o.model.cancel = nullptr;
    r = tr.design;
    json = toss_design_json(particle->name, target, o, tr);
  } else {
    py::gil_scoped_release release;
    r = design_quasi_static(*particle, target, options);
    json = design_json(particle->name, target, options, r);
  }
  if (!html.empty())
    write_file_atomically(html, design_report_html(particle->name, target, options, r, json));
  std::vector<std::array<double, 3>> vertices;
  for (const Vec3& v : r.mesh.vertices) vertices.push_back({v.x(), v.y(), v.z()});
  std::vector<std::array<int, 3>> triangles;
  for (const Triangle& t : r.mesh.triangles) triangles.push_back({t[0], t[1], t[2]});
  return py::make_tuple(json, vertices, triangles);
}

}  // namespace

void bind_design(py::module_& m) {
  m.def("design", &design_run, py::arg("particle"), py::arg("target_json"), py::arg("target_name"),
        py::arg("options"));
}

}  // namespace repose::python
