// Internal: the per-point arrays of the contact solvers (the arms, the reactions, the modes), held inline up
// to tol::kInlinePoints points so that the contact forces, solved at every evaluation of a frictional
// segment's rates, allocate nothing (issue 49); a problem with more points grows on the heap.
#pragma once

#include <boost/container/small_vector.hpp>
#include <span>

#include "../tolerances.hpp"

namespace repose::sim {

template <class T>
using PointList = boost::container::small_vector<T, tol::kInlinePoints>;

/// A point list as the solvers' span parameters take it (small_vector's iterators are not C++20 contiguous
/// iterators, so it does not convert by itself).
template <class T>
std::span<const T> view(const PointList<T>& list) {
  return {list.data(), list.size()};
}

}  // namespace repose::sim
