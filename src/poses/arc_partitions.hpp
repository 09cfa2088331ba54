// Rolling whole arcs of the Gauss map: which stable face each part of an edge's arc rolls to, and the area of
// every piece of a vertex region by the face it reaches (the exact basins of landscape.hpp).
#pragma once

#include <vector>

#include "gauss_map.hpp"
#include "rolling.hpp"
#include "spherical.hpp"

namespace repose::detail {

// A part of an edge's arc, as an interval of the chord parameter t of the arc (point ∝ x + t(y − x) between
// its end normals x, y), and the face it rolls to.
struct Interval {
  double t0, t1;
  int face;
};

// Every edge's arc is parametrised by the chord parameter t of n(face_ab) → n(face_ba). A partition of an arc
// lists which face each part of it rolls to: the reach of the face its motion ends on where that is already
// known (a stable face or a balance face), else the face itself (mapped through the routes at the end; the
// routes are being resolved while the first partitions are made). Sliding arcs split at their top; a
// crossing arc is rolled across the next region, lune by lune, and each crossing arc's partition is computed
// once (on a fine smooth mesh most arcs cross, and flows run through long chains of regions).
class ArcPartitions {
 public:
  explicit ArcPartitions(const GaussMap& g)
      : g_(g),
        memo_(g.edges.size()),
        state_(g.edges.size(), kUnvisited),
        max_depth_(static_cast<int>(g.regions.size()) + kMaxDepthSlack) {}

  // The face (as in a partition) point x of crossing edge e's arc rolls to, from the arc's memoised
  // partition; −1 if x is within kPartTol of a part's ends (where a flow may end on a corner or a balance,
  // which the partition does not resolve: roll x instead) or the partition is not known yet.
  int face_at(int e_index, const Vec3& x);

  // Adds the area of every piece of vertex v's region to the stable face it rolls to.
  void add_region(int v, std::vector<double>& area);

 private:
  using Edge = GaussMap::Edge;
  enum State { kUnvisited, kInProgress, kDone };

  // The face's reach once its route is known (always, after resolve_routes), else the face itself.
  int rest_of(int face) const {
    const int reach = g_.routes[static_cast<std::size_t>(face)].reach;
    return reach >= 0 ? reach : face;
  }

  // A piece of starting directions whose flows all reach balance face f: each side of the great circle
  // through the balance goes on to its own side's face (which may be a balance face again).
  void add_split(int f, const std::vector<Vec3>& piece, std::vector<double>& area, int depth);
  const Vec3& normal(int face) const { return g_.face_normals[static_cast<std::size_t>(face)]; }
  Vec3 point(const Edge& e, double t) const { return chord_point(normal(e.face_ab), normal(e.face_ba), t); }
  double param(const Edge& e, const Vec3& plane) const {
    return cut(plane, normal(e.face_ab), normal(e.face_ba));
  }

  static void append_clipped(const std::vector<Interval>& parts, double lo, double hi,
                             std::vector<Interval>& out);

  // Appends the parts of [lo, hi] of edge e's arc, reached by leaving vertex `from`'s region.
  void partition(int e_index, int from, double lo, double hi, int depth, std::vector<Interval>& out);

  // Computes the whole partition of crossing edge e's arc once.
  void memoise(int e_index, int depth);

  // Appends the parts of [lo, hi] of crossing edge e's arc, rolled across the region it crosses into: each
  // exit lune of that region takes a sub-range to a sub-range of its exit arc, along great circles from the
  // apex.
  void cross(const Edge& e, double lo, double hi, int depth, std::vector<Interval>& out);

  // Sorted, with neighbouring parts that roll to the same face joined (keeps memoised partitions short).
  static std::vector<Interval> merged(std::vector<Interval> parts);

  const GaussMap& g_;
  std::vector<std::vector<Interval>> memo_;
  std::vector<State> state_;
  int max_depth_;
  std::vector<Vec3> lune_, piece_;  // scratch polygons
};

}  // namespace repose::detail
