// The vertex sets of the contact phase near the wall, found by walks over the hull's edge graph
// (ConvexHull::neighbors) instead of scans, so a step costs about the vertices near the wall, not the hull's
// size (docs/method.md, "No overlap, ever").
#include <algorithm>
#include <cassert>

#include "contact.hpp"

namespace repose::sim {

// The hull vertices at most `level` above the wall at orientation `qq` about the current support, in `out`
// (in index order if `sorted`: the order of a contact list matters to its fit's round-off and to ties): a
// walk from the lowest vertex over the hull's edge graph (a linear function's sublevel sets on a convex
// polytope are connected), so the cost is the set and its border. The walk runs the event tolerance beyond
// `level` and the exact test (the same arithmetic as heights()) picks the members.
void Contact::vertices_below(const Quat& qq, double level, std::vector<int>& out, bool sorted) {
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  const double base = support_.world.z() - r3.dot(support_.body);  // height = base + r3·p
  out.clear();
  for (int k : walks_.walk(-r3, -(level + run_.tol.event - base)))
    if (height_of(r3, k) <= level) out.push_back(k);
  if (sorted) walks_.sort_ids(out);
}

// The same set, sorted, when it is known to lie within `among` (a superset, in increasing order, as the
// step's candidates are kept: picking keeps the order, so no set picked a step's many times is sorted): the
// members are picked from it by the same test, with no walk. The walk to the lowest vertex is still made
// (later walks start there).
void Contact::vertices_below_among(const Quat& qq, double level, std::span<const int> among,
                                   std::vector<int>& out) {
  assert(std::is_sorted(among.begin(), among.end()));
  const Vec3 r3 = qq.toRotationMatrix().row(2).transpose();
  walks_.lowest_along(-r3);
  out.clear();
  for (int k : among)
    if (height_of(r3, k) <= level) out.push_back(k);
}

// Whether the band picked from the step's candidates is the one a walk finds (the sanitizer build checks
// every such pick).
bool Contact::band_matches_walk(double level, const std::vector<int>& picked) {
  std::vector<int> walked;
  vertices_below(run_.q, level, walked, true);
  return walked == picked;
}

// Whether the step's candidates hold every vertex a walk to `level` at orientation qq finds (the sanitizer
// build checks every reuse of the candidates).
bool Contact::candidates_cover(const Quat& qq, double level) {
  std::vector<int> walked;
  vertices_below(qq, level, walked, false);
  std::vector<char> kept(z_.size(), 0);
  for (int k : event_candidates_) kept[static_cast<std::size_t>(k)] = 1;
  return std::all_of(walked.begin(), walked.end(), [&](int k) { return kept[static_cast<std::size_t>(k)]; });
}

// The height of the lowest hull vertex at the run's orientation (a walk downhill from the last lowest).
double Contact::lowest_height() {
  const Vec3 r3 = run_.q.toRotationMatrix().row(2).transpose();
  return height_of(r3, walks_.lowest_along(-r3));
}

}  // namespace repose::sim
