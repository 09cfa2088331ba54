// repose._repose's runs: one settle (with its time series), the step-wise Settler, and rest-pose studies.
// Results cross into Python as the library's own JSON (settle_summary_json, poses_json), so that a Python
// run and the CLI's --json print the same numbers; time series as NumPy arrays. Long runs release the GIL
// and stop on Ctrl-C.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "bindings.hpp"
#include "interruptible.hpp"
#include "repose/error.hpp"
#include "repose/model/orientation.hpp"
#include "repose/model/param_table.hpp"
#include "repose/output/report.hpp"
#include "repose/poses/ensemble.hpp"
#include "repose/poses/landscape.hpp"
#include "repose/poses/study.hpp"
#include "repose/sim/settle.hpp"

namespace repose::python {
namespace {

py::array_t<double> rows(const std::vector<std::array<double, 4>>& r, py::ssize_t width) {
  py::array_t<double> out({static_cast<py::ssize_t>(r.size()), width});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < r.size(); ++i)
    for (py::ssize_t k = 0; k < width; ++k)
      o(static_cast<py::ssize_t>(i), k) = r[i][static_cast<std::size_t>(k)];
  return out;
}

// The time series as NumPy arrays: t, quaternion (w, x, y, z), omega, com and velocity (the centre of mass's;
// world), kinetic and potential energy, contact (the type's name) and contact_count.
py::dict series(const std::vector<Sample>& samples) {
  std::vector<double> t, kinetic, potential;
  std::vector<std::array<double, 4>> quaternion, omega, com, velocity;
  std::vector<std::string> contact;
  std::vector<int> count;
  for (const Sample& s : samples) {
    t.push_back(s.t);
    quaternion.push_back({s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z()});
    omega.push_back({s.omega.x(), s.omega.y(), s.omega.z(), 0});
    com.push_back({s.com.x(), s.com.y(), s.com.z(), 0});
    velocity.push_back({s.velocity.x(), s.velocity.y(), s.velocity.z(), 0});
    kinetic.push_back(s.kinetic_energy);
    potential.push_back(s.potential_energy);
    contact.emplace_back(to_string(s.contact));
    count.push_back(s.contact_count);
  }
  py::dict d;
  d["t"] = py::array_t<double>(static_cast<py::ssize_t>(t.size()), t.data());
  d["quaternion"] = rows(quaternion, 4);
  d["omega"] = rows(omega, 3);
  d["com"] = rows(com, 3);
  d["velocity"] = rows(velocity, 3);
  d["kinetic_energy"] = py::array_t<double>(static_cast<py::ssize_t>(kinetic.size()), kinetic.data());
  d["potential_energy"] = py::array_t<double>(static_cast<py::ssize_t>(potential.size()), potential.data());
  d["contact"] = contact;
  d["contact_count"] = py::array_t<int>(static_cast<py::ssize_t>(count.size()), count.data());
  return d;
}

py::dict sample_dict(const Sample& s) {
  std::vector<Sample> one{s};
  py::dict d = series(one);
  py::dict out;
  for (auto item : d) out[item.first] = item.second.attr("__getitem__")(0);
  return out;
}

// One settle: (the JSON summary, the time series sampled every sample_dt; 0 = the CLI's default interval).
py::tuple settle_run(const PyParticle& p, const py::handle& orientation, double sample_dt,
                     const py::dict& kw) {
  const Quat q = orientation_from(orientation);
  const SettleParams params = params_from(kw, "settle");
  const double dt = sample_dt > 0 ? sample_dt : default_sample_dt(*p.model, params);
  std::vector<Sample> samples;
  const std::shared_ptr<const Particle> model = p.model;
  const std::string summary = interruptible<std::string>([&](const std::atomic<bool>& cancel) {
    const SettleResult r = settle(
        *model, params, q,
        [&](const Sample& s) {
          if (cancel.load(std::memory_order_relaxed)) throw Cancelled("interrupted");
          samples.push_back(s);
        },
        dt);
    return settle_summary_json(*model, params, q, r);
  });
  return py::make_tuple(summary, series(samples));
}

// The step-wise engine, holding its particle.
struct PySettler {
  std::shared_ptr<const Particle> model;
  SettleParams params;
  Quat initial;
  Settler settler;
  PySettler(const PyParticle& p, const Quat& q, const SettleParams& prm)
      : model(p.model), params(prm), initial(q), settler(*p.model, prm, q) {}
};

StudySettings study_settings(const PyParticle& p, std::uint64_t seed, const std::string& method,
                             double damping_ratio, bool decide_early, double velocity_max, double spin_max,
                             std::optional<double> persistence, const py::dict& kw) {
  if (!std::isfinite(damping_ratio) || damping_ratio < 0)
    throw Error("poses: damping_ratio must be a finite number >= 0, got " + std::to_string(damping_ratio));
  if (persistence && (!std::isfinite(*persistence) || *persistence < 0))
    throw Error("poses: persistence must be a finite number >= 0, got " + std::to_string(*persistence));
  StudySettings s;
  s.seed = seed;
  s.method = parse_pose_method(method);
  s.density = p.density;
  s.damping_given = kw.contains("damping");
  s.params = params_from(kw, "poses");
  if (!s.damping_given) s.params.damping = 0;  // set from the ratio once the particle is known
  s.damping_ratio = damping_ratio;
  s.persistence = persistence ? *persistence : -1;
  s.decide_early = decide_early;
  s.toss = {velocity_max, spin_max};
  return s;
}

std::string poses_run(const PyParticle& p, std::uint64_t n, std::uint64_t seed, int threads,
                      const std::string& method, double damping_ratio, bool decide_early, double velocity_max,
                      double spin_max, std::optional<double> persistence, const py::dict& kw) {
  if (n < 1) throw Error("poses: give the number of drops n >= 1");
  if (threads < 0) throw Error("poses: threads must be >= 0 (0 = all cores), got " + std::to_string(threads));
  const StudySettings settings =
      study_settings(p, seed, method, damping_ratio, decide_early, velocity_max, spin_max, persistence, kw);
  const std::shared_ptr<const Particle> model = p.model;
  return interruptible<std::string>([&](const std::atomic<bool>& cancel) {
    const RestLandscape landscape = compute_rest_landscape(*model);
    PosesStudy study = prepare_study(*model, landscape, settings);
    EnsembleOptions options = ensemble_options(study, {0, n}, threads);
    options.cancel = &cancel;
    study.tally = run_ensemble(*model, landscape, study.catalog, options);
    study.threads = threads > 0 ? threads : available_cores();
    return poses_json(study);
  });
}

// The exact quasi-static probabilities (no drops): the catalogue of a quasi-static study.
std::string quasi_static_run(const PyParticle& p, std::optional<double> persistence) {
  const StudySettings settings =
      study_settings(p, 1, "quasi-static", 0.05, true, 0, 0, persistence, py::dict());
  py::gil_scoped_release release;
  const RestLandscape landscape = compute_rest_landscape(*p.model);
  return poses_json(prepare_study(*p.model, landscape, settings));
}

}  // namespace

Quat orientation_from(const py::handle& value) {
  if (py::isinstance<py::str>(value)) return parse_orientation(value.cast<std::string>());
  std::vector<double> wxyz;
  try {
    wxyz = value.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    throw Error(
        "orientation: give a spec string (identity, quat:w,x,y,z, axis-angle:x,y,z,angle) or four "
        "numbers w, x, y, z");
  }
  if (wxyz.size() != 4)
    throw Error("orientation: four numbers w, x, y, z expected, got " + std::to_string(wxyz.size()));
  std::string spec = "quat:";
  for (std::size_t i = 0; i < 4; ++i)
    spec += (i ? "," : "") + py::repr(py::float_(wxyz[i])).cast<std::string>();
  return parse_orientation(spec);
}

SettleParams params_from(const py::dict& kwargs, const std::string& context, SettleParams p) {
  const auto number = [&](const std::string& name, const py::handle& v) {
    try {
      return v.cast<double>();
    } catch (const py::cast_error&) {
      throw Error(context + ": " + name + " must be a number");
    }
  };
  const auto vector = [&](const std::string& name, const py::handle& v) {
    std::vector<double> x;
    try {
      x = v.cast<std::vector<double>>();
    } catch (const py::cast_error&) {
      throw Error(context + ": " + name + " must be three numbers x, y, z");
    }
    if (x.size() != 3) throw Error(context + ": " + name + " must be three numbers x, y, z");
    return Vec3(x[0], x[1], x[2]);
  };
  const auto choice = [&](const std::string& name, const py::handle& v, const ParamChoice& c) {
    if (!py::isinstance<py::str>(v)) throw Error(context + ": " + name + " must be a string");
    try {
      c.set(p, v.cast<std::string>());
    } catch (const Error& e) {
      throw Error(context + ": " + e.what());
    }
  };
  for (auto [key, value] : kwargs) {
    const std::string name = key.cast<std::string>();
    const ParamInfo* info = find_param(name);
    if (info == nullptr || !(info->uses & in_python))
      throw Error(context + ": unknown parameter '" + name + "' (accepted: " + param_names(in_python) + ")");
    std::visit(Overloaded{[&](double SettleParams::*m) {  // None: infinity where valid (friction: no slip)
                            p.*m = value.is_none() && info->range.allows_infinity() ? INFINITY
                                                                                    : number(name, value);
                          },
                          [&](long SettleParams::*m) { p.*m = static_cast<long>(number(name, value)); },
                          [&](int SettleParams::*m) { p.*m = static_cast<int>(number(name, value)); },
                          [&](Vec3 SettleParams::*m) { p.*m = vector(name, value); },
                          [&](const ParamChoice& c) { choice(name, value, c); }},
               info->member);
  }
  validate(p);
  return p;
}

void bind_runs(py::module_& m) {
  m.def("settle", &settle_run, py::arg("particle"), py::arg("orientation"), py::arg("sample_dt"),
        py::arg("params"));
  m.def("poses", &poses_run, py::arg("particle"), py::arg("n"), py::arg("seed"), py::arg("threads"),
        py::arg("method"), py::arg("damping_ratio"), py::arg("decide_early"), py::arg("velocity_max"),
        py::arg("spin_max"), py::arg("persistence"), py::arg("params"));
  m.def("quasi_static", &quasi_static_run, py::arg("particle"), py::arg("persistence"));
  py::class_<PySettler>(m, "Settler")
      .def(py::init([](const PyParticle& p, const py::handle& orientation, const py::dict& kw) {
             return new PySettler(p, orientation_from(orientation), params_from(kw, "Settler"));
           }),
           py::arg("particle"), py::arg("orientation"), py::arg("params"))
      .def("step", [](PySettler& s) { return s.settler.step(); })
      .def(
          "advance_to",
          [](PySettler& s, double time) {
            py::gil_scoped_release release;
            return s.settler.advance_to(time);
          },
          py::arg("time"))
      .def("sample", [](const PySettler& s) { return sample_dict(s.settler.sample()); })
      .def_property_readonly("status",
                             [](const PySettler& s) { return std::string(to_string(s.settler.status())); })
      .def("result_json", [](const PySettler& s) {
        return settle_summary_json(*s.model, s.params, s.initial, s.settler.result());
      });
}

}  // namespace repose::python
