// Facts about a particle's surface derived once when the model is built: smoothness, convexity, and the
// static stability of each convex-hull face.
#include "surface_facts.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

namespace repose {

namespace {

Vec3 triangle_normal(const TriangleMesh& mesh, const Triangle& t) {
  const Vec3& a = mesh.vertices[t[0]];
  return (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
}

}  // namespace

void compute_dihedral_facts(const TriangleMesh& mesh, double length, double& max_angle, bool& convex) {
  // Each directed edge with its triangle, sorted by undirected edge (then triangle): the twin of lo → hi is
  // hi → lo, the neighbour across it. A sort, not a map: a 2,000,000-triangle scan has 6,000,000 edges.
  struct DirectedEdge {
    int lo, hi, face;
    bool forward;  // runs lo → hi in its triangle
  };
  std::vector<DirectedEdge> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles[f][k], b = mesh.triangles[f][(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), f, a < b});
    }
  std::sort(edges.begin(), edges.end(), [](const DirectedEdge& x, const DirectedEdge& y) {
    return std::tie(x.lo, x.hi, x.face) < std::tie(y.lo, y.hi, y.face);
  });
  max_angle = 0;
  convex = true;
  const double reflex_tol = 1e-9 * length;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    int owner = -1, twin = -1;  // the last triangle running lo → hi, and the last running hi → lo
    for (; j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi; ++j)
      (edges[j].forward ? owner : twin) = edges[j].face;
    const int lo = edges[i].lo, hi = edges[i].hi;
    i = j;
    if (owner < 0 || twin < 0) continue;  // a border edge (or one wound one way only)
    const Triangle& t1 = mesh.triangles[owner];
    const Triangle& t2 = mesh.triangles[twin];
    const Vec3 n1 = triangle_normal(mesh, t1).normalized();
    const Vec3 n2 = triangle_normal(mesh, t2).normalized();
    max_angle = std::max(max_angle, std::acos(std::clamp(n1.dot(n2), -1.0, 1.0)));
    // The neighbour's far vertex lies above this triangle's plane only at a reflex (concave) edge.
    int far = t2[0];
    for (int v : t2)
      if (v != lo && v != hi) far = v;
    if (n1.dot(mesh.vertices[far] - mesh.vertices[lo]) > reflex_tol) convex = false;
  }
}

double face_stability_margin(const ConvexHull& hull, const HullFace& face, const Vec3& com) {
  // Project the centre of mass onto the face plane, then take the smallest inward distance to an edge.
  const Vec3 p = com - (face.normal.dot(com) - face.offset) * face.normal;
  return polygon_margin(hull.vertices, face.loop, face.normal, p);
}

double polygon_margin(const std::vector<Vec3>& points, const std::vector<int>& loop, const Vec3& normal,
                      const Vec3& point) {
  double margin = INFINITY;
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = points[static_cast<std::size_t>(loop[i])];
    const Vec3& b = points[static_cast<std::size_t>(loop[(i + 1) % n])];
    const Vec3 inward = normal.cross(b - a).normalized();  // the loop is CCW seen from outside
    margin = std::min(margin, inward.dot(point - a));
  }
  return margin;
}

std::vector<bool> faces_covered_by_mesh(const TriangleMesh& mesh, const ConvexHull& hull, double length) {
  // Flood-fill from each face's corners across mesh triangles that lie in the face plane: the cost is
  // proportional to the triangles on hull faces, not to mesh size times face count.
  // The triangles of each vertex, in one array (first[v] .. first[v + 1]).
  std::vector<int> first(mesh.vertices.size() + 1, 0), triangles(3 * mesh.triangles.size());
  for (const Triangle& tri : mesh.triangles)
    for (int v : tri) ++first[v + 1];
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) first[v + 1] += first[v];
  {
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
      for (int v : mesh.triangles[t]) triangles[fill[v]++] = t;
  }

  const double tol = 1e-9 * length;
  std::vector<int> stamp(mesh.triangles.size(), -1);
  std::vector<bool> flat(hull.faces.size());
  for (int f = 0; f < static_cast<int>(hull.faces.size()); ++f) {
    const HullFace& face = hull.faces[f];
    auto on_plane = [&](int v) { return std::abs(face.normal.dot(mesh.vertices[v]) - face.offset) <= tol; };
    std::vector<int> stack;
    for (int h : face.loop) stack.push_back(hull.source_index[h]);
    double covered = 0;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int i = first[v]; i < first[v + 1]; ++i) {
        const int t = triangles[i];
        if (stamp[t] == f) continue;
        stamp[t] = f;
        const Triangle& tri = mesh.triangles[t];
        if (!on_plane(tri[0]) || !on_plane(tri[1]) || !on_plane(tri[2])) continue;
        covered += 0.5 * triangle_normal(mesh, tri).norm();
        for (int w : tri) stack.push_back(w);
      }
    }
    flat[f] = covered >= (1 - 1e-6) * face.area;
  }
  return flat;
}

}  // namespace repose
