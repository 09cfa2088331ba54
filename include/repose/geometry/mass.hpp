// Mass properties of a closed triangulated solid of uniform density, or of a uniform surface (a shell).
#pragma once

#include "repose/geometry/types.hpp"

namespace repose {

/// Mass properties. Units: volume L^3, mass M, inertia M·L^2, for whatever length L and mass M units the
/// mesh and density are in.
struct MassProperties {
  double volume = 0;                       ///< the solid's volume (0 for a shell)
  double area = 0;                         ///< the surface's area (L^2)
  double mass = 0;                         ///< density · volume, or surface density · area
  Vec3 center_of_mass = Vec3::Zero();      ///< in the mesh's frame
  Mat3 inertia = Mat3::Zero();             ///< inertia tensor about the centre of mass, mesh axes
  Vec3 principal_moments = Vec3::Zero();   ///< eigenvalues of `inertia`, ascending
  Mat3 principal_axes = Mat3::Identity();  ///< columns are the principal axes, a proper rotation
};

/// Exact mass properties of a closed, outward-oriented triangle mesh (Eberly's polyhedral mass properties,
/// after Mirtich 1996). Integrals are taken relative to the bounding-box centre, so a particle far from the
/// origin loses no precision.
MassProperties compute_mass_properties(const TriangleMesh& mesh, double density);

/// Exact mass properties of a thin shell: mass spread uniformly over the triangles (any triangle set: open,
/// non-manifold or closed), `areal_density` in mass per unit area. Integrals relative to the bounding-box
/// centre, as above.
MassProperties compute_shell_properties(const TriangleMesh& mesh, double areal_density);

/// The mass properties of a body known only to have its centre of mass at `point` (a weighted, hollow or
/// non-uniform part): the same mass, `point` as the centre of mass, and as inertia `props`'s distribution
/// taken about `point` (the parallel-axis theorem, I + m·(|d|²·1 − d·dᵀ), d = point − centre): the best
/// guess the shape alone gives. Principal moments and axes are recomputed.
MassProperties with_center_of_mass(const MassProperties& props, const Vec3& point);

}  // namespace repose
