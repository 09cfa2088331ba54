// libFuzzer harness for one mesh reader. The format is fixed at build time by REPOSE_FUZZ_MESH_EXT (".stl",
// ".obj", ".ply" or ".off"), so each reader gets its own binary and its own corpus.
//
// Oracle: the bytes are rejected with repose::Error, or they give a mesh whose triangle indices are in
// range; if validate_mesh() accepts it, every vertex is finite, and the particle built from it has finite
// mass properties and a positive volume. Anything else (another exception, a failed check, a sanitizer
// report) is a crash.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "repose/error.hpp"
#include "repose/geometry/mesh.hpp"
#include "repose/io/mesh_io.hpp"
#include "repose/model/particle.hpp"

#ifndef REPOSE_FUZZ_MESH_EXT
#error "define REPOSE_FUZZ_MESH_EXT, e.g. \".stl\""
#endif

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

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
    require(!mesh.triangles.empty() && indices_in_range(mesh));

    repose::validate_mesh(mesh, name);
    require(!mesh.triangles.empty() && indices_in_range(mesh));
    for (const repose::Vec3& v : mesh.vertices) require(v.allFinite());

    const repose::Particle p = repose::make_particle(mesh, name, 1.0);
    require(std::isfinite(p.mass.volume) && p.mass.volume > 0);
    require(std::isfinite(p.mass.mass) && p.mass.mass > 0);
    require(p.mass.center_of_mass.allFinite() && p.mass.inertia.allFinite());
    require(p.mass.principal_moments.allFinite() && p.mass.principal_axes.allFinite());
    require(std::isfinite(p.length) && p.length > 0);
    require(p.input_offset.allFinite() && !p.hull.faces.empty());
  } catch (const repose::Error&) {
    return 0;
  } catch (...) {
    __builtin_trap();
  }
  return 0;
}
