// Validation and repair of a triangulated particle surface.
//
// A mesh reader accepts what it can parse; whether the result is a closed solid is decided here. Repairs
// that cannot change the solid (welding duplicate vertices, dropping zero-area triangles, flipping a
// globally inverted surface) are applied and reported; anything else is an error.
#pragma once

#include <string>
#include <vector>

#include "repose/error.hpp"
#include "repose/geometry/types.hpp"

namespace repose {

/// What validate_mesh() found and repaired.
struct MeshReport {
  int input_vertices = 0;             ///< vertex records before welding
  int input_triangles = 0;            ///< triangles before repair
  int welded_vertices = 0;            ///< vertex records merged into an earlier coincident vertex
  int degenerate_triangles = 0;       ///< zero-area triangles removed
  int unused_vertices = 0;            ///< vertices referenced by no triangle, removed
  bool flipped = false;               ///< the whole surface was inverted (negative volume) and was flipped
  std::vector<std::string> warnings;  ///< one human-readable line per repair
};

/// The surface is not a closed, manifold, consistently wound solid (open, non-manifold or inconsistently
/// wound): what repair_mesh() fixes, and what the convex and shell inertia models accept.
class SurfaceError : public Error {
 public:
  using Error::Error;
};

/// The first checks of validate_mesh() (and of repair_mesh()): triangles and vertices present, indices in
/// range, finite coordinates, the used vertices' bounding-box diagonal D in [1e-50, 1e50]. Returns the used
/// vertices' bounding box; throws repose::Error("NAME: problem") otherwise.
Aabb check_surface_input(const TriangleMesh& mesh, const std::string& name);

/// The checks and repairs of validate_mesh() that any surface needs (non-finite coordinates, indices,
/// size, welding, degenerate triangles, unused vertices), for a surface that need not be closed: an open
/// or non-manifold shell. Throws repose::Error as validate_mesh() does for those problems.
MeshReport clean_mesh(TriangleMesh& mesh, const std::string& name);

/// Validates `mesh` in place and repairs what is safe to repair.
///
/// `name` (usually the file name or shape spec) starts every error message. Throws repose::Error when the
/// surface is empty, has a non-finite coordinate, an index out of range, is open (boundary edges) or
/// non-manifold, has inconsistent winding between neighbours (these three as SurfaceError), or encloses
/// zero volume. Tolerances are
/// relative to the bounding-box diagonal D: vertices closer than 1e-10·D are welded, triangles with area
/// below 1e-14·D² are degenerate, and |volume| below 1e-12·D³ is zero.
MeshReport validate_mesh(TriangleMesh& mesh, const std::string& name);

/// Signed volume enclosed by a closed surface (positive for outward-facing triangles).
double signed_volume(const TriangleMesh& mesh);

}  // namespace repose
