// Internal: the hull vertices near the wall, found by walks over the hull's edge graph instead of scans of
// the hull (issue 49: a phase's cost per event independent of the hull's size). A linear function on a
// convex polytope's vertex graph has no local minimum but the global one, and its sublevel sets are
// connected: the lowest vertex is found by descending from the last one found (the body turns little between
// two queries), and every vertex below a level by a walk from there, whose cost is the set and its border.
// The walk runs a slack beyond the level (far above the round-off of a height); the caller's own test, in
// its own arithmetic, then picks the members, so a set is the one a scan with that test gives, in index
// order. One per user: the run's (flight, impacts, the frictional phase) and the contact phase's own.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

#include "../tolerances.hpp"
#include "repose/geometry/hull.hpp"
#include "repose/geometry/types.hpp"

namespace repose::sim {

class NearWall {
 public:
  explicit NearWall(const ConvexHull& hull)
      : hull_(hull),
        visited_(hull.vertices.size(), 0),
        id_bits_((hull.vertices.size() + kWordBits - 1) / kWordBits) {}

  /// The lowest hull vertex along `down` (body frame; one of equals), by descent from the last one found.
  int lowest_along(const Vec3& down) {
    lowest_ = hull_.support_vertex_from(down, lowest_);
    return lowest_;
  }
  /// The same at orientation `q`.
  int lowest(const Quat& q) { return lowest_along(-q.toRotationMatrix().row(2).transpose()); }

  /// The hull vertices v with down·v ≥ `at_least` (body frame), in the order of a walk from the lowest along
  /// `down` (found first by descent).
  const std::vector<int>& walk(const Vec3& down, double at_least) {
    lowest_along(down);
    walk_.clear();
    hull_.vertices_at_least(down, at_least, lowest_, walk_, visited_);
    return walk_;
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
    picked_.clear();
    for (int k : walk(-q.toRotationMatrix().row(2).transpose(), com_z - level - slack))
      if (below(k)) picked_.push_back(k);
    sort_ids(picked_);
    return picked_;
  }

  /// Distinct hull vertex indices into increasing order. A set of hundreds is written into a bitset of the
  /// hull's vertices and read back in order: linear in the set plus its span/64 words, where a comparison
  /// sort costs ~n·log n (a tenth of a 10,000-vertex grain's settle went to std::sort).
  void sort_ids(std::vector<int>& ids) {
    if (ids.size() < tol::kBitsetSortFrom) {
      std::sort(ids.begin(), ids.end());
      return;
    }
    int lo = ids.front(), hi = ids.front();
    for (int k : ids) {
      id_bits_[static_cast<std::size_t>(k) / kWordBits] |= std::uint64_t{1}
                                                           << (static_cast<std::size_t>(k) % kWordBits);
      lo = std::min(lo, k);
      hi = std::max(hi, k);
    }
    ids.clear();
    for (std::size_t w = static_cast<std::size_t>(lo) / kWordBits;
         w <= static_cast<std::size_t>(hi) / kWordBits; ++w) {
      for (std::uint64_t bits = id_bits_[w]; bits != 0; bits &= bits - 1)
        ids.push_back(static_cast<int>(kWordBits * w) + std::countr_zero(bits));
      id_bits_[w] = 0;
    }
  }

 private:
  static constexpr std::size_t kWordBits = std::numeric_limits<std::uint64_t>::digits;
  const ConvexHull& hull_;
  int lowest_ = 0;
  std::vector<int> walk_, picked_;
  std::vector<char> visited_;           // of hull size, all zero between uses
  std::vector<std::uint64_t> id_bits_;  // of hull size in bits, all zero between uses (sort_ids)
};

}  // namespace repose::sim
