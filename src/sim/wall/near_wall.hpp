// Internal: the hull vertices near the wall, found by walks over the hull's edge graph instead of scans of
// the hull (issue 49: a phase's cost per event independent of the hull's size). A linear function on a
// convex polytope's vertex graph has no local minimum but the global one, and its sublevel sets are
// connected: the lowest vertex is found by descending from the last one found (the body turns little between
// two queries), and every vertex below a level by a walk from there, whose cost is the set and its border.
// The walk runs a slack beyond the level (far above the round-off of a height); the caller's own test, in
// its own arithmetic, then picks the members, so a set is the one a scan with that test gives, in index
// order.
#pragma once

#include <algorithm>
#include <vector>

#include "repose/geometry/hull.hpp"
#include "repose/geometry/types.hpp"

namespace repose::sim {

class NearWall {
 public:
  explicit NearWall(const ConvexHull& hull) : hull_(hull), visited_(hull.vertices.size(), 0) {}

  /// The lowest hull vertex at orientation `q` (one of equals), by descent from the last one found.
  int lowest(const Quat& q) {
    lowest_ = hull_.support_vertex_from(-q.toRotationMatrix().row(2).transpose(), lowest_);
    return lowest_;
  }

  /// The indices, in increasing order, of the hull vertices within `slack` of the lowest one's height at
  /// orientation `q`: the lowest by any arithmetic of the heights that is exact to within the slack (the
  /// first of equals, say) is among them.
  const std::vector<int>& near_lowest(const Quat& q, double slack) {
    const Vec3 up = q.toRotationMatrix().row(2).transpose();
    const double level = up.dot(hull_.vertices[static_cast<std::size_t>(lowest(q))]);
    return vertices_below(q, 0.0, level, slack, [](int) { return true; });
  }

  /// The indices k, in increasing order, of the hull vertices with `below(k)` true, where `below` is the
  /// caller's test of "at most `level` above the wall" for the body at orientation `q` with its centre of
  /// mass `com_z` above the wall; every such vertex must be within `slack` of that level by the exact height
  /// com_z + (R·v).z.
  template <class Below>
  const std::vector<int>& vertices_below(const Quat& q, double com_z, double level, double slack,
                                         Below&& below) {
    const Vec3 down = -q.toRotationMatrix().row(2).transpose();
    lowest_ = hull_.support_vertex_from(down, lowest_);
    walk_.clear();
    hull_.vertices_at_least(down, com_z - level - slack, lowest_, walk_, visited_);
    picked_.clear();
    for (int k : walk_)
      if (below(k)) picked_.push_back(k);
    std::sort(picked_.begin(), picked_.end());
    return picked_;
  }

 private:
  const ConvexHull& hull_;
  int lowest_ = 0;
  std::vector<int> walk_, picked_;
  std::vector<char> visited_;
};

}  // namespace repose::sim
