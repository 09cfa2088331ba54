// Exact basins of quasi-static rolling on the Gauss map of the convex hull (see landscape.hpp).
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
#include "repose/poses/landscape.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <unordered_map>
#include <utility>

#include "repose/error.hpp"

namespace repose {
namespace detail {

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

}  // namespace detail

namespace {

using detail::GaussMap;
using Region = GaussMap::Region;
using Edge = GaussMap::Edge;

// A part of an edge's arc, as an interval of the chord parameter t of the arc (point ∝ x + t(y − x) between
// its end normals x, y), and the face it rolls to.
struct Interval {
  double t0, t1;
  int face;
};

// Rolling chains are finite because h strictly decreases; these bounds only catch a broken invariant.
constexpr int kMaxDepthSlack = 16;
// A rolling direction within this angle (rad) of a face normal has reached that face.
constexpr double kCornerTol = 1e-12;
// A point of an arc within this chord parameter of the ends of its part of a memoised partition is rolled
// directly instead (generous: it only costs time).
constexpr double kPartTol = 1e-9;

Vec3 chord_point(const Vec3& x, const Vec3& y, double t) {
  if (t <= 0) return x;
  if (t >= 1) return y;
  return (x + t * (y - x)).normalized();
}

// Chord parameter in [0, 1] where the plane through the origin with normal n crosses the segment x → y.
double cut(const Vec3& n, const Vec3& x, const Vec3& y) {
  const double sx = n.dot(x);
  const double sy = n.dot(y);
  if (sx == sy) return 0.5;  // the segment lies in the plane (or is a point)
  return std::clamp(sx / (sx - sy), 0.0, 1.0);
}

// Restricts [lo, hi] to the part of segment x → y with n·d ≥ 0 (n·d is linear in the chord parameter).
void clip_interval(const Vec3& n, const Vec3& x, const Vec3& y, double& lo, double& hi) {
  const double sx = n.dot(x);
  const double sy = n.dot(y);
  if (sx >= 0 && sy >= 0) return;
  if (sx < 0 && sy < 0) {
    hi = lo - 1;
    return;
  }
  const double t = sx / (sx - sy);
  if (sx < 0) {
    lo = std::max(lo, t);
  } else {
    hi = std::min(hi, t);
  }
}

// The part of a convex spherical polygon with n·d ≥ 0 (Sutherland–Hodgman; edges are shorter than π).
void clip_polygon(const std::vector<Vec3>& polygon, const Vec3& n, std::vector<Vec3>& out) {
  out.clear();
  const std::size_t k = polygon.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& p = polygon[i];
    const Vec3& q = polygon[(i + 1) % k];
    const double sp = n.dot(p);
    const double sq = n.dot(q);
    if (sp >= 0) out.push_back(p);
    if ((sp >= 0) != (sq >= 0)) out.push_back((p + sp / (sp - sq) * (q - p)).normalized());
  }
}

// Area (steradian) of a convex spherical polygon: a fan of triangles, each by Van Oosterom & Strackee (1983),
// tan(E/2) = |a·(b×c)| / (1 + a·b + b·c + c·a), which stays accurate for thin triangles.
double spherical_area(const std::vector<Vec3>& polygon) {
  double area = 0;
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    const Vec3& a = polygon[0];
    const Vec3& b = polygon[i];
    const Vec3& c = polygon[i + 1];
    area += 2 * std::atan2(std::abs(a.dot(b.cross(c))), 1 + a.dot(b) + b.dot(c) + c.dot(a));
  }
  return area;
}

int other_face(const Edge& e, int face) { return face == e.face_ab ? e.face_ba : e.face_ab; }

// The face a point at signed tangent coordinate s (along·d) of a sliding edge's arc slides to.
int slide_end(const GaussMap& g, const Edge& e, double s) {
  if (!e.top_inside) return e.low_face;
  const bool ab_positive = e.along.dot(g.face_normals[static_cast<std::size_t>(e.face_ab)]) > 0;
  return (s > 0) == ab_positive ? e.face_ab : e.face_ba;
}

// ---- building the Gauss map -------------------------------------------------------------------------------

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
  const Vec3 dir = (b - a).normalized();
  const Vec3 foot = a - a.dot(dir) * dir;  // nonzero: the centre of mass is strictly inside the hull
  e.height = foot.norm();
  e.top = foot / e.height;
  e.along = dir.cross(e.top);
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

// ---- rolling one direction --------------------------------------------------------------------------------

// Where the great circle from v's apex through d (in or on v's region) leaves the region: the first exit
// plane it crosses. normal·(cos θ p + sin θ t) = A cos θ + B sin θ with A > 0 vanishes once on (0, π), at cot
// θ = −B/A; the smallest θ has the largest −B/A.
struct Exit {
  int edge;
  Vec3 point;
};

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

// How rolling one direction ends: on a face normal, or on an unstable balance at the top of a sliding arc.
struct RollEnd {
  int face = -1;                 ///< the face normal reached; −1 at a balance
  Vec3 unstable = Vec3::Zero();  ///< balance: the arc's unit tangent at its top
  int side[2] = {-1, -1};        ///< balance: the face the arc slides to on the side u·d ≤ 0 / u·d > 0
};

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
      return {-1, e.along, {slide_end(g, e, -1), slide_end(g, e, 1)}};
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

// ---- rolling whole arcs -----------------------------------------------------------------------------------

// Every edge's arc is parametrised by the chord parameter t of n(face_ab) → n(face_ba). A partition of an arc
// lists which face each part of it rolls to: the reach of the face its motion ends on where that is already
// known (a stable face or a balance face), else the face itself (mapped through the routes at the end; the
// routes are being resolved while the first partitions are made). Sliding arcs split at their top; a
// crossing arc is rolled across the next region, lune by lune, and each crossing arc's partition is computed
// once (on a fine smooth mesh most arcs cross, and flows run through long chains of regions).
class ArcPartitions {
 public:
  explicit ArcPartitions(const GaussMap& g)
      : g_(g),
        memo_(g.edges.size()),
        state_(g.edges.size(), kUnvisited),
        max_depth_(static_cast<int>(g.regions.size()) + kMaxDepthSlack) {}

  // The face (as in a partition) point x of crossing edge e's arc rolls to, from the arc's memoised
  // partition; −1 if x is within kPartTol of a part's ends (where a flow may end on a corner or a balance,
  // which the partition does not resolve: roll x instead) or the partition is not known yet.
  int face_at(int e_index, const Vec3& x) {
    const std::size_t i = static_cast<std::size_t>(e_index);
    memoise(e_index, 0);
    if (state_[i] != kDone || memo_[i].empty()) return -1;
    const Edge& e = g_.edges[i];
    const double t = param(e, x.cross(e.top.cross(e.along)));  // plane through x normal to the arc
    const std::vector<Interval>& parts = memo_[i];
    const auto it =
        std::partition_point(parts.begin(), parts.end(), [&](const Interval& s) { return s.t1 < t; });
    if (it == parts.end() || !(t > it->t0 + kPartTol && t < it->t1 - kPartTol)) return -1;
    return it->face;
  }

  // Adds the area of every piece of vertex v's region to the stable face it rolls to.
  void add_region(int v, std::vector<double>& area) {
    const Region& r = g_.regions[static_cast<std::size_t>(v)];
    const std::size_t k = r.corners.size();
    if (k < 3) return;  // a vertex inside a straight edge: its region is that arc (no area)
    const Vec3& p = r.apex;
    std::vector<Interval> parts;
    for (std::size_t i = 0; i < k; ++i) {
      if (!r.arcs[i].exit) continue;
      const Edge& e = g_.edges[static_cast<std::size_t>(r.arcs[i].edge)];
      parts.clear();
      partition(r.arcs[i].edge, v, 0, 1, 0, parts);
      // The lune planes need the part's ends in the order of the region's corners i → i + 1.
      const bool forward = r.faces[i] == e.face_ab;
      for (const Interval& s : parts) {
        if (!(s.t1 > s.t0)) continue;
        Vec3 x = point(e, s.t0);
        Vec3 y = point(e, s.t1);
        if (!forward) std::swap(x, y);
        clip_polygon(r.corners, r.sense * p.cross(x), lune_);
        clip_polygon(lune_, r.sense * y.cross(p), piece_);
        const int reach = rest_of(s.face);
        if (g_.routes[static_cast<std::size_t>(reach)].balance) {
          add_split(reach, piece_, area, 0);
        } else {
          area[static_cast<std::size_t>(reach)] += spherical_area(piece_);
        }
      }
    }
  }

 private:
  enum State { kUnvisited, kInProgress, kDone };

  // The face's reach once its route is known (always, after resolve_routes), else the face itself.
  int rest_of(int face) const {
    const int reach = g_.routes[static_cast<std::size_t>(face)].reach;
    return reach >= 0 ? reach : face;
  }

  // A piece of starting directions whose flows all reach balance face f: each side of the great circle
  // through the balance goes on to its own side's face (which may be a balance face again).
  void add_split(int f, const std::vector<Vec3>& piece, std::vector<double>& area, int depth) {
    if (depth > max_depth_) throw Error("rest landscape: balances lead to each other in a cycle");
    const GaussMap::FaceRoute& r = g_.routes[static_cast<std::size_t>(f)];
    std::vector<Vec3> half;
    for (int side = 0; side < 2; ++side) {
      clip_polygon(piece, side == 1 ? r.unstable : Vec3(-r.unstable), half);
      if (half.size() < 3) continue;
      const int next = rest_of(r.side[side]);
      if (g_.routes[static_cast<std::size_t>(next)].balance) {
        add_split(next, half, area, depth + 1);
      } else {
        area[static_cast<std::size_t>(next)] += spherical_area(half);
      }
    }
  }
  const Vec3& normal(int face) const { return g_.face_normals[static_cast<std::size_t>(face)]; }
  Vec3 point(const Edge& e, double t) const { return chord_point(normal(e.face_ab), normal(e.face_ba), t); }
  double param(const Edge& e, const Vec3& plane) const {
    return cut(plane, normal(e.face_ab), normal(e.face_ba));
  }

  static void append_clipped(const std::vector<Interval>& parts, double lo, double hi,
                             std::vector<Interval>& out) {
    for (const Interval& s : parts) {
      const double t0 = std::max(s.t0, lo);
      const double t1 = std::min(s.t1, hi);
      if (t1 > t0) out.push_back({t0, t1, s.face});
    }
  }

  // Appends the parts of [lo, hi] of edge e's arc, reached by leaving vertex `from`'s region.
  void partition(int e_index, int from, double lo, double hi, int depth, std::vector<Interval>& out) {
    const Edge& e = g_.edges[static_cast<std::size_t>(e_index)];
    if (e.cross_to < 0 || e.cross_to == from) {
      if (!e.top_inside) {
        out.push_back({lo, hi, rest_of(e.low_face)});
        return;
      }
      const double t = param(e, e.along);  // the top
      if (lo < t) out.push_back({lo, std::min(t, hi), rest_of(e.face_ab)});
      if (hi > t) out.push_back({std::max(t, lo), hi, rest_of(e.face_ba)});
      return;
    }
    const std::size_t i = static_cast<std::size_t>(e_index);
    memoise(e_index, depth);
    if (state_[i] == kDone) {
      append_clipped(memo_[i], lo, hi, out);
    } else {
      cross(e, lo, hi, depth, out);  // a cycle of whole arcs (flows themselves end): roll just this range
    }
  }

  // Computes the whole partition of crossing edge e's arc once.
  void memoise(int e_index, int depth) {
    const std::size_t i = static_cast<std::size_t>(e_index);
    if (state_[i] != kUnvisited) return;
    state_[i] = kInProgress;
    std::vector<Interval> whole;
    cross(g_.edges[i], 0, 1, depth, whole);
    memo_[i] = merged(std::move(whole));
    state_[i] = kDone;
  }

  // Appends the parts of [lo, hi] of crossing edge e's arc, rolled across the region it crosses into: each
  // exit lune of that region takes a sub-range to a sub-range of its exit arc, along great circles from the
  // apex.
  void cross(const Edge& e, double lo, double hi, int depth, std::vector<Interval>& out) {
    if (depth > max_depth_) {
      throw Error("rest landscape: rolling did not end after " + std::to_string(max_depth_) +
                  " vertex regions");
    }
    const Region& r = g_.regions[static_cast<std::size_t>(e.cross_to)];
    const Vec3& p = r.apex;
    const Vec3& c0 = normal(e.face_ab);
    const Vec3& c1 = normal(e.face_ba);
    const std::size_t k = r.corners.size();
    std::vector<Interval> sub;
    for (std::size_t j = 0; j < k; ++j) {
      if (!r.arcs[j].exit) continue;
      double a = lo, b = hi;
      clip_interval(r.sense * p.cross(r.corners[j]), c0, c1, a, b);
      clip_interval(r.sense * r.corners[(j + 1) % k].cross(p), c0, c1, a, b);
      if (!(b > a)) continue;
      const Edge& next = g_.edges[static_cast<std::size_t>(r.arcs[j].edge)];
      const double ta = param(next, p.cross(chord_point(c0, c1, a)));
      const double tb = param(next, p.cross(chord_point(c0, c1, b)));
      sub.clear();
      partition(r.arcs[j].edge, e.cross_to, std::min(ta, tb), std::max(ta, tb), depth + 1, sub);
      // Pull the parts back onto this arc along the same great circles (range ends map exactly).
      auto back = [&](double t) {
        if (t == ta) return a;
        if (t == tb) return b;
        return std::clamp(cut(p.cross(point(next, t)), c0, c1), a, b);
      };
      for (const Interval& s : sub) {
        const double t0 = back(s.t0);
        const double t1 = back(s.t1);
        out.push_back({std::min(t0, t1), std::max(t0, t1), s.face});
      }
    }
  }

  // Sorted, with neighbouring parts that roll to the same face joined (keeps memoised partitions short).
  static std::vector<Interval> merged(std::vector<Interval> parts) {
    std::sort(parts.begin(), parts.end(), [](const Interval& x, const Interval& y) { return x.t0 < y.t0; });
    std::vector<Interval> out;
    for (const Interval& s : parts) {
      if (!out.empty() && out.back().face == s.face && s.t0 <= out.back().t1) {
        out.back().t1 = std::max(out.back().t1, s.t1);
      } else {
        out.push_back(s);
      }
    }
    return out;
  }

  const GaussMap& g_;
  std::vector<std::vector<Interval>> memo_;
  std::vector<State> state_;
  int max_depth_;
  std::vector<Vec3> lune_, piece_;  // scratch polygons
};

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

int quasi_static_rest_face(const Particle& particle, const RestLandscape& landscape, const Vec3& down) {
  if (!down.allFinite() || down.norm() == 0) {
    throw Error("quasi_static_rest_face: the down direction must be finite and nonzero");
  }
  const GaussMap* g = landscape.gauss_map.get();
  if (g == nullptr || g->regions.size() != particle.hull.vertices.size() ||
      g->routes.size() != particle.hull.faces.size() ||
      landscape.face_rest.size() != particle.hull.faces.size()) {
    throw Error("quasi_static_rest_face: the landscape was not computed for " + particle.name);
  }
  const Vec3 d = down.normalized();
  const int v = particle.hull.support_vertex(d);
  // On a face normal (a corner of v's region, within round-off) the face decides where to tip, not v.
  const Region& r = g->regions[static_cast<std::size_t>(v)];
  for (std::size_t i = 0; i < r.corners.size(); ++i) {
    if ((d - r.corners[i]).norm() < kCornerTol) {
      return landscape.face_rest[static_cast<std::size_t>(r.faces[i])];
    }
  }
  const RollEnd end = roll(*g, v, d);
  // A balance reached directly leaves on the side of d itself; a face reached goes on along its route.
  const int face = end.face >= 0 ? end.face : end.side[end.unstable.dot(d) > 0 ? 1 : 0];
  return rest_for(*g, face, d);
}

}  // namespace repose
