// The built-in shapes' meshes (internal to src/geometry: shapes.cpp parses a spec and calls these). Each
// returns the surface, not yet checked as a solid.
#pragma once

#include <cstdint>

#include "repose/geometry/types.hpp"

namespace repose::detail {

TriangleMesh make_box(double x, double y, double z);
TriangleMesh make_cylinder(double r, double h, int n);             ///< n sides
TriangleMesh make_ellipsoid(double a, double b, double c, int n);  ///< geodesic frequency n
TriangleMesh make_tetrahedron(double edge);
/// A seeded irregular grain of typical size `size` on a geodesic sphere of frequency n.
TriangleMesh make_irregular(std::uint64_t seed, double size, int n);

}  // namespace repose::detail
