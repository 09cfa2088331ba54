// Internal to the Python extension repose._repose: what its source files share.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "repose/model/params.hpp"
#include "repose/model/particle.hpp"

namespace repose::python {

namespace py = pybind11;

/// A particle as Python holds it: the immutable model, shared by runs, and the density it was built with
/// (which the result files record and the model does not keep).
struct PyParticle {
  std::shared_ptr<const Particle> model;
  double density = 1;
};

/// An orientation from Python: a spec string ("identity", "quat:w,x,y,z", "axis-angle:x,y,z,a") or four
/// numbers w, x, y, z (normalised). Throws repose::Error naming the problem.
Quat orientation_from(const py::handle& value);

/// SettleParams from keyword arguments: the parameter table's entries marked in_python, under their names
/// (param_table.hpp), on top of `base`. Throws repose::Error for an unknown name or a bad value, naming it.
SettleParams params_from(const py::dict& kwargs, const std::string& context, SettleParams base = {});

void bind_particle(py::module_& m);
void bind_runs(py::module_& m);
void bind_design(py::module_& m);

}  // namespace repose::python
