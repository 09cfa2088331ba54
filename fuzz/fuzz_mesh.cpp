// libFuzzer harness for one mesh reader. The format is fixed at build time by REPOSE_FUZZ_MESH_EXT (".stl",
// ".obj", ".ply", ".off" or ".xyz"), so each reader gets its own binary and its own corpus.
//
// Oracle: the bytes are rejected with repose::Error, or they give a mesh with vertices whose triangle
// indices are in range (no triangles at all is a point cloud, which validate_mesh() then rejects; every .xyz
// file is one); if validate_mesh() accepts it, it is a solid by the harness's own checks (solid_checks.hpp):
// every vertex finite, closed and consistently wound (each directed edge once, its reverse once), a positive
// volume computed here by the divergence theorem and equal to the particle's within a round-off bound. The
// particle built from it has finite mass properties, a centre of mass inside its bounding box, and a convex
// hull that contains every vertex and the centre of mass. Anything else (another exception, a failed check, a
// sanitizer report) is a crash.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "repose/error.hpp"
#include "repose/geometry/mesh.hpp"
#include "repose/io/mesh_io.hpp"
#include "repose/model/particle.hpp"
#include "solid_checks.hpp"

#ifndef REPOSE_FUZZ_MESH_EXT
#error "define REPOSE_FUZZ_MESH_EXT, e.g. \".stl\""
#endif

namespace {

using repose_fuzz::require;

bool indices_in_range(const repose::TriangleMesh& mesh) {
  const auto n = static_cast<std::int64_t>(mesh.vertices.size());
  for (const repose::Triangle& t : mesh.triangles) {
    for (const std::int32_t i : t) {
      if (i < 0 || i >= n) return false;
    }
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::string name = std::string("fuzz") + REPOSE_FUZZ_MESH_EXT;
  try {
    repose::TriangleMesh mesh = repose::read_mesh_from_memory(bytes, name);
    require(!mesh.vertices.empty() && indices_in_range(mesh));
    if (std::string_view(REPOSE_FUZZ_MESH_EXT) == ".xyz") require(mesh.triangles.empty());

    repose::validate_mesh(mesh, name);
    require(!mesh.triangles.empty() && indices_in_range(mesh));
    for (const repose::Vec3& v : mesh.vertices) require(v.allFinite());
    require(repose_fuzz::closed_and_consistently_wound(mesh));
    const repose_fuzz::SolidSums sums = repose_fuzz::solid_sums(mesh);
    const double round_off = repose_fuzz::volume_round_off(mesh, sums);
    require(std::isfinite(sums.volume) && sums.volume > round_off);

    const repose::Particle p = repose::make_particle(mesh, name, 1.0);
    require(std::isfinite(p.mass.volume) && p.mass.volume > 0);
    require(std::isfinite(p.mass.mass) && p.mass.mass > 0);
    require(p.mass.center_of_mass.allFinite() && p.mass.inertia.allFinite());
    require(p.mass.principal_moments.allFinite() && p.mass.principal_axes.allFinite());
    require(std::isfinite(p.length) && p.length > 0);
    require(p.input_offset.allFinite() && !p.hull.faces.empty());
    // The same solid: the same volume (p.mesh is the validated mesh moved to the centre of mass).
    require(std::abs(p.mass.volume - sums.volume) <= round_off);
    require(p.mesh.triangles.size() == mesh.triangles.size());
    // A solid's centre of mass (the body-frame origin) lies in its bounding box and inside its convex hull,
    // and the hull contains every vertex: no vertex further than round-off outside any hull face's plane.
    // qhull places planes to ~1e-15 relative; 1e-9·D leaves room for its coplanar-facet merging. A face
    // through vertices only s apart (the mesh welds only below 1e-10·D) has its normal determined to ~ε·D/s
    // only, so its plane can miss a vertex across the solid by ε·D²/s: found by the fuzzer, a vertex 1.2e-9·D
    // outside a face through vertices 2e-9·D apart. The shortest edge bounds s from below.
    double shortest = sums.diagonal;
    for (const repose::Triangle& t : p.mesh.triangles)
      for (int k = 0; k < 3; ++k)
        shortest = std::min(shortest, (p.mesh.vertices[t[k]] - p.mesh.vertices[t[(k + 1) % 3]]).norm());
    const double tol = std::max(1e-9 * sums.diagonal,
                                4 * DBL_EPSILON * sums.diagonal * sums.diagonal / std::max(shortest, 1e-300));
    require((p.bounds.min.array() <= tol).all() && (p.bounds.max.array() >= -tol).all());
    for (const repose::HullFace& f : p.hull.faces) {
      require(f.normal.allFinite() && std::abs(f.normal.norm() - 1) < 1e-9 && f.offset >= -tol);
      for (const repose::Vec3& v : p.mesh.vertices) require(f.normal.dot(v) <= f.offset + tol);
    }
  } catch (const repose::Error&) {
    return 0;
  } catch (...) {
    __builtin_trap();
  }
  return 0;
}
