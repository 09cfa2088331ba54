// Convex hull of a particle, with coplanar hull triangles merged into planar faces.
#pragma once

#include <vector>

#include "repose/geometry/types.hpp"

namespace repose {

/// A planar face of the convex hull.
struct HullFace {
  Vec3 normal;        ///< outward unit normal
  double offset = 0;  ///< plane: normal·x = offset (offset is the support distance along normal)
  double area = 0;
  std::vector<int> loop;  ///< indices into ConvexHull::vertices, counter-clockwise seen from outside
  Vec3 centroid;          ///< area centroid of the face polygon
};

struct ConvexHull {
  std::vector<Vec3> vertices;     ///< the hull's vertices (a subset of the input points)
  std::vector<int> source_index;  ///< index of each hull vertex in the input point set
  std::vector<HullFace> faces;

  /// Index (into `vertices`) of the vertex furthest along `direction`.
  int support_vertex(const Vec3& direction) const;
};

/// Convex hull of `points` (qhull, reentrant C API). Hull triangles that qhull finds coplanar within
/// round-off are merged into one planar face. Throws repose::Error if the points are degenerate (fewer than 4
/// non-coplanar points).
ConvexHull compute_convex_hull(const std::vector<Vec3>& points);

}  // namespace repose
