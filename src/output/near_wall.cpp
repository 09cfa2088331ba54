#include "near_wall.hpp"

namespace repose {

std::vector<int> hull_vertices_near_wall(const Particle& particle, const Quat& orientation, const Vec3& com,
                                         double eps) {
  const Mat3 rot = orientation.normalized().toRotationMatrix();
  std::vector<int> near;
  const auto& vertices = particle.hull.vertices;
  for (std::size_t i = 0; i < vertices.size(); ++i)
    if ((rot * vertices[i] + com).z() <= eps) near.push_back(static_cast<int>(i));
  return near;
}

}  // namespace repose
