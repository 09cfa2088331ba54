// The exact quasi-static probabilities' gradients with respect to the hull's vertices and the centre of mass
// (issue 50: the design's objective, docs/inverse-design.md).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "repose/geometry/types.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace repose {

/// How the centre of mass moves when the vertices do: with the shape (the solid hull's centroid plus a fixed
/// offset: a uniform part, or an insert that moves with it), or fixed in the body frame (convex_dice's
/// "frozen G").
enum class MassModel { follows_shape, fixed };

struct BasinGradient {
  std::vector<double> probability;  ///< per hull face: its basin's area / 4π (landscape.basin_probability)
  /// Per hull face: the derivative of its probability with respect to the centre of mass's position in the
  /// body frame (per unit length), the vertices fixed.
  std::vector<Vec3> d_com;
  /// Row f, column 3i + k: the derivative of face f's probability with respect to coordinate k of hull vertex
  /// i (body frame, per unit length), the centre of mass moving as `mass` says.
  Eigen::MatrixXd d_vertices;
};

/// The probabilities and their gradients by reverse-mode automatic differentiation (ADOL-C) through the same
/// partitions `landscape` (= compute_rest_landscape(particle)) was computed with. Exact for the landscape's
/// structure (which faces are stable, which arcs cross, where balances split): the areas are smooth functions
/// of the vertices and the centre of mass between changes of that structure, where they are continuous but
/// not differentiable. A hull face's normal is its loop's (Newell's formula): moving one vertex of a merged
/// planar face differentiates the face kept planar on average. Cost: one reverse sweep per face (the design
/// asks only for its outcomes' rows). One call at a time in a process (ADOL-C's tapes are global; a mutex
/// serialises them).
BasinGradient basin_gradient(const Particle& particle, const RestLandscape& landscape,
                             MassModel mass = MassModel::follows_shape);

/// The probabilities and d_com only (d_vertices left empty): one forward sweep of three directions.
BasinGradient basin_com_gradient(const Particle& particle, const RestLandscape& landscape);

}  // namespace repose
