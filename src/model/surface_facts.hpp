// Internal: surface facts computed when a Particle is built.
#pragma once

#include <vector>

#include "repose/geometry/hull.hpp"
#include "repose/geometry/types.hpp"

namespace repose {

/// Largest angle between neighbouring triangle normals (rad), and whether no edge is reflex.
void compute_dihedral_facts(const TriangleMesh& mesh, double length, double& max_angle, bool& convex);

/// Signed distance from the projection of `com` onto the face plane to the face boundary (positive inside).
double face_stability_margin(const ConvexHull& hull, const HullFace& face, const Vec3& com);

/// Per hull face: whether mesh triangles lying in the face plane cover the whole face.
std::vector<bool> faces_covered_by_mesh(const TriangleMesh& mesh, const ConvexHull& hull, double length);

}  // namespace repose
