// Facts about a particle's surface derived once when the model is built: smoothness, convexity, and the
// static stability of each convex-hull face.
#include "surface_facts.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace repose {

namespace {

Vec3 triangle_normal(const TriangleMesh& mesh, const Triangle& t) {
  const Vec3& a = mesh.vertices[t[0]];
  return (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
}

}  // namespace

void compute_dihedral_facts(const TriangleMesh& mesh, double length, double& max_angle, bool& convex) {
  // Map each directed edge to its triangle; the twin edge is the neighbour across it.
  std::map<std::pair<int, int>, int> edge_owner;
  for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f)
    for (int k = 0; k < 3; ++k) edge_owner[{mesh.triangles[f][k], mesh.triangles[f][(k + 1) % 3]}] = f;
  max_angle = 0;
  convex = true;
  const double reflex_tol = 1e-9 * length;
  for (const auto& [edge, f] : edge_owner) {
    if (edge.first > edge.second) continue;  // each undirected edge once
    const auto twin = edge_owner.find({edge.second, edge.first});
    if (twin == edge_owner.end()) continue;
    const Triangle& t1 = mesh.triangles[f];
    const Triangle& t2 = mesh.triangles[twin->second];
    const Vec3 n1 = triangle_normal(mesh, t1).normalized();
    const Vec3 n2 = triangle_normal(mesh, t2).normalized();
    max_angle = std::max(max_angle, std::acos(std::clamp(n1.dot(n2), -1.0, 1.0)));
    // The neighbour's far vertex lies above this triangle's plane only at a reflex (concave) edge.
    int far = t2[0];
    for (int v : t2)
      if (v != edge.first && v != edge.second) far = v;
    if (n1.dot(mesh.vertices[far] - mesh.vertices[edge.first]) > reflex_tol) convex = false;
  }
}

double face_stability_margin(const ConvexHull& hull, const HullFace& face, const Vec3& com) {
  // Project the centre of mass onto the face plane, then take the smallest inward distance to an edge.
  const Vec3 p = com - (face.normal.dot(com) - face.offset) * face.normal;
  double margin = INFINITY;
  const std::size_t n = face.loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = hull.vertices[face.loop[i]];
    const Vec3& b = hull.vertices[face.loop[(i + 1) % n]];
    const Vec3 inward = face.normal.cross(b - a).normalized();  // loop is CCW seen from outside
    margin = std::min(margin, inward.dot(p - a));
  }
  return margin;
}

std::vector<bool> faces_covered_by_mesh(const TriangleMesh& mesh, const ConvexHull& hull, double length) {
  // Flood-fill from each face's corners across mesh triangles that lie in the face plane: the cost is
  // proportional to the triangles on hull faces, not to mesh size times face count.
  std::vector<std::vector<int>> triangles_of_vertex(mesh.vertices.size());
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    for (int v : mesh.triangles[t]) triangles_of_vertex[v].push_back(t);

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
      for (int t : triangles_of_vertex[v]) {
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
