// The CGAL side of repair_mesh(): types and the stages shared by repair.cpp and repair_soup.cpp.
//
// Every geometric decision is CGAL's, with the exact predicates of the Epick kernel; repose only orders the
// stages, counts what each changed and converts between TriangleMesh and CGAL::Surface_mesh. Vertex positions
// pass through unchanged (no stage constructs a point), which makes the counts and the winding comparison
// with the input exact.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "repose/geometry/repair.hpp"
#include "repose/geometry/types.hpp"

namespace repose::detail {

using RepairKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using RepairPoint = RepairKernel::Point_3;
using RepairMesh = CGAL::Surface_mesh<RepairPoint>;

std::string count_of(std::size_t n, const std::string& singular, const std::string& plural);

/// A triangle's three corner positions in ascending (x, y, z) order, and whether its winding is an even
/// permutation of that order: two triangles on the same corners have the same winding iff `even` agrees.
struct Winding {
  std::array<double, 9> corners{};
  bool even = false;
  bool operator<(const Winding& o) const { return corners < o.corners; }
};

Winding winding_of(const std::array<Vec3, 3>& corners);

/// The checks validate_mesh() makes first, with its messages (empty, index, non-finite, size): CGAL must see
/// only finite coordinates, valid indices and a size whose products neither underflow nor overflow.
void check_repair_input(const TriangleMesh& mesh, const std::string& name);

/// The soup stages: merge coincident vertices, drop collapsed and duplicate triangles, orient consistently
/// (cutting non-manifold edges and vertices apart), build `out`. Fills merged_vertices, degenerate_faces and
/// duplicate_faces. Returns the input's windings, sorted by corners (the first of
/// several input triangles on the same corners decides), to count flipped faces at the end.
std::vector<Winding> soup_to_mesh(const TriangleMesh& input, const std::string& name, RepairMesh& out,
                                  RepairReport& report);

}  // namespace repose::detail
