// A grain of many hull vertices for the benchmarks (bench/peers/peer_bullet.cpp, bench/scaling.cpp): the
// shape library's irregular grains reach only ~1,000 hull vertices at 128,000 triangles (their hull vertex
// count grows linearly with the icosphere frequency), so this is an ellipsoid (semi-axes 0.5, 0.4, 0.3 m) at
// geodesic frequency n (20·n² triangles, 10·n² + 2 vertices: n = 32 gives 10,242) with twelve smooth random
// radial bumps of ±10 % (fixed seed, the same bumps at every n): concave between bumps, so not "smooth", and
// several distinct rest poses.
#pragma once

#include <cmath>
#include <numbers>
#include <random>
#include <repose/geometry/shapes.hpp>
#include <string>
#include <vector>

inline repose::TriangleMesh bumpy_ellipsoid(int frequency) {
  repose::TriangleMesh mesh =
      repose::make_shape("ellipsoid:a=0.5,b=0.4,c=0.3,n=" + std::to_string(frequency));
  std::mt19937_64 bits(12);
  const auto uniform = [&] { return static_cast<double>(bits() >> 11) * 0x1.0p-53; };
  std::vector<repose::Vec3> centre;
  std::vector<double> amplitude;
  for (int k = 0; k < 12; ++k) {
    const double z = 2 * uniform() - 1, phi = 2 * std::numbers::pi * uniform(), s = std::sqrt(1 - z * z);
    centre.emplace_back(s * std::cos(phi), s * std::sin(phi), z);
    amplitude.push_back(0.2 * uniform() - 0.1);
  }
  for (repose::Vec3& v : mesh.vertices) {
    const repose::Vec3 u = v.normalized();
    double scale = 1;
    for (int k = 0; k < 12; ++k) scale += amplitude[k] * std::exp(-(1 - u.dot(centre[k])) / (0.3 * 0.3));
    v *= scale;
  }
  return mesh;
}
