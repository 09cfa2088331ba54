// The polygon-soup stages of repair_mesh() (see repair_cgal.hpp): input checks, welding, collapsed and
// duplicate triangles, orientation, and the conversion to a halfedge mesh.
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "repair_cgal.hpp"
#include "repose/error.hpp"
#include "repose/geometry/mesh.hpp"

namespace repose::detail {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Polygon = std::array<std::size_t, 3>;

}  // namespace

std::string count_of(std::size_t n, const std::string& singular, const std::string& plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

Winding winding_of(const std::array<Vec3, 3>& p) {
  auto less = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  // Rotating the smallest corner to the front keeps the winding; then the order of the other two decides.
  const int first = less(p[1], p[0]) ? (less(p[2], p[1]) ? 2 : 1) : (less(p[2], p[0]) ? 2 : 0);
  const Vec3& a = p[first];
  const Vec3& b = p[(first + 1) % 3];
  const Vec3& c = p[(first + 2) % 3];
  Winding w;
  w.even = less(b, c);
  const Vec3& lo = w.even ? b : c;
  const Vec3& hi = w.even ? c : b;
  for (int k = 0; k < 3; ++k) {
    w.corners[k] = a[k];
    w.corners[3 + k] = lo[k];
    w.corners[6 + k] = hi[k];
  }
  return w;
}

void check_repair_input(const TriangleMesh& mesh, const std::string& name) {
  check_surface_input(mesh, name);
  // Splitting non-manifold vertices may copy vertices: keep indices representable.
  if (mesh.vertices.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 2)) {
    throw Error(name + ": too many vertices (" + std::to_string(mesh.vertices.size()) + ")");
  }
}

std::vector<Winding> soup_to_mesh(const TriangleMesh& input, const std::string& name, RepairMesh& m,
                                  RepairReport& r) {
  std::vector<Winding> windings;
  windings.reserve(input.triangles.size());
  for (const Triangle& t : input.triangles) {
    windings.push_back(winding_of({input.vertices[t[0]], input.vertices[t[1]], input.vertices[t[2]]}));
  }
  // Of several input triangles on the same corners the first decides (stable sort, then unique).
  std::stable_sort(windings.begin(), windings.end());
  windings.erase(std::unique(windings.begin(), windings.end(),
                             [](const Winding& a, const Winding& b) { return a.corners == b.corners; }),
                 windings.end());

  // Only vertices that a triangle uses enter the soup, so merged_vertices counts welds of the surface.
  std::vector<std::size_t> index(input.vertices.size(), SIZE_MAX);
  std::vector<RepairPoint> points;
  std::vector<Polygon> polygons;
  polygons.reserve(input.triangles.size());
  for (const Triangle& t : input.triangles) {
    Polygon p;
    for (int k = 0; k < 3; ++k) {
      std::size_t& i = index[t[k]];
      if (i == SIZE_MAX) {
        i = points.size();
        const Vec3& v = input.vertices[t[k]];
        points.emplace_back(v.x(), v.y(), v.z());
      }
      p[k] = i;
    }
    polygons.push_back(p);
  }
  r.merged_vertices = static_cast<int>(PMP::merge_duplicate_points_in_polygon_soup(points, polygons));
  const auto collapsed =
      std::erase_if(polygons, [](const Polygon& p) { return p[0] == p[1] || p[1] == p[2] || p[2] == p[0]; });
  r.degenerate_faces = static_cast<int>(collapsed);
  if (polygons.empty()) {
    throw Error(name + ": nothing left to repair: all " + std::to_string(input.triangles.size()) +
                " triangles are degenerate (zero area)");
  }
  r.duplicate_faces = static_cast<int>(PMP::merge_duplicate_polygons_in_polygon_soup(points, polygons));
  PMP::remove_isolated_points_in_polygon_soup(points, polygons);

  // Turns triangles to agree with their neighbours, spreading from a seed triangle (so it may turn the other
  // side of a flipped patch: the final outward orientation settles that); where no consistent choice exists
  // (an edge of more than two triangles, a vertex with several fans) it duplicates the points.
  PMP::orient_polygon_soup(points, polygons);
  // CGAL only asserts this (in debug builds); a soup that still is no mesh would corrupt the halfedges.
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    throw Error(name + ": repair failed: the oriented triangles do not form a polygon mesh");
  }
  PMP::polygon_soup_to_polygon_mesh(points, polygons, m);
  return windings;
}

}  // namespace repose::detail
