#include "rolling.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "repose/error.hpp"

namespace repose::detail {
namespace {
using Region = GaussMap::Region;
using Edge = GaussMap::Edge;
}  // namespace

// Where the great circle from v's apex through d (in or on v's region) leaves the region: the first exit
// plane it crosses. normal·(cos θ p + sin θ t) = A cos θ + B sin θ with A > 0 vanishes once on (0, π), at cot
// θ = −B/A; the smallest θ has the largest −B/A.
Exit leave_region(const GaussMap& g, int v, const Vec3& d) {
  const Region& r = g.regions[static_cast<std::size_t>(v)];
  const Vec3& p = r.apex;
  Vec3 t = d - d.dot(p) * p;
  // At the apex itself (a maximum of h) every direction descends; any fixed one will do.
  t = t.norm() > 1e-14 ? Vec3(t.normalized()) : p.unitOrthogonal();
  double best = -std::numeric_limits<double>::infinity();
  const GaussMap::Arc* exit = nullptr;
  for (const GaussMap::Arc& arc : r.arcs) {
    if (!arc.exit) continue;
    const double key = -arc.normal.dot(t) / arc.normal.dot(p);
    if (key > best) {
      best = key;
      exit = &arc;
    }
  }
  if (exit == nullptr) throw Error("rest landscape: vertex region " + std::to_string(v) + " has no exit");
  const double theta = std::atan2(exit->normal.dot(p), -exit->normal.dot(t));
  return {exit->edge, std::cos(theta) * p + std::sin(theta) * t};
}

// From direction d in (or on the boundary of) vertex v's region, rolls region by region until the arc motion
// ends. Two exact cases matter when a whole face's worth of directions follows one path (tip_face):
// - leaving a region through a face normal (a corner: two arcs meet there) reaches that face, which decides
//   (otherwise round-off would pick one of the two arcs, and on a crossing arc roll on past the face);
// - leaving through a sliding arc's top (lever arm of the weight about the edge within balance_tol) is an
//   unstable balance. The great circle from the last region's apex meets the arc at its top at a right angle,
//   so that last stretch lies on the great circle u·d = 0 (u: the arc's tangent at the top) and cannot tell
//   the sides apart. If an earlier stretch of this path was off it, the flow leaves on that side (the side it
//   came from); if the whole path lies on it, the balance is returned and the caller picks the side.
RollEnd roll(const GaussMap& g, int v, Vec3 d) {
  const int max_steps = static_cast<int>(g.regions.size()) + kMaxDepthSlack;
  std::vector<Vec3> path;  // where the path entered each region (a stretch is a great-circle arc from there)
  for (int step = 0; step < max_steps; ++step) {
    path.push_back(d);
    const Exit exit = leave_region(g, v, d);
    const Edge& e = g.edges[static_cast<std::size_t>(exit.edge)];
    for (const int face : {e.face_ab, e.face_ba}) {
      const Vec3& n = g.face_normals[static_cast<std::size_t>(face)];
      if ((exit.point - n).norm() < kCornerTol && (d - n).norm() >= kCornerTol) return {face};
    }
    if (e.cross_to < 0 || e.cross_to == v) {
      const double s = e.along.dot(exit.point);
      if (!(e.top_inside && std::abs(s) * e.height <= g.balance_tol)) return {slide_end(g, e, s)};
      for (auto x = path.rbegin(); x != path.rend(); ++x) {
        const double side = e.along.dot(*x);
        if (std::abs(side) * e.height > g.balance_tol) return {slide_end(g, e, side)};
      }
      return {-1, e.along, {slide_end(g, e, -1), slide_end(g, e, 1)}, exit.edge};
    }
    v = e.cross_to;
    d = exit.point;
  }
  throw Error("rest landscape: rolling did not end after " + std::to_string(max_steps) + " vertex regions");
}

// The stable face reached from face f's normal by a flow that started at `start`: follows f's route, and at
// each balance face takes the side of `start`.
int rest_for(const GaussMap& g, int f, const Vec3& start) {
  for (std::size_t step = 0; step <= g.routes.size(); ++step) {
    const GaussMap::FaceRoute& r =
        g.routes[static_cast<std::size_t>(g.routes[static_cast<std::size_t>(f)].reach)];
    if (!r.balance) return g.routes[static_cast<std::size_t>(f)].reach;
    f = r.side[r.unstable.dot(start) > 0 ? 1 : 0];
  }
  throw Error("rest landscape: balances lead to each other in a cycle");
}

}  // namespace repose::detail
