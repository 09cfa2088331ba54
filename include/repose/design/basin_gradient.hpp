// The exact quasi-static probabilities' gradient with respect to the centre of mass (issue 50: the design's
// objective, docs/inverse-design.md).
#pragma once

#include <vector>

#include "repose/geometry/types.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace repose {

struct BasinGradient {
  std::vector<double> probability;  ///< per hull face: its basin's area / 4π (landscape.basin_probability)
  /// Per hull face: the derivative of its probability with respect to the centre of mass's position in the
  /// body frame (per unit length). Exact for the landscape's structure (which faces are stable, which arcs
  /// cross, where balances split): the areas are smooth functions of the centre of mass between changes of
  /// that structure, where they are continuous but not differentiable.
  std::vector<Vec3> d_com;
};

/// The probabilities and their gradient by automatic differentiation (Eigen's forward AutoDiffScalar) through
/// the same partitions `landscape` (= compute_rest_landscape(particle)) was computed with.
BasinGradient basin_com_gradient(const Particle& particle, const RestLandscape& landscape);

}  // namespace repose
