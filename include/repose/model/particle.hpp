// The particle model: everything about a particle that does not change while it settles.
//
// Built once from a mesh (or a built-in shape) and then shared read-only by any number of runs and threads,
// like MuJoCo's mjModel. The surface is re-expressed in the body frame: origin at the centre of mass, axes
// those of the input mesh (not the principal axes, so that a user's orientation refers to their own mesh).
#pragma once

#include <string>
#include <vector>

#include "repose/geometry/hull.hpp"
#include "repose/geometry/mass.hpp"
#include "repose/geometry/mesh.hpp"
#include "repose/geometry/types.hpp"

namespace repose {

struct Particle {
  std::string name;     ///< file name or shape spec it was built from
  TriangleMesh mesh;    ///< validated surface, body frame (centre of mass at the origin)
  Vec3 input_offset;    ///< centre of mass in the input mesh's frame (body = input − input_offset)
  MassProperties mass;  ///< about the centre of mass, body frame (center_of_mass is zero)
  ConvexHull hull;      ///< convex hull of `mesh.vertices`, body frame
  double length = 0;    ///< characteristic length L = volume-equivalent sphere diameter (6V/π)^(1/3)
  Aabb bounds;          ///< body-frame bounding box
  MeshReport report;    ///< what validation repaired

  // Derived facts the settling engine and the rest-pose statistics use (computed once here).
  double max_dihedral_angle = 0;  ///< largest angle between the normals of neighbouring triangles (rad)
  bool convex_surface = false;    ///< no reflex (concave) edge
  /// Per hull face: signed distance (length) from the centre of mass's projection onto the face plane to the
  /// face boundary, positive inside. A face is a stable rest iff its margin is > 0 (static stability).
  std::vector<double> face_stability_margin;
  /// Per hull face: true if mesh triangles cover it (a flat face of the particle), false if only isolated
  /// points of the particle lie on it (a jagged particle resting on its tips).
  std::vector<bool> face_is_flat;
};

/// Builds a particle from a validated-or-not mesh: validates/repairs it, computes mass properties with the
/// given density (mass per unit volume, > 0), moves it to the body frame and builds the hull.
Particle make_particle(TriangleMesh mesh, const std::string& name, double density);

/// Loads `source` (a mesh file or a shape spec such as "box:x=1,y=2,z=3") and builds the particle.
Particle load_particle(const std::string& source, double density);

/// The characteristic length of a solid of volume `volume`: the diameter of the sphere of equal volume.
double characteristic_length(double volume);

}  // namespace repose
