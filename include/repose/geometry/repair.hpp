// Repair of a user's surface into a closed solid (the --repair option), with CGAL's Polygon Mesh Processing.
//
// validate_mesh() accepts only closed, edge-manifold, consistently wound surfaces. Scans and exports bring
// holes, flipped patches, non-manifold edges, duplicate and degenerate faces and several pieces;
// repair_mesh() turns such a surface into one validate_mesh() accepts, and reports every change it made. It
// runs before validate_mesh(), only when the user asks for it: a repair changes the solid, so it is never
// silent.
#pragma once

#include <string>
#include <vector>

#include "repose/geometry/types.hpp"

namespace repose {

/// What repair_mesh() changed, stage by stage (in the order they run). Counts are of triangles, vertices or
/// edges; area_added and volume_change are dimensionless fractions.
struct RepairReport {
  /// Vertex records merged into an exactly coincident one (welding, as STL needs).
  int merged_vertices = 0;
  /// Zero-area triangles eliminated: two corners at one point (removed), or three distinct collinear
  /// corners (removed, or flipped away with a neighbour).
  int degenerate_faces = 0;
  /// Triangles removed because another has the same three corners (either winding).
  int duplicate_faces = 0;
  /// Vertices of the result at the position of another one: the copies that split non-manifold vertices and
  /// edges. An edge of more than two triangles, or a vertex whose triangles form several fans, is cut apart
  /// (each fan gets its own copy); nothing is removed. (Where holes touched, the copies are merged again.)
  int non_manifold_vertices = 0;
  /// Pairs of coincident border edges stitched into one edge. The soup is welded first (merged_vertices),
  /// so coincident borders survive only where orienting the soup had to cut an edge whose two sides cannot
  /// be wound alike (a non-orientable soup); on the files tried this is always 0, and the stage is a guard.
  int stitched_edges = 0;
  /// Edge-connected components after the stages above (before hole filling).
  int input_components = 0;
  /// Border cycles closed by a flat patch (no new vertices).
  int holes_filled = 0;
  /// Components that enclose no volume once closed (a stray sheet or triangle), removed.
  int flat_components = 0;
  /// Components in the result (1 with largest_component).
  int kept_components = 0;
  /// Triangles of the result wound opposite to the input triangle on the same three corner positions
  /// (patches and triangles made by flipping degenerate ones have no such input triangle: not counted).
  int flipped_faces = 0;
  /// Area of the patches / area of the result's other triangles (the input that was kept).
  double area_added = 0;
  /// (V − V_input) / V, where V is the result's volume and V_input the signed volume of its non-patch
  /// triangles as cones from the result's centroid; V − V_input is the patches' cones, which for an open
  /// surface is what filling added.
  double volume_change = 0;
  /// One human-readable line per change, e.g. "filled 3 holes (0.8 % of the area, volume +0.2 %)".
  std::vector<std::string> notes;
};

/// Repairs `mesh` in place into a closed, consistently and outwardly oriented 2-manifold that validate_mesh()
/// accepts, and reports what changed.
///
/// Stages (CGAL Polygon Mesh Processing, exact predicates): merge exactly coincident vertices; drop triangles
/// with a repeated corner and duplicate triangles; orient the triangle soup consistently, cutting it apart
/// at non-manifold edges and vertices; stitch coincident borders; flip or collapse zero-area triangles; merge
/// again the copies of a vertex where holes touched (so that each hole is filled on its own); fill every hole
/// with a flat triangulation of its border; remove components that enclose no volume; with
/// `largest_component`, keep only the component of largest surface area (after filling); orient so that the
/// mesh bounds a volume (outer surfaces outward, a surface nested inside another — a cavity — inward).
/// Several components are otherwise all kept: they are one rigid body.
///
/// Hole patches are not refined or faired: they use only the border's vertices, so no vertex is added or
/// moved, a patch lies inside the convex hull of its border, and the convex hull (the contact geometry) is
/// unchanged unless a component is removed. A flat patch over a curved hole misses the cap of surface that
/// was not scanned; volume_change says how much the patches' cones weigh.
///
/// `name` starts every error message. Throws repose::Error("NAME: ...") for an empty mesh, an index out of
/// range, a non-finite coordinate, a size out of range (as validate_mesh()), a hole that cannot be
/// triangulated, nothing left (every triangle degenerate, every component flat), or a result validate_mesh()
/// would reject: parts that touch along an edge are kept apart by copies of the shared vertices, which
/// validate_mesh() welds back into an edge of four triangles ("--largest-component keeps one"). On error
/// `mesh` is unchanged.
RepairReport repair_mesh(TriangleMesh& mesh, const std::string& name, bool largest_component);

}  // namespace repose
