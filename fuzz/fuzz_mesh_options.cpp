// libFuzzer harness for the ways a surface that is not a clean solid becomes a particle: --repair,
// --largest-component, --inertia convex and --inertia shell (MeshOptions). The first byte picks the option,
// the rest is an OBJ file (text mutates into coincident points, repeated corners, open borders, fins and
// several parts: the inputs these options exist for).
//
// Oracle: the bytes are rejected with repose::Error, or the particle has finite, positive mass properties
// and a convex hull that contains every vertex of its surface and its centre of mass (a solid's, a hull's
// and a surface's centre of mass all lie in the hull of its points). With --repair the surface is a closed,
// consistently wound solid by the harness's own checks (solid_checks.hpp) whose volume is the particle's
// within round-off. With --inertia convex, when the particle is the hull of the file's points, every one
// of them lies in the hull. Anything else (another
// exception, a failed check, a sanitizer report) is a crash.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "repose/error.hpp"
#include "repose/io/mesh_io.hpp"
#include "repose/model/particle.hpp"
#include "solid_checks.hpp"

namespace {

using repose_fuzz::require;

// How far outside a hull face's plane a point may lie by round-off: as in fuzz_mesh.cpp, 1e-9·D, or more
// for a face through points only s apart (its normal is then known to ~ε·D/s).
double hull_tolerance(const std::vector<repose::Vec3>& points, double diagonal) {
  double shortest = diagonal;
  for (std::size_t i = 0; i + 1 < points.size() && i < 64; ++i)
    for (std::size_t j = i + 1; j < points.size() && j < 64; ++j)
      if (points[i] != points[j]) shortest = std::min(shortest, (points[i] - points[j]).norm());
  return std::max(1e-9 * diagonal, 4 * DBL_EPSILON * diagonal * diagonal / std::max(shortest, 1e-300));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  repose::MeshOptions options;
  switch (data[0] % 4) {
    case 0:
      options.repair = true;
      break;
    case 1:
      options.largest_component = true;
      break;
    case 2:
      options.inertia = repose::InertiaModel::convex;
      break;
    default:
      options.inertia = repose::InertiaModel::shell;
  }
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    const repose::TriangleMesh file = repose::read_mesh_from_memory(bytes, "fuzz.obj");
    const repose::Particle p = repose::make_particle(file, "fuzz.obj", 1.0, options);
    require(std::isfinite(p.mass.mass) && p.mass.mass > 0);
    require(p.mass.inertia.allFinite() && p.mass.principal_moments.allFinite());
    require(
        (p.mass.principal_moments.array() >= -1e-9 * p.mass.principal_moments.cwiseAbs().maxCoeff()).all());
    require(std::isfinite(p.length) && p.length > 0 && p.input_offset.allFinite() && !p.hull.faces.empty());

    const double diagonal = (p.bounds.max - p.bounds.min).norm();
    std::vector<repose::Vec3> points = p.mesh.vertices;
    // With --inertia convex, when the particle is the hull of the file's points (a point cloud, or a soup
    // that is no closed solid), every point of the file too (body frame). A closed solid keeps its own
    // validated surface, without the vertices validation dropped (unused, or used only by a degenerate
    // triangle): its vertices are in `points` already.
    if (options.inertia == repose::InertiaModel::convex && p.surface_is_hull)
      for (const repose::Vec3& v : file.vertices) points.push_back(v * options.scale - p.input_offset);
    const double tol = hull_tolerance(points, diagonal);
    for (const repose::HullFace& f : p.hull.faces) {
      require(f.normal.allFinite() && std::abs(f.normal.norm() - 1) < 1e-9);
      require(f.offset >= -tol);  // the centre of mass (the body origin) is inside
      for (const repose::Vec3& v : points) require(f.normal.dot(v) <= f.offset + tol);
    }

    if (options.repair || options.largest_component) {
      require(repose_fuzz::closed_and_consistently_wound(p.mesh));
      const repose_fuzz::SolidSums sums = repose_fuzz::solid_sums(p.mesh);
      require(std::abs(p.mass.volume - sums.volume) <= repose_fuzz::volume_round_off(p.mesh, sums));
      require(p.repair.has_value());
    }
  } catch (const repose::Error&) {
    return 0;
  } catch (...) {
    __builtin_trap();
  }
  return 0;
}
