#include "repose/geometry/types.hpp"

namespace repose {

Aabb bounding_box(const std::vector<Vec3>& points) {
  Aabb box;
  if (points.empty()) return box;
  box.min = points.front();
  box.max = points.front();
  for (const Vec3& p : points) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

}  // namespace repose
