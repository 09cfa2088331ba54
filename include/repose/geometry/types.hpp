// Basic geometric types shared by every module.
//
// Conventions (used everywhere in repose):
// - Vectors and matrices are Eigen, double precision.
// - Quaternions are Eigen::Quaterniond; when written as four numbers the order is [w, x, y, z].
// - The world frame has gravity along -z and the wall is the plane z = 0.
// - Lengths are in the user's length unit (m for --units si, cm for --units cgs); repose never assumes a
//   scale, and every tolerance is relative to the particle's characteristic length L.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

namespace repose {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// Indices of a triangle's three vertices, counter-clockwise seen from outside (outward normal by the
/// right-hand rule).
using Triangle = std::array<std::int32_t, 3>;

/// An indexed triangle mesh. Plain data: no invariants are enforced here; see validate_mesh().
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
};

/// Axis-aligned bounding box.
struct Aabb {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
  Vec3 size() const { return max - min; }
  Vec3 center() const { return 0.5 * (min + max); }
};

/// Bounding box of a point set (zero box for an empty set).
Aabb bounding_box(const std::vector<Vec3>& points);

}  // namespace repose
