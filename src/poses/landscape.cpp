// Exact basins of quasi-static rolling on the Gauss map of the convex hull (see landscape.hpp). The pieces:
// gauss_map (the map and how rolling crosses or slides on each edge's arc), rolling (one direction, and the
// tie rule at unstable balances), arc_partitions (whole arcs and the areas of region pieces), spherical (the
// spherical geometry they share). This file decides where each face tips and assembles the landscape.
#include "repose/poses/landscape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "arc_partitions.hpp"
#include "gauss_map.hpp"
#include "repose/error.hpp"
#include "rolling.hpp"

namespace repose {
namespace {

using detail::ArcPartitions;
using detail::build_gauss_map;
using detail::Exit;
using detail::GaussMap;
using detail::kCornerTol;
using detail::leave_region;
using detail::other_face;
using detail::rest_for;
using detail::roll;
using detail::RollEnd;
using Region = GaussMap::Region;
using Edge = GaussMap::Edge;

// ---- faces ------------------------------------------------------------------------------------------------

// Where an unstable face tips: the steepest descent of h at n_f is away from the point of the face polygon
// nearest the centre of mass's projection. An edge: along its arc (monotone) to the neighbouring face; a
// corner u: into u's region along the great circle from u's apex, and on as rolling goes (which may end on a
// balance).
RollEnd tip_face(const ConvexHull& hull, const GaussMap& g, ArcPartitions& arcs, int f) {
  const HullFace& face = hull.faces[static_cast<std::size_t>(f)];
  const Vec3 p = face.offset * face.normal;
  double best = std::numeric_limits<double>::infinity();
  int best_a = -1, best_b = -1;
  double best_t = 0;
  for (std::size_t k = 0; k < face.loop.size(); ++k) {
    const int a = face.loop[k];
    const int b = face.loop[(k + 1) % face.loop.size()];
    const Vec3& va = hull.vertices[static_cast<std::size_t>(a)];
    const Vec3 ab = hull.vertices[static_cast<std::size_t>(b)] - va;
    const double t = std::clamp((p - va).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    const double dist = (va + t * ab - p).norm();
    if (dist < best) {
      best = dist;
      best_a = a;
      best_b = b;
      best_t = t;
    }
  }
  if (best_t > 0 && best_t < 1) {
    for (const GaussMap::Arc& arc : g.regions[static_cast<std::size_t>(best_a)].arcs) {
      const Edge& e = g.edges[static_cast<std::size_t>(arc.edge)];
      if (e.a == best_b || e.b == best_b) return {other_face(e, f)};
    }
    throw Error("rest landscape: face " + std::to_string(f) + " has an edge missing from the Gauss map");
  }
  const int u = best_t <= 0 ? best_a : best_b;
  // With the centre of mass right above u (u's apex snapped onto n_f) the face balances on u and the great
  // circle is undefined: tip along the bisector of u's corner at n_f.
  Vec3 d = face.normal;
  const Region& r = g.regions[static_cast<std::size_t>(u)];
  if (r.apex == d) {
    const std::size_t k = r.corners.size();
    const std::size_t i =
        static_cast<std::size_t>(std::find(r.faces.begin(), r.faces.end(), f) - r.faces.begin());
    const Vec3& prev = r.corners[(i + k - 1) % k];
    const Vec3& next = r.corners[(i + 1) % k];
    const Vec3 bisector = (prev - prev.dot(d) * d).normalized() + (next - next.dot(d) * d).normalized();
    d = (d + 1e-6 * bisector.normalized()).normalized();
  }
  // Through a crossing arc the memoised partition answers at once, away from its parts' ends.
  const Exit exit = leave_region(g, u, d);
  const Edge& e = g.edges[static_cast<std::size_t>(exit.edge)];
  if (e.cross_to >= 0 && e.cross_to != u) {
    const int face = arcs.face_at(exit.edge, exit.point);
    if (face >= 0) return {face};
  }
  return roll(g, u, d);
}

// Every face's route, in order of rising h at the face normal: a face tips only to lower faces, which then
// already know their reach (the chain is followed in case round-off breaks the order).
void resolve_routes(const Particle& particle, GaussMap& g, ArcPartitions& arcs) {
  const std::size_t nf = particle.hull.faces.size();
  g.routes.assign(nf, {});
  for (std::size_t f = 0; f < nf; ++f) {
    if (particle.face_stability_margin[f] > 0) g.routes[f].reach = static_cast<int>(f);
  }
  std::vector<int> order(nf);
  for (std::size_t f = 0; f < nf; ++f) order[f] = static_cast<int>(f);
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
    return particle.hull.faces[static_cast<std::size_t>(x)].offset <
           particle.hull.faces[static_cast<std::size_t>(y)].offset;
  });
  std::vector<int> path;
  for (int f : order) {
    path.clear();
    int x = f;
    while (g.routes[static_cast<std::size_t>(x)].reach < 0) {
      path.push_back(x);
      if (path.size() > nf) {
        throw Error("rest landscape: faces tip over in a cycle (from face " + std::to_string(f) + ")");
      }
      const RollEnd end = tip_face(particle.hull, g, arcs, x);
      if (end.face >= 0) {
        x = end.face;
        continue;
      }
      GaussMap::FaceRoute& route = g.routes[static_cast<std::size_t>(x)];
      route.reach = x;
      route.balance = true;
      route.unstable = end.unstable;
      route.side[0] = end.side[0];
      route.side[1] = end.side[1];
      route.edge = end.edge;
    }
    for (int y : path)
      g.routes[static_cast<std::size_t>(y)].reach = g.routes[static_cast<std::size_t>(x)].reach;
  }
}

}  // namespace

RestLandscape compute_rest_landscape(const Particle& particle) {
  const ConvexHull& hull = particle.hull;
  if (particle.face_stability_margin.size() != hull.faces.size()) {
    throw Error("rest landscape: " + particle.name + ": face stability margins do not match the hull");
  }
  RestLandscape land;
  const std::shared_ptr<GaussMap> built = build_gauss_map(hull, particle.length);
  const GaussMap& g = *built;
  ArcPartitions arcs(g);
  resolve_routes(particle, *built, arcs);
  land.gauss_map = built;
  // A face normal as the starting direction itself (quasi_static_rest_face returns this for it).
  land.face_rest.resize(hull.faces.size());
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    land.face_rest[f] = rest_for(g, static_cast<int>(f), g.face_normals[f]);
  }

  // Areas by the stable face a piece rolls to (pieces reaching a balance face are split there).
  std::vector<double> area(hull.faces.size(), 0.0);
  for (int v = 0; v < static_cast<int>(g.regions.size()); ++v) arcs.add_region(v, area);
  land.basin_probability.assign(area.size(), 0.0);
  for (std::size_t f = 0; f < area.size(); ++f) land.basin_probability[f] = area[f] / (4 * std::numbers::pi);

  for (const Edge& e : g.edges) {
    if (!e.saddle) continue;
    Saddle s;
    s.vertex_a = e.a;
    s.vertex_b = e.b;
    s.face_a = e.face_ab;
    s.face_b = e.face_ba;
    s.height = e.height;
    s.down = e.top;
    // Rolling off the saddle starts on the arc between its top and the face's normal.
    s.rest_a =
        rest_for(g, e.face_ab, (e.top + g.face_normals[static_cast<std::size_t>(e.face_ab)]).normalized());
    s.rest_b =
        rest_for(g, e.face_ba, (e.top + g.face_normals[static_cast<std::size_t>(e.face_ba)]).normalized());
    land.saddles.push_back(s);
  }
  return land;
}

namespace {

// The landscape's Gauss map, after checking the direction and that the landscape is `particle`'s.
const GaussMap& checked_map(const Particle& particle, const RestLandscape& landscape, const Vec3& down) {
  if (!down.allFinite() || down.norm() == 0) {
    throw Error("quasi_static_rest_face: the down direction must be finite and nonzero");
  }
  const GaussMap* g = landscape.gauss_map.get();
  if (g == nullptr || g->regions.size() != particle.hull.vertices.size() ||
      g->routes.size() != particle.hull.faces.size() ||
      landscape.face_rest.size() != particle.hull.faces.size()) {
    throw Error("quasi_static_rest_face: the landscape was not computed for " + particle.name);
  }
  return *g;
}

// Rolling from unit direction d, which lies in the region of hull vertex v (v is lowest along d).
int rest_face_from(const GaussMap& g, const RestLandscape& landscape, const Vec3& d, int v) {
  // On a face normal (a corner of v's region, within round-off) the face decides where to tip, not v.
  const Region& r = g.regions[static_cast<std::size_t>(v)];
  for (std::size_t i = 0; i < r.corners.size(); ++i) {
    if ((d - r.corners[i]).norm() < kCornerTol) {
      return landscape.face_rest[static_cast<std::size_t>(r.faces[i])];
    }
  }
  const RollEnd end = roll(g, v, d);
  // A balance reached directly leaves on the side of d itself; a face reached goes on along its route.
  const int face = end.face >= 0 ? end.face : end.side[end.unstable.dot(d) > 0 ? 1 : 0];
  return rest_for(g, face, d);
}

}  // namespace

int quasi_static_rest_face(const Particle& particle, const RestLandscape& landscape, const Vec3& down) {
  const GaussMap& g = checked_map(particle, landscape, down);
  const Vec3 d = down.normalized();
  return rest_face_from(g, landscape, d, particle.hull.support_vertex(d));
}

int quasi_static_rest_face(const Particle& particle, const RestLandscape& landscape, const Vec3& down,
                           int& start_vertex) {
  const GaussMap& g = checked_map(particle, landscape, down);
  if (start_vertex < 0 || start_vertex >= static_cast<int>(particle.hull.vertices.size())) {
    throw Error("quasi_static_rest_face: start vertex " + std::to_string(start_vertex) +
                " is not a hull vertex");
  }
  const Vec3 d = down.normalized();
  start_vertex = particle.hull.support_vertex_from(d, start_vertex);
  return rest_face_from(g, landscape, d, start_vertex);
}

}  // namespace repose
