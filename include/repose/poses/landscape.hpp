// The quasi-static rest-pose landscape of a particle's convex hull, computed exactly on the Gauss map.
//
// Let d be the body-frame unit "down" direction (from the body towards the wall). A particle touching the
// wall has its centre of mass at height h(d) = max over hull vertices v of v·d (the support function; the
// centre of mass is the body-frame origin). Quasi-static rolling, without momentum, is the steepest descent
// of h on the sphere of down directions:
// - on one vertex v, d moves along the great circle away from v/|v| (the body pivots about v);
// - on an edge, if the centre of mass's foot on the edge line lies between its ends, d moves along the edge's
//   arc away from the point where the centre of mass is above the edge line (the body rotates about the
//   edge); if the foot lies beyond one end, the other end lifts and the body pivots on to that end's vertex;
// - at a face normal it stops if the face is statically stable (Particle::face_stability_margin > 0, as in
//   the settling engine), else it tips over the edge or corner of the face nearest the centre of mass's
//   projection.
// Each stable face owns the set of down directions that roll to it (its basin); for a direction drawn
// uniformly on the sphere, the basin's area / 4π is the probability of that rest.
//
// Ties (unstable balances). A flow can stop exactly on an unstable balance: the top of an edge's arc, where h
// is a minimum along the way the flow came but a maximum along the arc (the body balances on the edge). For
// one direction that is measure zero, but on a mesh with a mirror plane that flows slide into (the built-in
// ellipsoid: flows slide into the plane z = 0 and along it to a balance on one of 8 edges near the middle
// axis ±y; measured, 7.2 % of directions for n = 10, 2.6 % for n = 22) a set of positive area ends there. A
// real particle leaves by an infinitesimal perturbation; without momentum the natural side is the one it came
// from. The rule: the flow leaves along the arc on the side of the last point of its path off the great
// circle through the balance perpendicular to the arc (u·d = 0, u the arc's unit tangent at its top). The
// path is followed exactly from the last face normal it passed (within the tipping from that face); before
// that, the starting direction stands in for it (exact when the path does not cross that great circle, as for
// a mirror plane, which flows reach but never cross). So mirror-image starting directions rest on
// mirror-image faces, and mirror-image faces have equal basins (to ~1e-15). compute_rest_landscape splits the
// pieces of starting directions that reach such a balance by that great circle, and quasi_static_rest_face
// applies the same rule, so the two agree. A balance is detected when the weight's lever arm about the edge
// is within 1e-12·L (L = Particle::length), and a face normal is reached within 1e-12 rad; a path exactly on
// that great circle from its start (measure zero) goes to a fixed side. Limits: a stable face lying in a
// mirror plane belongs to neither side (it keeps its own basin), and balances that are not arc tops are not
// special-cased (a face balanced on a corner, margin 0, tips along the corner's bisector).
#pragma once

#include <memory>
#include <vector>

#include "repose/geometry/types.hpp"
#include "repose/model/particle.hpp"

namespace repose {

/// A saddle of h: an edge whose arc has an interior maximum of h, i.e. the centre of mass can balance on the
/// edge (above the edge line, between its end points). Rolling leaves it towards either of its two faces.
struct Saddle {
  int vertex_a = -1, vertex_b = -1;  ///< hull vertex indices of the edge
  int face_a = -1, face_b = -1;      ///< the two hull faces sharing the edge
  double height = 0;         ///< h at the saddle: distance from the centre of mass to the edge line (length)
  Vec3 down = Vec3::Zero();  ///< body-frame unit down direction at the saddle
  int rest_a = -1, rest_b = -1;  ///< stable faces reached by rolling from the saddle towards face_a / face_b
                                 ///< (from the midpoint of the arc between the saddle and the face's normal)
};

namespace detail {
struct GaussMap;  // the hull's Gauss map, shared by compute_rest_landscape and quasi_static_rest_face
}

/// Where quasi-static rolling takes every down direction.
struct RestLandscape {
  /// Per hull face: the stable face rolling from its normal ends on (itself if stable). An unstable face
  /// whose tipping ends on an unstable balance sends other directions that reach it to either side (see Ties
  /// above); this is the rest for its own normal as the starting direction.
  std::vector<int> face_rest;
  std::vector<double>
      basin_probability;        ///< per hull face: area of its basin / 4π (0 if unstable); sums to 1
  std::vector<Saddle> saddles;  ///< every saddle of h, in no particular order
  std::shared_ptr<const detail::GaussMap> gauss_map;  ///< internal, for quasi_static_rest_face
};

/// The exact rest landscape of `particle`'s convex hull: basin areas are sums of convex spherical polygons
/// (no sampling; they sum to 1 within ~1e-14). Cost about linear in the hull size: a few milliseconds for a
/// 10,000-triangle irregular grain, ~40 ms for a 10,000-triangle ellipsoid (every vertex on the hull). Throws
/// repose::Error if the hull's faces do not form a closed polyhedron or a rolling chain does not end.
RestLandscape compute_rest_landscape(const Particle& particle);

/// The stable hull face quasi-static rolling from the body-frame direction `down` (any finite nonzero length)
/// ends on, following the same rules one step at a time. `landscape` must be
/// compute_rest_landscape(particle). Throws repose::Error for a bad direction or a landscape of another
/// particle.
int quasi_static_rest_face(const Particle& particle, const RestLandscape& landscape, const Vec3& down);

/// The same, for a sequence of nearby directions (a drop's orientation after each step): the hull vertex
/// lowest along `down` is found by a walk on the hull's edges from `start_vertex` (a hull vertex index, any
/// at first) instead of a scan of every vertex, and `start_vertex` is set to it for the next call. Where
/// several vertices are exactly lowest (`down` exactly on an edge's arc of the Gauss map, a set of measure
/// zero) the walk may start rolling from another of them than the scan would.
int quasi_static_rest_face(const Particle& particle, const RestLandscape& landscape, const Vec3& down,
                           int& start_vertex);

}  // namespace repose
