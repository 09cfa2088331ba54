// The catalogue of a particle's rest poses: its stable hull faces, merged where the barrier between them is
// negligible (the facets of a smooth particle's mesh), each with its exact quasi-static probability and the
// energy barrier that keeps a particle in it.
#pragma once

#include <vector>

#include "repose/geometry/types.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace repose {

struct RestPose {
  int face = -1;           ///< representative hull face: the pose's lowest stable face
  std::vector<int> faces;  ///< the stable hull faces merged into this pose, ascending
  Vec3 down_normal_body;   ///< body-frame outward normal of `face`: the direction pointing at the wall
  double com_height = 0;   ///< centre-of-mass height above the wall at rest on `face` (length)
  /// Lowest centre-of-mass height of a saddle leading out of this pose (length); +infinity if the particle
  /// has no other pose. A particle touching the wall whose energy stays below m·g·barrier cannot leave.
  double barrier = 0;
  double quasi_static_probability = 0;  ///< exact basin area / 4π, summed over `faces`
};

struct RestPoseCatalog {
  std::vector<RestPose> poses;  ///< ordered by com_height, then face index
  std::vector<int> face_pose;   ///< per hull face: the pose quasi-static rolling from that face ends in
  double persistence = 0;       ///< the merge threshold used (length)
};

/// Builds the catalogue. Stable faces are merged by topological persistence: walking the saddles upward, a
/// minimum whose depth below the saddle joining it to a deeper one is less than `persistence` (length, ≥ 0)
/// joins that deeper minimum's pose. `persistence` = 0 keeps every stable face a pose of its own.
RestPoseCatalog catalog_rest_poses(const Particle& particle, const RestLandscape& landscape,
                                   double persistence);

/// The default merge threshold: 0 for faceted particles, 1 % of L for smooth ones (is_smooth_surface), whose
/// meshes have many nearly flat stable facets around each true minimum.
double default_persistence(const Particle& particle, bool smooth);

}  // namespace repose
