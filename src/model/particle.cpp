#include "repose/model/particle.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "repose/error.hpp"
#include "repose/geometry/shapes.hpp"
#include "repose/io/mesh_io.hpp"
#include "surface_facts.hpp"

namespace repose {

double characteristic_length(double volume) { return std::cbrt(6.0 * volume / std::numbers::pi); }

Particle make_particle(TriangleMesh mesh, const std::string& name, double density) {
  if (!std::isfinite(density) || density <= 0) {
    std::ostringstream msg;
    msg << name << ": density must be a finite positive number, got " << density;
    throw Error(msg.str());
  }
  Particle p;
  p.name = name;
  p.report = validate_mesh(mesh, name);

  const MassProperties input_mass = compute_mass_properties(mesh, density);
  // A solid's centre of mass lies inside its bounding box. When the signed volume is only round-off (a
  // nearly flat closed surface), the centre of mass comes out anywhere; such a mesh is no solid (found by
  // fuzz_mesh_ply: volume 0 after re-centring, centre of mass 1e7 away).
  const Aabb box = bounding_box(mesh.vertices);
  const double slack = 1e-6 * box.size().norm();
  const bool com_inside = input_mass.center_of_mass.allFinite() &&
                          (input_mass.center_of_mass.array() >= box.min.array() - slack).all() &&
                          (input_mass.center_of_mass.array() <= box.max.array() + slack).all();
  if (!(input_mass.volume > 0) || !com_inside)
    throw Error(name + ": degenerate solid: its volume is too small to locate its centre of mass");
  p.input_offset = input_mass.center_of_mass;
  for (Vec3& v : mesh.vertices) v -= p.input_offset;
  p.mesh = std::move(mesh);

  // Recompute in the body frame rather than shifting, so the stored centre of mass is zero to round-off of
  // the body-frame coordinates themselves.
  p.mass = compute_mass_properties(p.mesh, density);
  if (!(p.mass.volume > 0) || !std::isfinite(p.mass.volume) || !p.mass.inertia.allFinite())
    throw Error(name + ": degenerate solid: its volume is too small to locate its centre of mass");
  p.length = characteristic_length(p.mass.volume);
  p.bounds = bounding_box(p.mesh.vertices);
  p.hull = compute_convex_hull(p.mesh.vertices);
  // A solid's centre of mass is strictly inside its convex hull. A closed, consistently wound surface of
  // positive volume can still pass through itself; then the centre of mass can fall outside the hull, and no
  // rest pose makes sense (found by fuzz_mesh_off / fuzz_mesh_ply).
  for (const HullFace& face : p.hull.faces)
    if (!(face.offset > 0))
      throw Error(
          name +
          ": not a solid: the surface intersects itself (its centre of mass is outside its convex hull)");

  compute_dihedral_facts(p.mesh, p.length, p.max_dihedral_angle, p.convex_surface);
  for (const HullFace& face : p.hull.faces)
    p.face_stability_margin.push_back(face_stability_margin(p.hull, face, Vec3::Zero()));
  p.face_is_flat = faces_covered_by_mesh(p.mesh, p.hull, p.length);
  return p;
}

Particle load_particle(const std::string& source, double density) {
  if (is_shape_spec(source)) return make_particle(make_shape(source), source, density);
  return make_particle(read_mesh(source), source, density);
}

}  // namespace repose
