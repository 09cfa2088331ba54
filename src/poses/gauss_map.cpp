#include "gauss_map.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "repose/error.hpp"

namespace repose::detail {
namespace {

using Region = GaussMap::Region;
using Edge = GaussMap::Edge;

std::int64_t edge_key(int a, int b, std::size_t n) {
  return static_cast<std::int64_t>(std::min(a, b)) * static_cast<std::int64_t>(n) + std::max(a, b);
}

// A loop edge leaving a vertex: the next vertex of the face's loop, the face, and the (undirected) edge.
struct Spoke {
  int next, face, edge;
};

// Edges with their two faces; per vertex, its spokes.
void build_edges(const ConvexHull& hull, GaussMap& g, std::vector<std::vector<Spoke>>& out) {
  const std::size_t nv = hull.vertices.size();
  std::unordered_map<std::int64_t, int> edge_of;
  edge_of.reserve(3 * nv);
  g.edges.reserve(3 * nv);
  out.assign(nv, {});
  for (int f = 0; f < static_cast<int>(hull.faces.size()); ++f) {
    const std::vector<int>& loop = hull.faces[static_cast<std::size_t>(f)].loop;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k];
      const int b = loop[(k + 1) % loop.size()];
      const auto [it, fresh] = edge_of.try_emplace(edge_key(a, b, nv), static_cast<int>(g.edges.size()));
      out[static_cast<std::size_t>(a)].push_back({b, f, it->second});
      if (fresh) {
        Edge e;
        e.a = std::min(a, b);
        e.b = std::max(a, b);
        g.edges.push_back(e);
      }
      Edge& e = g.edges[static_cast<std::size_t>(it->second)];
      int& slot = a < b ? e.face_ab : e.face_ba;
      if (slot >= 0)
        throw Error("rest landscape: hull edge " + std::to_string(a) + "-" + std::to_string(b) +
                    " is used twice in the same direction");
      slot = f;
    }
  }
  for (const Edge& e : g.edges) {
    if (e.face_ab < 0 || e.face_ba < 0) {
      throw Error("rest landscape: hull edge " + std::to_string(e.a) + "-" + std::to_string(e.b) +
                  " has only one face (the hull is not closed)");
    }
  }
}

// The arc of edge (a, b): where h peaks on it, which end is lower, and whether rolling slides or crosses.
void describe_edge(const ConvexHull& hull, Edge& e) {
  const Vec3& a = hull.vertices[static_cast<std::size_t>(e.a)];
  const Vec3& b = hull.vertices[static_cast<std::size_t>(e.b)];
  edge_arc(a, b, e.height, e.top, e.along);
  const HullFace& fab = hull.faces[static_cast<std::size_t>(e.face_ab)];
  const HullFace& fba = hull.faces[static_cast<std::size_t>(e.face_ba)];
  e.top_inside = e.along.dot(fab.normal) * e.along.dot(fba.normal) < 0;
  e.low_face = fab.offset <= fba.offset ? e.face_ab : e.face_ba;
  // The foot parameter s = da/|b − a|², 1 − s = db/|b − a|². Within round-off of an end (the foot on a
  // vertex) sliding and crossing coincide (the arc's top is then that vertex's apex); slide.
  const double da = a.dot(a) - a.dot(b);
  const double db = b.dot(b) - a.dot(b);
  const double tol = 1e-12 * (b - a).squaredNorm();
  e.cross_to = db < -tol ? e.b : (da < -tol ? e.a : -1);
  e.saddle = e.top_inside && da > 0 && db > 0;
}

// Walks the faces around vertex v: from face f (loop ... → v → w → ...) across edge (v, w) to the face whose
// loop runs w → v, and so on. Corner i is that face's normal; arc i (corners i, i + 1) is edge (v, w).
void build_region(const ConvexHull& hull, const GaussMap& g, int v, const std::vector<Spoke>& mine,
                  Region& r) {
  const Vec3& pv = hull.vertices[static_cast<std::size_t>(v)];
  if (mine.empty()) throw Error("rest landscape: hull vertex " + std::to_string(v) + " is on no face");
  r.faces.reserve(mine.size());
  r.corners.reserve(mine.size());
  r.arcs.reserve(mine.size());
  const Spoke* spoke = &mine.front();
  for (std::size_t step = 0; step < mine.size(); ++step) {
    r.faces.push_back(spoke->face);
    r.corners.push_back(hull.faces[static_cast<std::size_t>(spoke->face)].normal);
    r.arcs.push_back(
        {spoke->edge, (pv - hull.vertices[static_cast<std::size_t>(spoke->next)]).normalized(), false});
    const int face = other_face(g.edges[static_cast<std::size_t>(spoke->edge)], spoke->face);
    const auto it = std::find_if(mine.begin(), mine.end(), [&](const Spoke& o) { return o.face == face; });
    if (it == mine.end()) {
      throw Error("rest landscape: the faces around hull vertex " + std::to_string(v) + " do not close");
    }
    spoke = &*it;
    if (face == r.faces.front()) break;
  }
  const int face = spoke->face;
  if (face != r.faces.front() || r.faces.size() != mine.size()) {
    throw Error("rest landscape: the faces around hull vertex " + std::to_string(v) + " do not form one fan");
  }

  const std::size_t k = r.corners.size();
  // The lune orientation is the same for every arc of a convex polygon; take it from the longest arc.
  double best = -1;
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3 c = r.corners[i].cross(r.corners[(i + 1) % k]);
    if (c.norm() > best) {
      best = c.norm();
      r.sense = r.arcs[i].normal.dot(c) >= 0 ? 1.0 : -1.0;
    }
  }
  // An apex on a corner (the centre of mass projects onto v in that face) leaves the lune planes through
  // that corner undefined; snap it there, where the two arcs at the corner pass through it (not exits).
  r.apex = pv.normalized();
  std::size_t snapped = k;
  for (std::size_t i = 0; i < k; ++i) {
    if ((r.apex - r.corners[i]).norm() < 1e-10) {
      r.apex = r.corners[i];
      snapped = i;
    }
  }
  for (std::size_t i = 0; i < k; ++i) {
    const bool at_snap = snapped < k && (i == snapped || (i + 1) % k == snapped);
    r.arcs[i].exit = !at_snap && r.arcs[i].normal.dot(r.apex) > 0;
  }
}

}  // namespace

std::shared_ptr<GaussMap> build_gauss_map(const ConvexHull& hull, double length) {
  auto g = std::make_shared<GaussMap>();
  g->balance_tol = 1e-12 * length;
  std::vector<std::vector<Spoke>> out;
  build_edges(hull, *g, out);
  for (const HullFace& f : hull.faces) g->face_normals.push_back(f.normal);
  for (Edge& e : g->edges) describe_edge(hull, e);
  g->regions.resize(hull.vertices.size());
  for (int v = 0; v < static_cast<int>(hull.vertices.size()); ++v) {
    build_region(hull, *g, v, out[static_cast<std::size_t>(v)], g->regions[static_cast<std::size_t>(v)]);
  }
  return g;
}

int other_face(const GaussMap::Edge& e, int face) { return face == e.face_ab ? e.face_ba : e.face_ab; }

int slide_end(const GaussMap& g, const GaussMap::Edge& e, double s) {
  if (!e.top_inside) return e.low_face;
  const bool ab_positive = e.along.dot(g.face_normals[static_cast<std::size_t>(e.face_ab)]) > 0;
  return (s > 0) == ab_positive ? e.face_ab : e.face_ba;
}

}  // namespace repose::detail
