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

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "repose/geometry/hull.hpp"
#include "repose/geometry/types.hpp"

namespace repose::detail {

// The map's numbers in the scalar T: double for the landscape; an automatic-differentiation type when the
// design differentiates the basins (src/design/basin_gradient.cpp): the same structure, the geometry in T.
template <class T>
struct GaussMapT {
  using V = Eigen::Matrix<T, 3, 1>;
  // One boundary arc of a vertex region, between corners i and i + 1.
  struct Arc {
    int edge = -1;
    V normal = V::Zero();  ///< unit (v − w)/|v − w|: the region is on its positive side
    bool exit = false;     ///< the apex is on the region's side: rolling leaves the region through this arc
  };
  struct Region {
    V apex = V::Zero();      ///< p_v (snapped onto a corner within 1e-10 rad, see build_region)
    std::vector<V> corners;  ///< face normals around the vertex
    std::vector<int> faces;
    std::vector<Arc> arcs;
    double sense = 1;  ///< sign of normal·(c_i × c_{i+1}), the same for every arc (orients the lunes)
  };
  struct Edge {
    int a = -1, b = -1;              ///< hull vertices, a < b
    int face_ab = -1, face_ba = -1;  ///< the face whose loop runs a → b, and b → a
    V top = V::Zero();               ///< unit: the arc's maximum of h (centre of mass above the edge line)
    V along = V::Zero();             ///< unit tangent of the arc's great circle at `top`
    T height = 0;                    ///< distance from the centre of mass to the edge line
    bool top_inside = false;         ///< `top` strictly inside the arc
    int low_face = -1;               ///< the lower end when `top` is not inside
    int cross_to = -1;  ///< the vertex whose region rolling crosses into; −1: it slides along the arc
    bool saddle = false;
  };
  // Where a face's normal rolls: its own rest if stable, else where tipping over takes it.
  struct FaceRoute {
    int reach = -1;  ///< the stable face, or the first balance face, that tipping leads to (itself if either)
    bool balance = false;    ///< tipping from this face ends on an unstable balance (see above)
    V unstable = V::Zero();  ///< balance: the arc's unit tangent at its top (h descends both ways)
    int side[2] = {-1, -1};  ///< balance: the face it slides to for u·d ≤ 0 ([0]) and u·d > 0 ([1])
    int edge = -1;           ///< balance: the edge whose arc it is (unstable is its `along`)
  };
  std::vector<Region> regions;  // per hull vertex
  std::vector<Edge> edges;
  std::vector<V> face_normals;
  std::vector<FaceRoute> routes;  // per hull face
  T balance_tol = 0;              // 1e-12·L: lever arm (length) within which an arc's top counts as reached
};

// An edge (a, b)'s arc geometry from its end vertices (body frame, centre of mass at the origin), in any
// scalar: the distance from the centre of mass to the edge line, the arc's top (the unit direction of that
// foot) and the tangent of its great circle there.
template <class T>
void edge_arc(const Eigen::Matrix<T, 3, 1>& a, const Eigen::Matrix<T, 3, 1>& b, T& height,
              Eigen::Matrix<T, 3, 1>& top, Eigen::Matrix<T, 3, 1>& along) {
  const Eigen::Matrix<T, 3, 1> dir = (b - a).normalized();
  const Eigen::Matrix<T, 3, 1> foot = a - a.dot(dir) * dir;  // nonzero: the centre of mass is inside the hull
  height = foot.norm();
  top = foot / height;
  along = dir.cross(top);
}

// The landscape's map (a type of its own: landscape.hpp declares it).
struct GaussMap : GaussMapT<double> {};

// The Gauss map of `hull` (body frame, centre of mass at the origin) with its edges described and its regions
// built; `length` (L) scales the balance tolerance. Routes are left empty (landscape.cpp resolves them).
std::shared_ptr<GaussMap> build_gauss_map(const ConvexHull& hull, double length);

// The face of edge e other than `face`.
int other_face(const GaussMap::Edge& e, int face);
// The face a point at signed tangent coordinate s (along·d) of a sliding edge's arc slides to.
int slide_end(const GaussMap& g, const GaussMap::Edge& e, double s);

}  // namespace repose::detail
