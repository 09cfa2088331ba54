// The landscape's Gauss map replayed in another scalar (docs/inverse-design.md): the structure the double
// map found (each face's route, which arcs cross or slide, the balance sides, where apexes snap) kept, its
// geometry recomputed from hull vertices given in T, so that an automatic-differentiation type carries the
// derivatives of every apex, arc and face normal with respect to the vertices and the centre of mass.
#pragma once

#include <algorithm>
#include <vector>

#include "../poses/gauss_map.hpp"
#include "repose/geometry/hull.hpp"

namespace repose::detail {

// The outward normal of a planar loop by Newell's formula (the sum of its edges' cross products, which for a
// triangle is the cross product of two edges and for a planar polygon any fan's sum): smooth in the vertices.
template <class T>
Eigen::Matrix<T, 3, 1> newell_normal(const std::vector<Eigen::Matrix<T, 3, 1>>& vertices,
                                     const std::vector<int>& loop) {
  Eigen::Matrix<T, 3, 1> n = Eigen::Matrix<T, 3, 1>::Zero();
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const auto& a = vertices[static_cast<std::size_t>(loop[k])];
    const auto& b = vertices[static_cast<std::size_t>(loop[(k + 1) % loop.size()])];
    n += a.cross(b);
  }
  return n.normalized();
}

// `g` (built from `hull`, body frame) with its geometry from `vertices` (hull vertex i at vertices[i], body
// frame: the centre of mass at the origin).
template <class T>
GaussMapT<T> replay_map(const GaussMap& g, const ConvexHull& hull,
                        const std::vector<Eigen::Matrix<T, 3, 1>>& vertices) {
  using V = Eigen::Matrix<T, 3, 1>;
  GaussMapT<T> m;
  m.balance_tol = g.balance_tol;
  m.face_normals.reserve(hull.faces.size());
  for (const HullFace& f : hull.faces) m.face_normals.push_back(newell_normal<T>(vertices, f.loop));
  m.edges.resize(g.edges.size());
  for (std::size_t i = 0; i < g.edges.size(); ++i) {
    const auto& e = g.edges[i];
    auto& x = m.edges[i];
    x.a = e.a, x.b = e.b, x.face_ab = e.face_ab, x.face_ba = e.face_ba;
    x.top_inside = e.top_inside, x.low_face = e.low_face, x.cross_to = e.cross_to, x.saddle = e.saddle;
    edge_arc<T>(vertices[static_cast<std::size_t>(e.a)], vertices[static_cast<std::size_t>(e.b)], x.height,
                x.top, x.along);
  }
  m.regions.resize(g.regions.size());
  for (std::size_t v = 0; v < g.regions.size(); ++v) {
    const auto& r = g.regions[v];
    auto& x = m.regions[v];
    x.faces = r.faces;
    x.sense = r.sense;
    x.corners.reserve(r.faces.size());
    for (const int f : r.faces) x.corners.push_back(m.face_normals[static_cast<std::size_t>(f)]);
    x.arcs.reserve(r.arcs.size());
    for (const auto& arc : r.arcs) {
      const auto& e = g.edges[static_cast<std::size_t>(arc.edge)];
      const int w = e.a == static_cast<int>(v) ? e.b : e.a;
      const V along = vertices[v] - vertices[static_cast<std::size_t>(w)];
      x.arcs.push_back({arc.edge, V(along.normalized()), arc.exit});
    }
    // An apex snapped onto a corner stays there (build_region): the structure, not the geometry, says so.
    const auto snapped = std::find(r.corners.begin(), r.corners.end(), r.apex);
    x.apex = snapped != r.corners.end() ? x.corners[static_cast<std::size_t>(snapped - r.corners.begin())]
                                        : V(vertices[v].normalized());
  }
  m.routes.resize(g.routes.size());
  for (std::size_t f = 0; f < g.routes.size(); ++f) {
    const auto& r = g.routes[f];
    auto& x = m.routes[f];
    x.reach = r.reach, x.balance = r.balance, x.side[0] = r.side[0], x.side[1] = r.side[1], x.edge = r.edge;
    if (r.balance) x.unstable = m.edges[static_cast<std::size_t>(r.edge)].along;
  }
  return m;
}

}  // namespace repose::detail
