// The hull vertices drawn as touching the wall, shared by the ParaView markers and the HTML reports so that
// both show the same points.
#pragma once

#include <vector>

#include "repose/model/particle.hpp"

namespace repose {

/// Indices into particle.hull.vertices of the vertices within `eps` (length) of the wall z = 0 at the pose
/// (orientation body → world, normalised here; com the centre of mass, world frame).
std::vector<int> hull_vertices_near_wall(const Particle& particle, const Quat& orientation, const Vec3& com,
                                         double eps);

}  // namespace repose
