#include <algorithm>
#include <cmath>
#include <numbers>

#include "readers.hpp"

namespace repose::io {

void Polygons::finish(const std::vector<Vec3>& vertices) {
  for (const std::size_t q : quads_) {
    const std::int32_t c[4] = {out_[q][0], out_[q][1], out_[q][2], out_[q + 1][2]};
    // A corner is concave when the angles from its two edges to the diagonal add up to more than π; a quad
    // has at most one. Indices were checked, so the positions exist.
    for (int i = 0; i < 4; ++i) {
      const Vec3& v = vertices[c[i]];
      const Vec3 left = (vertices[c[(i + 3) % 4]] - v).normalized();
      const Vec3 diag = (vertices[c[(i + 2) % 4]] - v).normalized();
      const Vec3 right = (vertices[c[(i + 1) % 4]] - v).normalized();
      const auto angle = [](const Vec3& a, const Vec3& b) {
        return std::acos(std::clamp(a.dot(b), -1.0, 1.0));
      };
      if (angle(left, diag) + angle(right, diag) > std::numbers::pi) {
        out_[q] = {c[i], c[(i + 1) % 4], c[(i + 2) % 4]};
        out_[q + 1] = {c[i], c[(i + 2) % 4], c[(i + 3) % 4]};
        break;
      }
    }
  }
}

}  // namespace repose::io
