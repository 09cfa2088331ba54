// repair_mesh(): the halfedge-mesh stages (stitching, degenerate faces, holes, components, orientation) and
// the report. The soup stages are in repair_soup.cpp; what is CGAL's and what is ours: repair_cgal.hpp.
#include "repose/geometry/repair.hpp"

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/merge_border_vertices.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/exceptions.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "repair_cgal.hpp"
#include "repose/error.hpp"
#include "repose/geometry/mesh.hpp"

namespace repose {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using detail::count_of;
using detail::Winding;
using Point = detail::RepairPoint;
using Mesh = detail::RepairMesh;
using VertexIndex = Mesh::Vertex_index;
using FaceIndex = Mesh::Face_index;
using HalfedgeIndex = Mesh::Halfedge_index;

// A component is flat when |volume| ≤ 1e-12·D³ (D its own bounding-box diagonal): validate_mesh()'s zero
// volume, taken per component so that a small real piece beside a large one is not mistaken for flat.
constexpr double kFlatVolume = 1e-12;
// Above this many border edges a hole is triangulated only in the Delaunay search spaces: CGAL's fallback
// (all triangulations) takes O(n³) time and O(n²) memory.
constexpr std::size_t kMaxCubicHole = 1000;

std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g %%", 100 * fraction);
  return text;
}

Vec3 vec(const Point& p) { return {p.x(), p.y(), p.z()}; }

std::array<Vec3, 3> corners(const Mesh& m, FaceIndex f) {
  std::array<Vec3, 3> p;
  int k = 0;
  for (const VertexIndex v : CGAL::vertices_around_face(m.halfedge(f), m)) p[k++] = vec(m.point(v));
  return p;
}

// Whether a hole's border lies in a plane (within 1e-12 of its size) and passes through no point twice: then
// CGAL's 2D constrained Delaunay triangulation fills it (flat, the common case of a scan's cut or a CAD
// part's missing face). Otherwise the search over the border's triangulations does: CGAL's 2D path
// projects the border on a plane it fits and dereferences a null vertex when two border points project to
// one (found by fuzz_mesh_options, a four-point border spanning 5 units in z).
bool flat_border(const Mesh& m, HalfedgeIndex h) {
  std::vector<Vec3> border;
  for (const HalfedgeIndex e : CGAL::halfedges_around_face(h, m)) border.push_back(vec(m.point(m.target(e))));
  Vec3 normal = Vec3::Zero(), centre = Vec3::Zero();  // Newell's normal of the closed polygon
  for (std::size_t i = 0; i < border.size(); ++i) {
    normal += border[i].cross(border[(i + 1) % border.size()]);
    centre += border[i];
  }
  centre /= static_cast<double>(border.size());
  double size = 0, off_plane = 0;
  for (const Vec3& p : border) size = std::max(size, (p - centre).norm());
  if (!(normal.norm() > 0) || !(size > 0)) return false;
  normal.normalize();
  for (const Vec3& p : border) off_plane = std::max(off_plane, std::abs(normal.dot(p - centre)));
  if (off_plane > 1e-12 * size) return false;
  std::sort(border.begin(), border.end(), [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  return std::adjacent_find(border.begin(), border.end()) == border.end();
}

// Fills every hole with a flat triangulation of its border; marks the patch faces in `patch`.
void fill_holes(Mesh& m, const std::string& name, Mesh::Property_map<FaceIndex, bool>& patch,
                RepairReport& r) {
  std::vector<HalfedgeIndex> cycles;
  PMP::extract_boundary_cycles(m, std::back_inserter(cycles));
  for (const HalfedgeIndex h : cycles) {
    const auto edges = static_cast<std::size_t>(
        std::distance(CGAL::halfedges_around_face(h, m).begin(), CGAL::halfedges_around_face(h, m).end()));
    std::vector<FaceIndex> faces;
    // No refinement or fairing: the patch uses only the border's vertices, so it lies inside their convex
    // hull and the particle's convex hull (its contact geometry) is unchanged.
    PMP::triangulate_hole(m, h, std::back_inserter(faces),
                          CGAL::parameters::use_2d_constrained_delaunay_triangulation(flat_border(m, h))
                              .do_not_use_cubic_algorithm(edges > kMaxCubicHole));
    if (faces.empty()) {
      throw Error(name + ": cannot fill a hole of " + std::to_string(edges) +
                  " border edges (each triangulation of its border makes a non-manifold edge or a zero-area "
                  "triangle)");
    }
    for (const FaceIndex f : faces) patch[f] = true;
    ++r.holes_filled;
  }
}

// Removes the components that enclose no volume once closed: a stray triangle or sheet closes into a
// two-sided flat patch, which is no solid and would only add points to the convex hull.
void remove_flat_components(Mesh& m, const std::string& name, Mesh::Property_map<FaceIndex, std::size_t>& cc,
                            RepairReport& r) {
  const std::size_t n = PMP::connected_components(m, cc);
  std::vector<Aabb> boxes(n, Aabb{Vec3::Constant(std::numeric_limits<double>::infinity()),
                                  Vec3::Constant(-std::numeric_limits<double>::infinity())});
  for (const FaceIndex f : m.faces()) {
    for (const Vec3& p : corners(m, f)) {
      boxes[cc[f]].min = boxes[cc[f]].min.cwiseMin(p);
      boxes[cc[f]].max = boxes[cc[f]].max.cwiseMax(p);
    }
  }
  std::vector<double> six_volume(n, 0.0);
  for (const FaceIndex f : m.faces()) {
    const Vec3 o = boxes[cc[f]].center();  // cones from the component's own centre keep the round-off small
    const auto p = corners(m, f);
    six_volume[cc[f]] += (p[0] - o).dot((p[1] - o).cross(p[2] - o));
  }
  std::vector<std::size_t> flat;
  for (std::size_t c = 0; c < n; ++c) {
    const double d = boxes[c].size().norm();
    if (std::abs(six_volume[c]) / 6 <= kFlatVolume * d * d * d) flat.push_back(c);
  }
  if (flat.size() == n) {
    throw Error(name + ": nothing left to repair: the surface encloses no volume (" +
                count_of(n, "flat component", "flat components") + ")");
  }
  if (flat.empty()) return;
  PMP::remove_connected_components(m, flat, cc);
  m.collect_garbage();
  r.flat_components = static_cast<int>(flat.size());
}

// Converts the repaired mesh, measuring on the way what the patches added (repair.hpp: area_added,
// volume_change) and which kept triangles are wound against the input (flipped_faces).
TriangleMesh to_triangle_mesh(const Mesh& m, const Mesh::Property_map<FaceIndex, bool>& patch,
                              const std::vector<Winding>& input_windings, const std::string& name,
                              RepairReport& r) {
  // Cones from the centroid: V − V_input is then the patches' cones.
  const Vec3 centroid = vec(PMP::centroid(m));
  double patch_area = 0, kept_area = 0, patch_six_volume = 0, kept_six_volume = 0;
  std::vector<std::int32_t> new_index(m.num_vertices(), -1);  // num_vertices() counts removed ones too
  TriangleMesh out;
  out.triangles.reserve(m.number_of_faces());
  for (const FaceIndex f : m.faces()) {
    const auto p = corners(m, f);
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    const double six_volume = (p[0] - centroid).dot((p[1] - centroid).cross(p[2] - centroid));
    if (patch[f]) {
      patch_area += area;
      patch_six_volume += six_volume;
    } else {
      kept_area += area;
      kept_six_volume += six_volume;
      const Winding w = detail::winding_of(p);
      const auto it = std::lower_bound(input_windings.begin(), input_windings.end(), w);
      if (it != input_windings.end() && it->corners == w.corners && it->even != w.even) ++r.flipped_faces;
    }
    Triangle t;
    int k = 0;
    for (const VertexIndex v : CGAL::vertices_around_face(m.halfedge(f), m)) {
      std::int32_t& i = new_index[v.idx()];
      if (i < 0) {
        i = static_cast<std::int32_t>(out.vertices.size());
        out.vertices.push_back(vec(m.point(v)));
      }
      t[k++] = i;
    }
    out.triangles.push_back(t);
  }
  const double volume = (kept_six_volume + patch_six_volume) / 6;
  if (!(volume > 0)) {
    throw Error(name + ": repair could not make a valid solid: the result encloses no positive volume");
  }
  // The copies left at one position are what splits non-manifold places (counted here, at the end, because
  // some are merged again or go with removed components).
  std::vector<std::array<double, 3>> positions;
  positions.reserve(out.vertices.size());
  for (const Vec3& v : out.vertices) positions.push_back({v.x(), v.y(), v.z()});
  std::sort(positions.begin(), positions.end());
  r.non_manifold_vertices =
      static_cast<int>(positions.end() - std::unique(positions.begin(), positions.end()));
  r.area_added = kept_area > 0 ? patch_area / kept_area : 0.0;
  r.volume_change = patch_six_volume / 6 / volume;
  return out;
}

void add_notes(RepairReport& r, std::size_t components_before_largest) {
  auto note = [&](long long n, const std::string& text) {
    if (n > 0) r.notes.push_back(text);
  };
  note(r.merged_vertices,
       "merged " + count_of(r.merged_vertices, "coincident vertex", "coincident vertices"));
  note(r.degenerate_faces, "removed " +
                               count_of(r.degenerate_faces, "degenerate triangle", "degenerate triangles") +
                               " (zero area)");
  note(r.duplicate_faces,
       "removed " + count_of(r.duplicate_faces, "duplicate triangle", "duplicate triangles"));
  note(r.non_manifold_vertices, "split non-manifold vertices and edges (" +
                                    count_of(r.non_manifold_vertices, "vertex copy", "vertex copies") +
                                    " at shared positions)");
  note(r.stitched_edges, "stitched " + count_of(r.stitched_edges, "border edge", "border edges"));
  note(r.holes_filled, "filled " + count_of(r.holes_filled, "hole", "holes") + " (" + percent(r.area_added) +
                           " of the area, volume " + (r.volume_change >= 0 ? "+" : "") +
                           percent(r.volume_change) + ")");
  note(r.flat_components,
       "removed " + count_of(r.flat_components, "flat component", "flat components") + " (no volume)");
  note(r.kept_components < static_cast<int>(components_before_largest),
       "kept the largest of " + std::to_string(components_before_largest) + " components (by surface area)");
  note(r.flipped_faces,
       "flipped " + count_of(r.flipped_faces, "triangle", "triangles") + " to a consistent outward winding");
}

RepairReport run(TriangleMesh& mesh, const std::string& name, bool largest_component) {
  RepairReport r;
  Mesh m;
  const std::vector<Winding> input_windings = detail::soup_to_mesh(mesh, name, m, r);

  r.stitched_edges = static_cast<int>(PMP::stitch_borders(m));
  m.collect_garbage();

  // Exactly collinear corners (two coincident ones were dropped in the soup): CGAL flips such a triangle's
  // longest edge or collapses its shortest, which keeps the surface closed where dropping it would not.
  std::vector<FaceIndex> degenerate;
  PMP::degenerate_faces(m, std::back_inserter(degenerate));
  if (!degenerate.empty()) {
    r.degenerate_faces += static_cast<int>(degenerate.size());
    PMP::remove_degenerate_faces(m);
    m.collect_garbage();
    degenerate.clear();
    PMP::degenerate_faces(m, std::back_inserter(degenerate));
    if (!degenerate.empty()) {
      throw Error(name + ": cannot remove " +
                  count_of(degenerate.size(), "degenerate triangle", "degenerate triangles") +
                  " (zero area)");
    }
    if (m.number_of_faces() == 0) {
      throw Error(name + ": nothing left to repair: every triangle is degenerate (zero area)");
    }
  }
  // Stitching and collapsing can pinch a vertex between two fans again; hole filling needs simple borders.
  PMP::duplicate_non_manifold_vertices(m);
  // Where two holes touched at a vertex, the split above left one border cycle passing twice through that
  // point (once per copy): a patch spanning it would have to fold through the pinch, overlapping the rest.
  // Merging the copies again splits the cycle into one per hole, which meet at the vertex and are filled
  // apart; once both are filled the vertex is manifold again.
  PMP::merge_duplicated_vertices_in_boundary_cycles(m);
  m.collect_garbage();

  auto cc = m.add_property_map<FaceIndex, std::size_t>("f:repose_component", 0).first;
  r.input_components = static_cast<int>(PMP::connected_components(m, cc));

  auto patch = m.add_property_map<FaceIndex, bool>("f:repose_patch", false).first;
  fill_holes(m, name, patch, r);
  if (!CGAL::is_closed(m)) {
    throw Error(name + ": repair failed: the surface is still open after hole filling");
  }
  remove_flat_components(m, name, cc, r);

  std::size_t components = PMP::connected_components(m, cc);
  const std::size_t before_largest = components;
  if (largest_component && components > 1) {
    auto area = m.add_property_map<FaceIndex, double>("f:repose_area", 0.0).first;
    for (const FaceIndex f : m.faces()) area[f] = PMP::face_area(f, m);
    PMP::keep_largest_connected_components(m, 1, CGAL::parameters::face_size_map(area));
    m.collect_garbage();
    components = 1;
  }
  r.kept_components = static_cast<int>(components);

  PMP::orient_to_bound_a_volume(m);
  TriangleMesh out = to_triangle_mesh(m, patch, input_windings, name, r);
  add_notes(r, before_largest);

  // The contract is a mesh validate_mesh() accepts; it welds by position, so coincident copies that CGAL
  // kept apart (two parts touching along an edge) come back together there. Check here, on a copy, so that
  // the user learns it from the repair rather than as an unexplained failure after it.
  try {
    TriangleMesh check = out;
    validate_mesh(check, name);
  } catch (const Error& e) {
    std::string what = e.what();
    if (what.starts_with(name + ": ")) what.erase(0, name.size() + 2);
    const bool touching = r.kept_components > 1 && what.find("non-manifold") != std::string::npos;
    throw Error(name + ": repair could not make a valid solid: " + what +
                (touching ? " (parts touching along an edge; --largest-component keeps one)" : ""));
  }
  mesh = std::move(out);
  return r;
}

}  // namespace

RepairReport repair_mesh(TriangleMesh& mesh, const std::string& name, bool largest_component) {
  detail::check_repair_input(mesh, name);
  try {
    return run(mesh, name, largest_component);
  } catch (const CGAL::Failure_exception& e) {
    // A violated CGAL precondition or assertion (checked in debug builds only; found on random soups: the
    // outward test at a vertex where the surface folds back onto itself). One line, never a crash.
    throw Error(name + ": repair failed: CGAL check " + (e.message().empty() ? e.expression() : e.message()) +
                " does not hold");
  }
}

}  // namespace repose
