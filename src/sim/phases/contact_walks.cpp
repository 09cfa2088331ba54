// The vertex sets of the contact phase near the wall, found by walks over the hull's edge graph
// (ConvexHull::neighbors) instead of scans, so a step costs about the vertices near the wall, not the hull's
// size (docs/method.md, "No overlap, ever").
#include <algorithm>
#include <bit>
#include <cstdint>

#include "contact.hpp"

namespace repose::sim {

// The hull vertices at most `level` above the wall at orientation `qq` about the current support, in `out`
// (in index order if `sorted`: the order of a contact list matters to its fit's round-off and to ties): a
// walk from the lowest vertex over the hull's edge graph (a linear function's sublevel sets on a convex
// polytope are connected), so the cost is the set and its border. The walk runs the event tolerance beyond
// `level` and the exact test (the same arithmetic as heights()) picks the members.
void Contact::vertices_below(const Quat& qq, double level, std::vector<int>& out, bool sorted) {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  const Vec3 down = -r3;
  const ConvexHull& hull = run_.particle.hull;
  lowest_vertex_ = hull.support_vertex_from(down, lowest_vertex_);
  const double base = support_.world.z() - r3.dot(support_.body);  // height = base + r3·p
  walk_out_.clear();
  hull.vertices_at_least(down, -(level + run_.tol.event - base), lowest_vertex_, walk_out_, walk_visited_);
  out.clear();
  for (int k : walk_out_)
    if (height_of(r3, k) <= level) out.push_back(k);
  if (sorted) sort_vertex_ids(out);
}

// The same set, sorted, when it is known to lie within `among` (a superset): the members are picked from it
// by the same test, with no walk. The walk to the lowest vertex is still made (later walks start there).
void Contact::vertices_below_among(const Quat& qq, double level, std::span<const int> among,
                                   std::vector<int>& out) {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  lowest_vertex_ = run_.particle.hull.support_vertex_from(-r3, lowest_vertex_);
  out.clear();
  for (int k : among)
    if (height_of(r3, k) <= level) out.push_back(k);
  sort_vertex_ids(out);
}

// Whether the band picked from the step's candidates is the one a walk finds (the sanitizer build checks
// every such pick).
bool Contact::band_matches_walk(double level, const std::vector<int>& picked) {
  std::vector<int> walked;
  vertices_below(run_.q, level, walked, true);
  return walked == picked;
}

// Distinct hull vertex indices into increasing order. A band of hundreds is written into a bitset of the
// hull's vertices and read back in order: linear in the set plus its span/64 words, where a comparison sort
// costs ~n·log n (a tenth of a 10,000-vertex grain's settle went to std::sort).
void Contact::sort_vertex_ids(std::vector<int>& ids) {
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

// The height of the lowest hull vertex at the run's orientation (a walk downhill from the last lowest).
double Contact::lowest_height() {
  const Vec3 r3 = run_.q.toRotationMatrix().row(2).transpose();
  lowest_vertex_ = run_.particle.hull.support_vertex_from(-r3, lowest_vertex_);
  return height_of(r3, lowest_vertex_);
}

}  // namespace repose::sim
