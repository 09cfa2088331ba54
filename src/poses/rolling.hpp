// Rolling one direction on the Gauss map: region by region to a face normal or an unstable balance.
//
//
// Unstable balances (the tie rule; see landscape.hpp). A flow can stop where h is a minimum along the way it
// came but a maximum across it: the top of a sliding arc, reached exactly. For one direction that is measure
// zero, but a face tips along one fixed path, so every direction reaching an unstable face whose tipping ends
// on such a balance ends there too: positive area on meshes with a mirror plane that flows slide into (the
// built-in ellipsoid). The flow leaves along the arc on the side it came from: that of the last point of its
// path off the great circle u·d = 0 through the balance perpendicular to the arc (u: the arc's tangent at the
// top). roll() looks back along its own path for it; when the whole tipping path from a face normal runs on
// that great circle (a mirror plane), the face becomes a "balance face" and the starting direction's side
// decides. In the integration each piece that reaches a balance face is split by that great circle, so the
// areas and quasi_static_rest_face follow the same rule, and a mirror symmetry maps basins onto basins.
#pragma once

#include "gauss_map.hpp"

namespace repose::detail {

// Rolling chains are finite because h strictly decreases; these bounds only catch a broken invariant.
constexpr int kMaxDepthSlack = 16;
// A rolling direction within this angle (rad) of a face normal has reached that face.
constexpr double kCornerTol = 1e-12;

// Where the great circle from a region's apex through a direction leaves the region: the exit arc's edge
// and the point on it.
struct Exit {
  int edge;
  Vec3 point;
};
Exit leave_region(const GaussMap& g, int v, const Vec3& d);

// How rolling one direction ends: on a face normal, or on an unstable balance at the top of a sliding arc.
struct RollEnd {
  int face = -1;                 ///< the face normal reached; −1 at a balance
  Vec3 unstable = Vec3::Zero();  ///< balance: the arc's unit tangent at its top
  int side[2] = {-1, -1};        ///< balance: the face the arc slides to on the side u·d ≤ 0 / u·d > 0
  int edge = -1;                 ///< balance: the edge whose arc it is
};
// From direction d in (or on the boundary of) vertex v's region, rolls region by region until the arc motion
// ends (rolling.cpp says how corners and balances are decided).
RollEnd roll(const GaussMap& g, int v, Vec3 d);

// The stable face reached from face f's normal by a flow that started at `start` (routes resolved).
int rest_for(const GaussMap& g, int f, const Vec3& start);

}  // namespace repose::detail
