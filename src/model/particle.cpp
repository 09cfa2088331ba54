#include "repose/model/particle.hpp"

#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>

#include "repose/error.hpp"
#include "repose/geometry/shapes.hpp"
#include "repose/io/mesh_io.hpp"
#include "surface_facts.hpp"

namespace repose {

namespace {

// The hull's planar faces as triangles (fans: each face is convex, its loop counter-clockwise from outside).
TriangleMesh hull_surface(const ConvexHull& hull) {
  TriangleMesh mesh;
  mesh.vertices = hull.vertices;
  for (const HullFace& face : hull.faces)
    for (std::size_t i = 1; i + 1 < face.loop.size(); ++i)
      mesh.triangles.push_back({face.loop[0], face.loop[i], face.loop[i + 1]});
  return mesh;
}

// The convex hull of a point set, with `name` in its errors.
ConvexHull hull_of(const std::vector<Vec3>& points, const std::string& name) {
  try {
    return compute_convex_hull(points);
  } catch (const Error& e) {
    throw Error(name + ": " + e.what());
  }
}

std::string str(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

// The surface whose mass the particle has, per inertia model, in the input frame; `mesh` becomes the surface
// the particle keeps (validated or cleaned, or the hull's for the convex model of a non-solid).
MassProperties input_mass_properties(TriangleMesh& mesh, const std::string& name, double density,
                                     Particle& p) {
  switch (p.options.inertia) {
    case InertiaModel::exact:
      try {
        p.report = validate_mesh(mesh, name);
      } catch (const SurfaceError& e) {
        throw SurfaceError(
            std::string(e.what()) +
            "; --repair tries to mend it (holes, winding, duplicates), or --inertia convex or --inertia "
            "shell loads it as it is");
      }
      return compute_mass_properties(mesh, density);
    case InertiaModel::shell:
      p.report = clean_mesh(mesh, name);
      return compute_shell_properties(mesh, density);
    case InertiaModel::convex:
      break;
  }
  // The convex model: a closed solid keeps its own surface (and so its shape in output and its flat faces);
  // anything else, a soup or a point cloud, is its hull.
  if (!mesh.triangles.empty()) {
    TriangleMesh solid = mesh;
    try {
      p.report = validate_mesh(solid, name);
      mesh = std::move(solid);
    } catch (const SurfaceError& e) {
      p.surface_is_hull = true;
      // What the file holds, as for a solid (duplicates, degenerate triangles), though its hull is used.
      TriangleMesh cleaned = mesh;
      p.report = clean_mesh(cleaned, name);
      // The message without its "NAME: " prefix (validate_mesh starts every message with the name).
      p.report.warnings.push_back(std::string("the surface is not a closed solid (") +
                                  (e.what() + name.size() + 2) + "): the particle is its convex hull");
    }
  } else {
    p.surface_is_hull = true;
    p.report = {};
    p.report.input_vertices = static_cast<int>(mesh.vertices.size());
  }
  if (!p.surface_is_hull) return compute_mass_properties(hull_surface(hull_of(mesh.vertices, name)), density);
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (!mesh.vertices[v].allFinite())
      throw Error(name + ": vertex " + std::to_string(v) + " has a non-finite coordinate");
  // The range validate_mesh() accepts, for the same reason (tolerances and inertia stay representable).
  const double diag = bounding_box(mesh.vertices).size().norm();
  if (!(diag >= 1e-50 && diag <= 1e50))
    throw Error(name + ": size out of range (bounding-box diagonal " + str(diag) +
                "; must be in [1e-50, 1e50])");
  mesh = hull_surface(hull_of(mesh.vertices, name));
  return compute_mass_properties(mesh, density);
}

}  // namespace

const char* to_string(InertiaModel model) {
  switch (model) {
    case InertiaModel::exact:
      return "exact";
    case InertiaModel::convex:
      return "convex";
    case InertiaModel::shell:
      return "shell";
  }
  return "?";
}

InertiaModel parse_inertia_model(const std::string& text) {
  if (text == "exact") return InertiaModel::exact;
  if (text == "convex") return InertiaModel::convex;
  if (text == "shell") return InertiaModel::shell;
  throw Error("inertia model '" + text + "': must be exact, convex or shell");
}

double mesh_unit_scale(const std::string& unit, bool to_cm) {
  const double to = to_cm ? 100.0 : 1.0;
  if (unit == "mm") return 1e-3 * to;
  if (unit == "cm") return 1e-2 * to;
  if (unit == "m") return to;
  if (unit == "in") return 0.0254 * to;
  throw Error("mesh unit '" + unit + "': must be mm, cm, m or in");
}

double characteristic_length(double volume) { return std::cbrt(6.0 * volume / std::numbers::pi); }

Particle make_particle(TriangleMesh mesh, const std::string& name, double density,
                       const MeshOptions& options) {
  if (!std::isfinite(density) || density <= 0)
    throw Error(name + ": density must be a finite positive number, got " + str(density));
  if (!std::isfinite(options.scale) || options.scale <= 0)
    throw Error(name + ": scale must be a finite positive number, got " + str(options.scale));
  Particle p;
  p.name = name;
  p.options = options;
  // The scale comes first: every tolerance below is relative to the scaled size.
  if (options.scale != 1)
    for (Vec3& v : mesh.vertices) v *= options.scale;
  if (mesh.triangles.empty() && options.inertia != InertiaModel::convex)
    throw Error(name + ": no faces (a point cloud of " + std::to_string(mesh.vertices.size()) +
                " vertices); --inertia convex loads it as the solid convex hull of its points");
  std::optional<MeshReport> file_report;
  if (options.repair || options.largest_component) {
    if (mesh.triangles.empty())
      throw Error(name +
                  ": --repair needs faces, and this file has none (a point cloud); --inertia convex "
                  "alone loads it");
    // What the file holds (its duplicate vertices, degenerate triangles), counted as without --repair,
    // before the repair changes it: the report describes the user's file, not the repaired surface.
    TriangleMesh as_read = mesh;
    file_report = clean_mesh(as_read, name);
    p.repair = repair_mesh(mesh, name, options.largest_component);
  }

  const MassProperties input_mass = input_mass_properties(mesh, name, density, p);
  if (file_report) {
    file_report->flipped = p.report.flipped;  // the repaired surface's orientation (faces: p.repair)
    file_report->warnings.insert(file_report->warnings.end(), p.report.warnings.begin(),
                                 p.report.warnings.end());
    p.report = std::move(*file_report);
  }
  // A solid's centre of mass lies inside its bounding box. When the signed volume is only round-off (a
  // nearly flat closed surface), the centre of mass comes out anywhere; such a mesh is no solid (found by
  // fuzz_mesh_ply: volume 0 after re-centring, centre of mass 1e7 away).
  const Aabb box = bounding_box(mesh.vertices);
  const double slack = 1e-6 * box.size().norm();
  const bool com_inside = input_mass.center_of_mass.allFinite() &&
                          (input_mass.center_of_mass.array() >= box.min.array() - slack).all() &&
                          (input_mass.center_of_mass.array() <= box.max.array() + slack).all();
  const bool shell = options.inertia == InertiaModel::shell;
  if (!(shell ? input_mass.area > 0 : input_mass.volume > 0) || !com_inside)
    throw Error(name + ": degenerate solid: its volume is too small to locate its centre of mass");
  p.input_offset = input_mass.center_of_mass;
  if (options.center_of_mass) {
    if (!options.center_of_mass->allFinite())
      throw Error(name + ": the centre of mass given must be three finite numbers");
    p.input_offset = options.scale * *options.center_of_mass;
  }
  for (Vec3& v : mesh.vertices) v -= p.input_offset;
  p.mesh = std::move(mesh);
  p.hull = hull_of(p.mesh.vertices, name);

  // Recompute in the body frame rather than shifting, so the stored centre of mass is zero to round-off of
  // the body-frame coordinates themselves.
  const bool hull_solid = options.inertia == InertiaModel::convex && !p.surface_is_hull;
  const TriangleMesh hull_mesh = hull_surface(p.hull);
  p.mass = shell        ? compute_shell_properties(p.mesh, density)
           : hull_solid ? compute_mass_properties(hull_mesh, density)
                        : compute_mass_properties(p.mesh, density);
  const double volume =
      options.inertia == InertiaModel::exact ? p.mass.volume : compute_mass_properties(hull_mesh, 1.0).volume;
  if (!(volume > 0) || !std::isfinite(volume) || !p.mass.inertia.allFinite() || !(p.mass.mass > 0))
    throw Error(name + ": degenerate solid: its volume is too small to locate its centre of mass");
  if (options.center_of_mass) p.mass = with_center_of_mass(p.mass, Vec3::Zero());
  p.length = characteristic_length(volume);
  p.bounds = bounding_box(p.mesh.vertices);
  // A solid's centre of mass is strictly inside its convex hull. A closed, consistently wound surface of
  // positive volume can still pass through itself; then the centre of mass can fall outside the hull, and no
  // rest pose makes sense (found by fuzz_mesh_off / fuzz_mesh_ply).
  for (const HullFace& face : p.hull.faces)
    if (!(face.offset > 0))
      throw Error(name + (options.center_of_mass
                              ? ": the centre of mass given (--com) is not inside the convex hull"
                              : ": not a solid: the surface intersects itself (its centre of mass is outside "
                                "its convex hull)"));

  // Nor are its principal moments a body's: each is the sum of two of the second moments Σm·x², Σm·y², Σm·z²
  // along the principal axes, which are never negative, so the largest is at most the sum of the other two
  // (equal for a flat plate; 1e-9 of the trace for round-off). A surface through itself can break this with
  // its centre of mass inside the hull (found by fuzz_mesh_options: a repaired part with a moment of −0.47).
  const Vec3& moments = p.mass.principal_moments;
  const double trace = moments.sum();
  if (!(trace / 2 - moments.maxCoeff() >= -1e-9 * std::abs(trace)))
    throw Error(name + ": not a solid: its principal moments of inertia " + str(moments[0]) + ", " +
                str(moments[1]) + ", " + str(moments[2]) + " are no body's (the surface intersects itself)" +
                (options.inertia == InertiaModel::convex ? "" : "; --inertia convex loads its convex hull"));

  compute_dihedral_facts(p.mesh, p.length, p.max_dihedral_angle, p.convex_surface);
  for (const HullFace& face : p.hull.faces)
    p.face_stability_margin.push_back(face_stability_margin(p.hull, face, Vec3::Zero()));
  p.face_is_flat = faces_covered_by_mesh(p.mesh, p.hull, p.length);
  return p;
}

Particle load_particle(const std::string& source, double density, const MeshOptions& options) {
  if (is_shape_spec(source)) return make_particle(make_shape(source), source, density, options);
  return make_particle(read_mesh(source), source, density, options);
}

}  // namespace repose
