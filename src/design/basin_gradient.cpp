// The basins' gradient with respect to the centre of mass (basin_gradient.hpp): the landscape's Gauss map
// (its structure: routes, crossing and sliding arcs, balance sides) with its geometry recomputed in Eigen's
// AutoDiffScalar, the centre of mass's displacement c the three variables, then the same partitions and
// areas.
#include "repose/design/basin_gradient.hpp"

#include <algorithm>
#include <numbers>
#include <unsupported/Eigen/AutoDiff>

#include "../poses/arc_partitions_impl.hpp"
#include "repose/error.hpp"

namespace repose {

using Ad = Eigen::AutoDiffScalar<Eigen::Vector3d>;

namespace detail {
template class ArcPartitionsT<Ad>;
}  // namespace detail

namespace {

using AdVec = Eigen::Matrix<Ad, 3, 1>;

AdVec constant(const Vec3& v) {
  AdVec out;
  for (int k = 0; k < 3; ++k) out[k] = Ad(v[k], Eigen::Vector3d::Zero());
  return out;
}

// The map of `g` with the body displaced so that its centre of mass moves by c (at c = 0, the variables):
// every hull vertex at v − c; face normals and arc planes do not move with it.
detail::GaussMapT<Ad> map_with_com(const detail::GaussMap& g, const ConvexHull& hull) {
  AdVec c;
  for (int k = 0; k < 3; ++k) c[k] = Ad(0.0, 3, k);
  std::vector<AdVec> vertices(hull.vertices.size());
  for (std::size_t i = 0; i < hull.vertices.size(); ++i) vertices[i] = constant(hull.vertices[i]) - c;

  detail::GaussMapT<Ad> m;
  m.balance_tol = g.balance_tol;
  for (const Vec3& n : g.face_normals) m.face_normals.push_back(constant(n));
  m.edges.resize(g.edges.size());
  for (std::size_t i = 0; i < g.edges.size(); ++i) {
    const auto& e = g.edges[i];
    auto& x = m.edges[i];
    x.a = e.a, x.b = e.b, x.face_ab = e.face_ab, x.face_ba = e.face_ba;
    x.top_inside = e.top_inside, x.low_face = e.low_face, x.cross_to = e.cross_to, x.saddle = e.saddle;
    detail::edge_arc(vertices[static_cast<std::size_t>(e.a)], vertices[static_cast<std::size_t>(e.b)],
                     x.height, x.top, x.along);
  }
  m.regions.resize(g.regions.size());
  for (std::size_t v = 0; v < g.regions.size(); ++v) {
    const auto& r = g.regions[v];
    auto& x = m.regions[v];
    x.faces = r.faces;
    x.sense = r.sense;
    for (const Vec3& corner : r.corners) x.corners.push_back(constant(corner));
    for (const auto& arc : r.arcs) x.arcs.push_back({arc.edge, constant(arc.normal), arc.exit});
    // An apex snapped onto a corner stays there (build_region): the structure, not the geometry, says so.
    const auto snapped = std::find(r.corners.begin(), r.corners.end(), r.apex);
    x.apex = snapped != r.corners.end() ? x.corners[static_cast<std::size_t>(snapped - r.corners.begin())]
                                        : AdVec(vertices[v].normalized());
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

}  // namespace

BasinGradient basin_com_gradient(const Particle& particle, const RestLandscape& landscape) {
  const detail::GaussMap* g = landscape.gauss_map.get();
  if (g == nullptr || g->regions.size() != particle.hull.vertices.size() ||
      g->routes.size() != particle.hull.faces.size())
    throw Error("basin gradient: the landscape was not computed for " + particle.name);
  const detail::GaussMapT<Ad> m = map_with_com(*g, particle.hull);
  detail::ArcPartitionsT<Ad> arcs(m);
  std::vector<Ad> area(particle.hull.faces.size(), Ad(0.0, Eigen::Vector3d::Zero()));
  for (int v = 0; v < static_cast<int>(m.regions.size()); ++v) arcs.add_region(v, area);
  BasinGradient out;
  for (const Ad& a : area) {
    out.probability.push_back(a.value() / (4 * std::numbers::pi));
    // An area that no piece reached has no derivative vector (Eigen leaves it empty).
    out.d_com.push_back(a.derivatives().size() == 3 ? Vec3(a.derivatives() / (4 * std::numbers::pi))
                                                    : Vec3::Zero());
  }
  return out;
}

}  // namespace repose
