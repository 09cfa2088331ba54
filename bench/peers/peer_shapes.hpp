// The peer benchmark's particles (peer_bullet.cpp): its built-in shapes, and mesh files listed in a file
// (--meshes), each scaled to the run's characteristic length.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <repose/error.hpp>
#include <repose/model/particle.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../bumpy_ellipsoid.hpp"
#include "bullet_side.hpp"

namespace peer {

struct Shape {
  std::string name;               // row label
  std::string spec;               // repose shape spec, a mesh file, or "bumpy-ellipsoid" (built here)
  std::string about;              // what it is
  repose::MeshOptions mesh = {};  // how a mesh file is read (--meshes: repair, inertia model)
};

inline repose::Particle make_shape_particle(const Shape& shape, double scale = 1) {
  repose::MeshOptions options = shape.mesh;
  options.scale *= scale;
  if (shape.spec == "bumpy-ellipsoid")
    return repose::make_particle(bumpy_ellipsoid(32), shape.spec, kDensity, options);
  return repose::load_particle(shape.spec, kDensity, options);
}

// The scale that gives the shape a characteristic length of `length` metres (0: its own size).
inline double scale_to(const Shape& shape, double length) {
  return length > 0 ? length / make_shape_particle(shape).length : 1.0;
}

// --meshes FILE: one row per line, "NAME PATH [--repair] [--convex]" (PATH relative to FILE's directory;
// # starts a comment), e.g. the real meshes scripts/fetch-meshes.sh writes with their provenance.
inline std::vector<Shape> read_mesh_list(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw repose::Error(file + ": cannot read the mesh list");
  const std::filesystem::path dir = std::filesystem::path(file).parent_path();
  std::vector<Shape> shapes;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    Shape shape;
    std::string path, option;
    if (!(words >> shape.name)) continue;
    if (!(words >> path))
      throw repose::Error(file + ":" + std::to_string(number) + ": expected NAME PATH [--repair] [--convex]");
    shape.spec = (dir / path).string();
    shape.about = path;
    while (words >> option) {
      if (option == "--repair")
        shape.mesh.repair = true;
      else if (option == "--convex")
        shape.mesh.inertia = repose::InertiaModel::convex;
      else
        throw repose::Error(file + ":" + std::to_string(number) + ": unknown option " + option +
                            " (expected --repair or --convex)");
    }
    shapes.push_back(shape);
  }
  return shapes;
}

// The built-in rows and their default drops (a run of a few minutes, about 2.5 on a loaded 2 GHz core).
inline std::vector<std::pair<Shape, std::uint64_t>> default_shapes() {
  return {
      {{"cube", "box:x=1,y=1,z=1", "cube, 1 m"}, 2000},
      {{"box123", "box:x=1,y=2,z=3", "box 1x2x3 m"}, 2000},
      {{"tetrahedron", "tetrahedron:edge=1", "regular tetrahedron, edge 1 m"}, 2000},
      {{"cylinder64", "cylinder:r=0.5,h=1,n=64", "64-segment cylinder"}, 1000},
      {{"ellipsoid2000", "ellipsoid:a=0.625,b=0.5,c=0.285,n=10", "ellipsoid, 2,000 triangles"}, 500},
      {{"grain100", "irregular:seed=1,n=7", "irregular grain"}, 500},
      {{"grain1000", "irregular:seed=1,n=68", "irregular grain"}, 200},
      {{"grain10000", "bumpy-ellipsoid", "bumpy ellipsoid (see source)"}, 50},
  };
}

}  // namespace peer
