// design_quasi_static (design.hpp): the descent (descent.hpp) from the start toward the target.
#include "repose/design/design.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "descent.hpp"
#include "repose/error.hpp"

namespace repose {

DesignFreedom parse_design_freedom(const std::string& text) {
  DesignFreedom out{false, ShapeFreedom::none};
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, '+')) {
    if (item == "center-of-mass" && !out.center_of_mass) {
      out.center_of_mass = true;
    } else if ((item == "vertices" || item == "faces") && out.shape == ShapeFreedom::none) {
      out.shape = item == "vertices" ? ShapeFreedom::vertices : ShapeFreedom::faces;
    } else {
      throw Error(
          "--vary '" + text +
          "': expected center-of-mass, vertices or faces, or one shape and center-of-mass joined by '+'");
    }
  }
  if (!out.center_of_mass && out.shape == ShapeFreedom::none)
    throw Error("--vary '" + text + "': nothing to vary");
  return out;
}

double DesignResult::max_error() const {
  double out = 0;
  for (std::size_t o = 0; o < target.size(); ++o) out = std::max(out, std::abs(achieved[o] - target[o]));
  return out;
}

DesignResult design_quasi_static(const Particle& start, DesignTarget target, const DesignOptions& options) {
  const detail::DesignSetup setup = detail::design_setup(start, options);
  const detail::Point first = detail::start_point(setup, std::move(target), options);
  return detail::design_result(setup, first, detail::descend(first, first.target, setup, options));
}

}  // namespace repose
