// The Gauss map of a convex hull, as the rest landscape rolls on it (see landscape.hpp).
//
// Gauss map: face f → its normal n_f; edge (a, b) → the great-circle arc between its two faces' normals, in
// the plane (b − a)·d = 0; vertex v → the convex spherical polygon {d : (v − w)·d ≥ 0 for every neighbour w}
// ("region"), whose corners are the normals of the faces around v. In v's region h = v·d, so rolling follows
// great circles away from the apex p_v = v/|v|, and leaves through an arc whose plane has p_v on the region's
// side (an "exit"). The points leaving through exit arc (c0, c1) are the region ∩ the lune from p_v through
// c0 and c1, and a sub-arc (x, y) of it is reached from region ∩ lune(p_v, x, y): basins are unions of such
// convex spherical polygons, whose areas we sum.
//
// On an edge's arc both end vertices touch. Let s be where the centre of mass's foot on the edge line lies
// (0 at a, 1 at b); s does not depend on d along the arc. For 0 < s < 1 the body rotates about the edge: d
// slides along the arc away from its top (the centre of mass above the edge line) to a face normal. For s > 1
// the weight's line of action passes beyond b, so a lifts and the body pivots about b alone: d crosses into
// b's region (the arc is an exit of a's region and an entry of b's). Both are the steepest descent of h (its
// minimum-norm subgradient); the crossing case is what makes basins depend on where an arc is reached.
#pragma once

#include <memory>
#include <vector>

#include "repose/geometry/hull.hpp"
#include "repose/geometry/types.hpp"

namespace repose::detail {

struct GaussMap {
  // One boundary arc of a vertex region, between corners i and i + 1.
  struct Arc {
    int edge = -1;
    Vec3 normal = Vec3::Zero();  ///< unit (v − w)/|v − w|: the region is on its positive side
    bool exit = false;  ///< the apex is on the region's side: rolling leaves the region through this arc
  };
  struct Region {
    Vec3 apex = Vec3::Zero();   ///< p_v (snapped onto a corner within 1e-10 rad, see build_region)
    std::vector<Vec3> corners;  ///< face normals around the vertex
    std::vector<int> faces;
    std::vector<Arc> arcs;
    double sense = 1;  ///< sign of normal·(c_i × c_{i+1}), the same for every arc (orients the lunes)
  };
  struct Edge {
    int a = -1, b = -1;              ///< hull vertices, a < b
    int face_ab = -1, face_ba = -1;  ///< the face whose loop runs a → b, and b → a
    Vec3 top = Vec3::Zero();         ///< unit: the arc's maximum of h (centre of mass above the edge line)
    Vec3 along = Vec3::Zero();       ///< unit tangent of the arc's great circle at `top`
    double height = 0;               ///< distance from the centre of mass to the edge line
    bool top_inside = false;         ///< `top` strictly inside the arc
    int low_face = -1;               ///< the lower end when `top` is not inside
    int cross_to = -1;  ///< the vertex whose region rolling crosses into; −1: it slides along the arc
    bool saddle = false;
  };
  // Where a face's normal rolls: its own rest if stable, else where tipping over takes it.
  struct FaceRoute {
    int reach = -1;  ///< the stable face, or the first balance face, that tipping leads to (itself if either)
    bool balance = false;          ///< tipping from this face ends on an unstable balance (see above)
    Vec3 unstable = Vec3::Zero();  ///< balance: the arc's unit tangent at its top (h descends both ways)
    int side[2] = {-1, -1};        ///< balance: the face it slides to for u·d ≤ 0 ([0]) and u·d > 0 ([1])
  };
  std::vector<Region> regions;  // per hull vertex
  std::vector<Edge> edges;
  std::vector<Vec3> face_normals;
  std::vector<FaceRoute> routes;  // per hull face
  double balance_tol = 0;         // 1e-12·L: lever arm (length) within which an arc's top counts as reached
};

// The Gauss map of `hull` (body frame, centre of mass at the origin) with its edges described and its regions
// built; `length` (L) scales the balance tolerance. Routes are left empty (landscape.cpp resolves them).
std::shared_ptr<GaussMap> build_gauss_map(const ConvexHull& hull, double length);

// The face of edge e other than `face`.
int other_face(const GaussMap::Edge& e, int face);
// The face a point at signed tangent coordinate s (along·d) of a sliding edge's arc slides to.
int slide_end(const GaussMap& g, const GaussMap::Edge& e, double s);

}  // namespace repose::detail
