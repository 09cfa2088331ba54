// The definitions of ArcPartitionsT (arc_partitions.hpp), for its instantiations: the landscape's double
// (arc_partitions.cpp) and the design's automatic-differentiation type.
#pragma once

#include <algorithm>
#include <string>
#include <utility>

#include "arc_partitions.hpp"
#include "repose/error.hpp"

namespace repose::detail {

// A point of an arc within this chord parameter of the ends of its part of a memoised partition is rolled
// directly instead (generous: it only costs time).
inline constexpr double kPartTol = 1e-9;

// The face (as in a partition) point x of crossing edge e's arc rolls to, from the arc's memoised
// partition; −1 if x is within kPartTol of a part's ends (where a flow may end on a corner or a balance,
// which the partition does not resolve: roll x instead) or the partition is not known yet.
template <class T>
int ArcPartitionsT<T>::face_at(int e_index, const V& x) {
  const std::size_t i = static_cast<std::size_t>(e_index);
  memoise(e_index, 0);
  if (state_[i] != kDone || memo_[i].empty()) return -1;
  const Edge& e = g_.edges[i];
  const T t = param(e, V(x.cross(e.top.cross(e.along))));  // plane through x normal to the arc
  const std::vector<Interval>& parts = memo_[i];
  const auto it =
      std::partition_point(parts.begin(), parts.end(), [&](const Interval& s) { return s.t1 < t; });
  if (it == parts.end() || !(t > it->t0 + kPartTol && t < it->t1 - kPartTol)) return -1;
  return it->face;
}

// Adds the area of every piece of vertex v's region to the stable face it rolls to.
template <class T>
void ArcPartitionsT<T>::add_region(int v, std::vector<T>& area) {
  const auto& r = g_.regions[static_cast<std::size_t>(v)];
  const std::size_t k = r.corners.size();
  if (k < 3) return;  // a vertex inside a straight edge: its region is that arc (no area)
  const V& p = r.apex;
  std::vector<Interval> parts;
  for (std::size_t i = 0; i < k; ++i) {
    if (!r.arcs[i].exit) continue;
    const Edge& e = g_.edges[static_cast<std::size_t>(r.arcs[i].edge)];
    parts.clear();
    partition(r.arcs[i].edge, v, 0, 1, 0, parts);
    // The lune planes need the part's ends in the order of the region's corners i → i + 1.
    const bool forward = r.faces[i] == e.face_ab;
    for (const Interval& s : parts) {
      if (!(s.t1 > s.t0)) continue;
      V x = point(e, s.t0);
      V y = point(e, s.t1);
      if (!forward) std::swap(x, y);
      clip_polygon<T>(r.corners, V(T(r.sense) * p.cross(x)), lune_);
      clip_polygon<T>(lune_, V(T(r.sense) * y.cross(p)), piece_);
      const int reach = rest_of(s.face);
      if (g_.routes[static_cast<std::size_t>(reach)].balance) {
        add_split(reach, piece_, area, 0);
      } else {
        area[static_cast<std::size_t>(reach)] += spherical_area<T>(piece_);
      }
    }
  }
}

// A piece of starting directions whose flows all reach balance face f: each side of the great circle
// through the balance goes on to its own side's face (which may be a balance face again).
template <class T>
void ArcPartitionsT<T>::add_split(int f, const std::vector<V>& piece, std::vector<T>& area, int depth) {
  if (depth > max_depth_) throw Error("rest landscape: balances lead to each other in a cycle");
  const auto& r = g_.routes[static_cast<std::size_t>(f)];
  std::vector<V> half;
  for (int side = 0; side < 2; ++side) {
    clip_polygon<T>(piece, side == 1 ? r.unstable : V(-r.unstable), half);
    if (half.size() < 3) continue;
    const int next = rest_of(r.side[side]);
    if (g_.routes[static_cast<std::size_t>(next)].balance) {
      add_split(next, half, area, depth + 1);
    } else {
      area[static_cast<std::size_t>(next)] += spherical_area<T>(half);
    }
  }
}

template <class T>
void ArcPartitionsT<T>::append_clipped(const std::vector<Interval>& parts, const T& lo, const T& hi,
                                       std::vector<Interval>& out) {
  for (const Interval& s : parts) {
    const T t0 = std::max(s.t0, lo);
    const T t1 = std::min(s.t1, hi);
    if (t1 > t0) out.push_back({t0, t1, s.face});
  }
}

// Appends the parts of [lo, hi] of edge e's arc, reached by leaving vertex `from`'s region.
template <class T>
void ArcPartitionsT<T>::partition(int e_index, int from, const T& lo, const T& hi, int depth,
                                  std::vector<Interval>& out) {
  const Edge& e = g_.edges[static_cast<std::size_t>(e_index)];
  if (e.cross_to < 0 || e.cross_to == from) {
    if (!e.top_inside) {
      out.push_back({lo, hi, rest_of(e.low_face)});
      return;
    }
    const T t = param(e, e.along);  // the top
    if (lo < t) out.push_back({lo, std::min(t, hi), rest_of(e.face_ab)});
    if (hi > t) out.push_back({std::max(t, lo), hi, rest_of(e.face_ba)});
    return;
  }
  const std::size_t i = static_cast<std::size_t>(e_index);
  memoise(e_index, depth);
  if (state_[i] == kDone) {
    append_clipped(memo_[i], lo, hi, out);
  } else {
    cross(e, lo, hi, depth, out);  // a cycle of whole arcs (flows themselves end): roll just this range
  }
}

// Computes the whole partition of crossing edge e's arc once.
template <class T>
void ArcPartitionsT<T>::memoise(int e_index, int depth) {
  const std::size_t i = static_cast<std::size_t>(e_index);
  if (state_[i] != kUnvisited) return;
  state_[i] = kInProgress;
  std::vector<Interval> whole;
  cross(g_.edges[i], T(0), T(1), depth, whole);
  memo_[i] = merged(std::move(whole));
  state_[i] = kDone;
}

// Appends the parts of [lo, hi] of crossing edge e's arc, rolled across the region it crosses into: each
// exit lune of that region takes a sub-range to a sub-range of its exit arc, along great circles from the
// apex.
template <class T>
void ArcPartitionsT<T>::cross(const Edge& e, const T& lo, const T& hi, int depth,
                              std::vector<Interval>& out) {
  if (depth > max_depth_) {
    throw Error("rest landscape: rolling did not end after " + std::to_string(max_depth_) +
                " vertex regions");
  }
  const auto& r = g_.regions[static_cast<std::size_t>(e.cross_to)];
  const V& p = r.apex;
  const V& c0 = normal(e.face_ab);
  const V& c1 = normal(e.face_ba);
  const std::size_t k = r.corners.size();
  std::vector<Interval> sub;
  for (std::size_t j = 0; j < k; ++j) {
    if (!r.arcs[j].exit) continue;
    T a = lo, b = hi;
    clip_interval<T>(V(T(r.sense) * p.cross(r.corners[j])), c0, c1, a, b);
    clip_interval<T>(V(T(r.sense) * r.corners[(j + 1) % k].cross(p)), c0, c1, a, b);
    if (!(b > a)) continue;
    const Edge& next = g_.edges[static_cast<std::size_t>(r.arcs[j].edge)];
    const T ta = param(next, V(p.cross(chord_point<T>(c0, c1, a))));
    const T tb = param(next, V(p.cross(chord_point<T>(c0, c1, b))));
    sub.clear();
    partition(r.arcs[j].edge, e.cross_to, std::min(ta, tb), std::max(ta, tb), depth + 1, sub);
    // Pull the parts back onto this arc along the same great circles (range ends map exactly).
    auto back = [&](const T& t) -> T {
      if (t == ta) return a;
      if (t == tb) return b;
      return std::clamp(cut<T>(V(p.cross(point(next, t))), c0, c1), a, b);
    };
    for (const Interval& s : sub) {
      const T t0 = back(s.t0);
      const T t1 = back(s.t1);
      out.push_back({std::min(t0, t1), std::max(t0, t1), s.face});
    }
  }
}

// Sorted, with neighbouring parts that roll to the same face joined (keeps memoised partitions short).
template <class T>
std::vector<IntervalT<T>> ArcPartitionsT<T>::merged(std::vector<Interval> parts) {
  std::sort(parts.begin(), parts.end(), [](const Interval& x, const Interval& y) { return x.t0 < y.t0; });
  std::vector<Interval> out;
  for (const Interval& s : parts) {
    if (!out.empty() && out.back().face == s.face && s.t0 <= out.back().t1) {
      out.back().t1 = std::max(out.back().t1, s.t1);
    } else {
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace repose::detail
