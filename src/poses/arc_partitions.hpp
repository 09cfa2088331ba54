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
template <class T>
struct IntervalT {
  T t0, t1;
  int face;
};
using Interval = IntervalT<double>;

// Every edge's arc is parametrised by the chord parameter t of n(face_ab) → n(face_ba). A partition of an arc
// lists which face each part of it rolls to: the reach of the face its motion ends on where that is already
// known (a stable face or a balance face), else the face itself (mapped through the routes at the end; the
// routes are being resolved while the first partitions are made). Sliding arcs split at their top; a
// crossing arc is rolled across the next region, lune by lune, and each crossing arc's partition is computed
// once (on a fine smooth mesh most arcs cross, and flows run through long chains of regions).
// Templates over the scalar as the map is (GaussMapT): the landscape's double, or the design's
// automatic-differentiation type replaying the same partitions (arc_partitions_impl.hpp has the definitions).
template <class T>
class ArcPartitionsT {
 public:
  using V = Eigen::Matrix<T, 3, 1>;
  explicit ArcPartitionsT(const GaussMapT<T>& g)
      : g_(g),
        memo_(g.edges.size()),
        state_(g.edges.size(), kUnvisited),
        max_depth_(static_cast<int>(g.regions.size()) + kMaxDepthSlack) {}

  // The face (as in a partition) point x of crossing edge e's arc rolls to, from the arc's memoised
  // partition; −1 if x is within kPartTol of a part's ends (where a flow may end on a corner or a balance,
  // which the partition does not resolve: roll x instead) or the partition is not known yet.
  int face_at(int e_index, const V& x);

  // Adds the area of every piece of vertex v's region to the stable face it rolls to.
  void add_region(int v, std::vector<T>& area);

 private:
  using Edge = typename GaussMapT<T>::Edge;
  using Interval = IntervalT<T>;
  enum State { kUnvisited, kInProgress, kDone };

  // The face's reach once its route is known (always, after resolve_routes), else the face itself.
  int rest_of(int face) const {
    const int reach = g_.routes[static_cast<std::size_t>(face)].reach;
    return reach >= 0 ? reach : face;
  }

  // A piece of starting directions whose flows all reach balance face f: each side of the great circle
  // through the balance goes on to its own side's face (which may be a balance face again).
  void add_split(int f, const std::vector<V>& piece, std::vector<T>& area, int depth);
  const V& normal(int face) const { return g_.face_normals[static_cast<std::size_t>(face)]; }
  V point(const Edge& e, const T& t) const { return chord_point<T>(normal(e.face_ab), normal(e.face_ba), t); }
  T param(const Edge& e, const V& plane) const { return cut<T>(plane, normal(e.face_ab), normal(e.face_ba)); }

  static void append_clipped(const std::vector<Interval>& parts, const T& lo, const T& hi,
                             std::vector<Interval>& out);

  // Appends the parts of [lo, hi] of edge e's arc, reached by leaving vertex `from`'s region.
  void partition(int e_index, int from, const T& lo, const T& hi, int depth, std::vector<Interval>& out);

  // Computes the whole partition of crossing edge e's arc once.
  void memoise(int e_index, int depth);

  // Appends the parts of [lo, hi] of crossing edge e's arc, rolled across the region it crosses into: each
  // exit lune of that region takes a sub-range to a sub-range of its exit arc, along great circles from the
  // apex.
  void cross(const Edge& e, const T& lo, const T& hi, int depth, std::vector<Interval>& out);

  // Sorted, with neighbouring parts that roll to the same face joined (keeps memoised partitions short).
  static std::vector<Interval> merged(std::vector<Interval> parts);

  const GaussMapT<T>& g_;
  std::vector<std::vector<Interval>> memo_;
  std::vector<State> state_;
  int max_depth_;
  std::vector<V> lune_, piece_;  // scratch polygons
};
using ArcPartitions = ArcPartitionsT<double>;
extern template class ArcPartitionsT<double>;

}  // namespace repose::detail
