// The C API's particles: from a file or shape spec, or from vertex and triangle arrays.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "capi_support.hpp"
#include "repose/geometry/shapes.hpp"

using repose::capi::CodedError;
using repose::capi::guarded;
using repose::capi::require;

namespace {

repose::MeshOptions mesh_options(const repose_mesh_options* c) {
  repose::MeshOptions o;
  if (c == nullptr) return o;
  if (!std::isfinite(c->scale) || c->scale <= 0)
    throw CodedError(REPOSE_ERROR_BAD_PARAMETER,
                     "options.scale must be a finite number > 0, got " + std::to_string(c->scale));
  o.scale = c->scale;
  switch (c->inertia) {
    case REPOSE_INERTIA_EXACT:
      o.inertia = repose::InertiaModel::exact;
      break;
    case REPOSE_INERTIA_CONVEX:
      o.inertia = repose::InertiaModel::convex;
      break;
    case REPOSE_INERTIA_SHELL:
      o.inertia = repose::InertiaModel::shell;
      break;
    default:
      throw CodedError(REPOSE_ERROR_BAD_PARAMETER,
                       "options.inertia must be REPOSE_INERTIA_EXACT, _CONVEX or _SHELL (0, 1, 2), got " +
                           std::to_string(c->inertia));
  }
  o.largest_component = c->largest_component != 0;
  o.repair = c->repair != 0 || o.largest_component;
  if (c->has_center_of_mass != 0) {
    const repose::Vec3 com(c->center_of_mass[0], c->center_of_mass[1], c->center_of_mass[2]);
    if (!com.allFinite())
      throw CodedError(REPOSE_ERROR_BAD_PARAMETER, "options.center_of_mass must be finite");
    o.center_of_mass = com;
  }
  return o;
}

void check_density(double density) {
  if (!std::isfinite(density) || density <= 0)
    throw CodedError(REPOSE_ERROR_BAD_PARAMETER,
                     "density must be a finite number > 0, got " + std::to_string(density));
}

}  // namespace

extern "C" {

int repose_mesh_options_init(repose_mesh_options* options) {
  return guarded("repose_mesh_options_init", REPOSE_ERROR_INTERNAL, [&] {
    require(options, "options");
    *options = repose_mesh_options{};
    options->scale = 1;
    options->inertia = REPOSE_INERTIA_EXACT;
  });
}

int repose_particle_load(const char* source, double density, const repose_mesh_options* options,
                         repose_particle** particle) {
  return guarded("repose_particle_load", REPOSE_ERROR_BAD_MESH, [&] {
    require(source, "source");
    require(particle, "particle");
    check_density(density);
    const repose::MeshOptions o = mesh_options(options);
    const std::string path = source;
    if (!repose::is_shape_spec(path) && (!std::filesystem::is_regular_file(path) || !std::ifstream(path)))
      throw CodedError(REPOSE_ERROR_FILE, path + ": cannot open (not a readable file)");
    auto model = std::make_shared<const repose::Particle>(repose::load_particle(path, density, o));
    *particle = new repose_particle{std::move(model)};
  });
}

int repose_particle_from_arrays(const double* vertices, size_t vertex_count, const int* triangles,
                                size_t triangle_count, double density, const repose_mesh_options* options,
                                const char* name, repose_particle** particle) {
  return guarded("repose_particle_from_arrays", REPOSE_ERROR_BAD_MESH, [&] {
    require(particle, "particle");
    if (vertex_count > 0) require(vertices, "vertices");
    if (triangle_count > 0) require(triangles, "triangles");
    check_density(density);
    const std::string label = name != nullptr ? name : "arrays";
    if (vertex_count > static_cast<size_t>(INT32_MAX) || triangle_count > static_cast<size_t>(INT32_MAX))
      throw CodedError(REPOSE_ERROR_BAD_MESH, label + ": more than 2^31 - 1 vertices or triangles");
    repose::TriangleMesh mesh;
    mesh.vertices.reserve(vertex_count);
    for (size_t i = 0; i < vertex_count; ++i)
      mesh.vertices.emplace_back(vertices[3 * i], vertices[3 * i + 1], vertices[3 * i + 2]);
    mesh.triangles.reserve(triangle_count);
    for (size_t i = 0; i < triangle_count; ++i) {
      repose::Triangle t;
      for (size_t k = 0; k < 3; ++k) {
        const int index = triangles[3 * i + k];
        if (index < 0 || static_cast<size_t>(index) >= vertex_count)
          throw CodedError(REPOSE_ERROR_BAD_MESH, label + ": triangle " + std::to_string(i) +
                                                      " refers to vertex " + std::to_string(index) + " of " +
                                                      std::to_string(vertex_count) + " (0-based)");
        t[k] = index;
      }
      mesh.triangles.push_back(t);
    }
    const repose::MeshOptions o = mesh_options(options);
    auto model =
        std::make_shared<const repose::Particle>(repose::make_particle(std::move(mesh), label, density, o));
    *particle = new repose_particle{std::move(model)};
  });
}

void repose_particle_free(repose_particle* particle) { delete particle; }

int repose_particle_info_get(const repose_particle* particle, repose_particle_info* info) {
  return guarded("repose_particle_info_get", REPOSE_ERROR_INTERNAL, [&] {
    require(particle, "particle");
    require(info, "info");
    const repose::Particle& p = *particle->model;
    repose_particle_info out{};
    out.mass = p.mass.mass;
    out.volume = p.mass.volume;
    out.length = p.length;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out.inertia[3 * r + c] = p.mass.inertia(r, c);
    for (int k = 0; k < 3; ++k) out.center_of_mass[k] = p.input_offset[k];
    out.hull_vertex_count = static_cast<int>(p.hull.vertices.size());
    out.hull_face_count = static_cast<int>(p.hull.faces.size());
    *info = out;
  });
}

}  // extern "C"
