// A particle with a face of stability margin exactly 0: a triangular prism, cross-section A(0,0), B(1,0),
// C(2,1) in x–z, 1 deep in y (uniform convex solid, density 1000). Its centroid's x is (0 + 1 + 2)/3 = 1,
// over the edge B of its base AB; |BG| = 1/3, and I_G/(m·|BG|²) = 2 (the triangle's polar moment, (1 + 2 +
// 5)/36).
#pragma once

#include "repose/model/particle.hpp"

namespace repose::test_shapes {

inline Particle zero_margin_prism() {
  TriangleMesh mesh;
  for (const double y : {0.0, 1.0})
    for (const Vec2& xz : {Vec2(0, 0), Vec2(1, 0), Vec2(2, 1)}) mesh.vertices.emplace_back(xz.x(), y, xz.y());
  MeshOptions options;
  options.inertia = InertiaModel::convex;
  return make_particle(mesh, "prism", 1000.0, options);
}

}  // namespace repose::test_shapes
