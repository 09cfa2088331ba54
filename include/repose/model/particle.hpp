// The particle model: everything about a particle that does not change while it settles.
//
// Built once from a mesh (or a built-in shape) and then shared read-only by any number of runs and threads,
// like MuJoCo's mjModel. The surface is re-expressed in the body frame: origin at the centre of mass, axes
// those of the input mesh (not the principal axes, so that a user's orientation refers to their own mesh).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "repose/geometry/hull.hpp"
#include "repose/geometry/mass.hpp"
#include "repose/geometry/mesh.hpp"
#include "repose/geometry/repair.hpp"
#include "repose/geometry/types.hpp"

namespace repose {

/// How the mass properties come from the mesh. The contact geometry is the convex hull in every model.
enum class InertiaModel {
  exact,   ///< the closed solid the surface bounds, uniform density (mass per volume): the default
  convex,  ///< the solid convex hull of the vertices, uniform density: any triangle soup or point cloud
  shell,   ///< mass spread uniformly on the surface, density per unit AREA: thin-walled parts, open or not
};
const char* to_string(InertiaModel model);
/// "exact", "convex" or "shell"; throws repose::Error naming the accepted values otherwise.
InertiaModel parse_inertia_model(const std::string& text);

/// How a mesh file becomes a particle; the defaults read a closed solid as it is.
struct MeshOptions {
  /// Every coordinate is multiplied by this before anything else (a file in mm run in metres: 0.001).
  double scale = 1;
  InertiaModel inertia = InertiaModel::exact;
  bool repair = false;             ///< repair_mesh() the surface first (holes, winding, duplicates)
  bool largest_component = false;  ///< keep only the largest connected component (implies repair)
  /// The centre of mass, in the file's coordinates (multiplied by `scale` like them), when it is known and
  /// is not the uniform model's (a weighted, hollow or non-uniform part): the inertia is then the model's
  /// distribution about this point (with_center_of_mass). It must lie inside the convex hull.
  std::optional<Vec3> center_of_mass;
  bool operator==(const MeshOptions&) const = default;
};

/// The factor that converts lengths in `unit` (mm, cm, m or in) to metres (`to_cm`: to centimetres);
/// throws repose::Error naming the accepted units otherwise.
double mesh_unit_scale(const std::string& unit, bool to_cm = false);

struct Particle {
  std::string name;     ///< file name or shape spec it was built from
  TriangleMesh mesh;    ///< validated surface, body frame (centre of mass at the origin)
  Vec3 input_offset;    ///< centre of mass in the input mesh's frame (body = input − input_offset)
  MassProperties mass;  ///< about the centre of mass, body frame (center_of_mass is zero)
  ConvexHull hull;      ///< convex hull of `mesh.vertices`, body frame
  /// characteristic length L = volume-equivalent sphere diameter (6V/π)^(1/3), V the solid's volume (exact)
  /// or the convex hull's (convex, shell)
  double length = 0;
  Aabb bounds;                         ///< body-frame bounding box
  MeshReport report;                   ///< what validation repaired
  MeshOptions options;                 ///< how the file was read (scale, inertia model, repair)
  std::optional<RepairReport> repair;  ///< what --repair did, if it ran
  /// The surface that holds the mass is the convex hull's (convex model, when the file is not a closed
  /// solid: `mesh` is then the hull triangulated).
  bool surface_is_hull = false;

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

/// Builds a particle from a validated-or-not mesh: scales it, repairs it if asked, validates it, computes
/// mass properties with the given density (> 0: mass per unit volume, or per unit area for the shell model),
/// moves it to the body frame and builds the hull. A mesh with no triangles (a point cloud) needs the convex
/// model; an open, non-manifold or inconsistently wound one needs repair or the convex or shell model: the
/// error names the option that would load it.
Particle make_particle(TriangleMesh mesh, const std::string& name, double density,
                       const MeshOptions& options = {});

/// Loads `source` (a mesh file or a shape spec such as "box:x=1,y=2,z=3") and builds the particle.
Particle load_particle(const std::string& source, double density, const MeshOptions& options = {});

/// The characteristic length of a solid of volume `volume`: the diameter of the sphere of equal volume.
double characteristic_length(double volume);

}  // namespace repose
