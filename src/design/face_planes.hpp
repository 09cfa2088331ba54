// A convex polytope as its face planes, the design's variables when faces must stay flat (`--vary faces`):
// plane f is {x : p_f·x = 1} (p_f = n_f / offset_f, the origin inside), so three numbers per face and no
// constraint among them. Vertices follow as the planes' intersections (the polar dual's hull), and the
// probabilities' gradient with respect to the planes from the one with respect to the vertices by the chain
// rule through each vertex's three planes.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "repose/geometry/hull.hpp"
#include "repose/geometry/types.hpp"

namespace repose::detail {

// Each face's p_f (the hull's frame, its origin inside: every offset > 0).
std::vector<Vec3> face_planes(const ConvexHull& hull);

// The vertices of the polytope ∩_f {p_f·x ≤ 1}: the facets of the hull of the points p_f, each facet
// m·p = c giving the vertex m / c. Nothing if the planes do not bound a polytope around the origin. A plane
// whose point is inside that hull bounds nothing (its face has vanished); it may come back as it moves.
std::optional<std::vector<Vec3>> plane_vertices(const std::vector<Vec3>& planes);

// Each hull face's plane: the one whose normal it has (within 1e-6 of the cosine), or −1.
std::vector<int> plane_indices(const ConvexHull& hull, const std::vector<Vec3>& planes);

// Columns over hull vertices (3j + k; `hull` in a frame where the planes' origin is at `origin`) to columns
// over the planes (3f + k). A vertex where more than three faces meet moves with the three of them whose
// normals are the most independent (the current structure's one-sided derivative: such a vertex splits as
// the planes move).
Eigen::MatrixXd plane_columns(const Eigen::MatrixXd& vertex_columns, const ConvexHull& hull,
                              const Vec3& origin, const std::vector<Vec3>& planes);

}  // namespace repose::detail
