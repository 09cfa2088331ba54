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

/// The same for the polygon `loop` of `points` (counter-clockwise seen from outside) with unit `normal`, and
/// `point` in its plane or not (the distance is in the plane either way): the smallest inward distance from
/// an edge (the design moves the vertices: src/design/attraction.cpp).
double polygon_margin(const std::vector<Vec3>& points, const std::vector<int>& loop, const Vec3& normal,
                      const Vec3& point);

/// Per hull face: whether mesh triangles lying in the face plane cover the whole face.
std::vector<bool> faces_covered_by_mesh(const TriangleMesh& mesh, const ConvexHull& hull, double length);

}  // namespace repose
