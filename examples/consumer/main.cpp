// Builds a particle from a built-in shape and prints its mass properties.
#include <cmath>
#include <cstdio>
#include <repose/repose.hpp>

int main() {
  const repose::Particle cube = repose::load_particle("box:x=1,y=1,z=1", 2.0);
  std::printf("volume %.6f mass %.6f L %.6f hull faces %zu\n", cube.mass.volume, cube.mass.mass, cube.length,
              cube.hull.faces.size());
  // A unit cube of density 2: mass 2, six hull faces.
  return (std::abs(cube.mass.mass - 2.0) < 1e-12 && cube.hull.faces.size() == 6) ? 0 : 1;
}
