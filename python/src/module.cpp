// The extension module repose._repose: the library's particle model, settling runs and rest-pose studies
// (docs/python.md). The public Python API is the package around it (python/repose/__init__.py).
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "repose/error.hpp"

PYBIND11_MODULE(_repose, m) {
  namespace py = pybind11;
  m.doc() = "repose: kinematics-based settling of rigid particles on a wall (C++ core)";
  // The library's one-line messages become Python exceptions: bad input is a ValueError, an interrupted
  // run (Ctrl-C) a KeyboardInterrupt.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const repose::Cancelled&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    } catch (const repose::Error& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  repose::python::bind_particle(m);
  repose::python::bind_runs(m);
  repose::python::bind_design(m);
}
