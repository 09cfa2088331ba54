// Convex hull of a particle, with coplanar hull triangles merged into planar faces.
#pragma once

#include <span>
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
  /// The edge graph in compressed rows (one flat array, walked constantly by the engine): the neighbours of
  /// vertex v are neighbor_list[neighbor_offsets[v] .. neighbor_offsets[v + 1]) (vertices.size() + 1
  /// offsets).
  std::vector<int> neighbor_offsets;
  std::vector<int> neighbor_list;

  /// The vertices joined to vertex `v` by an edge of a (merged, planar) face.
  std::span<const int> neighbors(int v) const {
    const auto i = static_cast<std::size_t>(v);
    const auto begin = static_cast<std::size_t>(neighbor_offsets[i]);
    return {neighbor_list.data() + begin, static_cast<std::size_t>(neighbor_offsets[i + 1]) - begin};
  }

  /// Index (into `vertices`) of the vertex furthest along `direction` (a scan of every vertex).
  int support_vertex(const Vec3& direction) const;

  /// The same, found by walking the edge graph uphill from vertex `start`: on a convex polytope a vertex
  /// no neighbour of which is further along `direction` is furthest of all. The cost is the vertices on the
  /// way (a few when `start` is the previous answer of a slowly turning direction), not the hull's size.
  int support_vertex_from(const Vec3& direction, int start) const;

  /// Appends to `out` every vertex v with direction·v ≥ level, found by a walk over the edge graph from the
  /// furthest vertex `top` (support_vertex_from): those vertices are connected (from each of them an edge
  /// path that only rises leads to `top`), so the cost is the set and its border, not the hull's size.
  /// `visited` is scratch of vertices.size() entries, all false on entry and on return.
  void vertices_at_least(const Vec3& direction, double level, int top, std::vector<int>& out,
                         std::vector<char>& visited) const;
};

/// Convex hull of `points` (qhull, reentrant C API). Hull triangles that qhull finds coplanar within
/// round-off are merged into one planar face. Throws repose::Error if the points are degenerate (fewer than 4
/// non-coplanar points).
ConvexHull compute_convex_hull(const std::vector<Vec3>& points);

}  // namespace repose
