// The vertex sets near the wall found by walks of the hull's edge graph (src/sim/wall/near_wall.hpp) against
// a scan of every vertex, the independent answer: on random convex hulls (4–300 points, so faces of many
// vertices and near-ties) at random orientations, one query after another as the body turns a little (the
// walks start from the last lowest vertex), the sets below random levels are the scan's exactly, in index
// order, and the lowest vertex by a scan's own arithmetic is among the candidates near the lowest.
#include "../../../src/sim/wall/near_wall.hpp"

#include <gtest/gtest.h>

#include <random>
#include <repose/model/particle.hpp>

namespace repose::sim {
namespace {

TEST(NearWall, WalksFindWhatAScanFinds) {
  std::mt19937_64 rng(49);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int body = 0; body < 40; ++body) {
    const int count = 4 + static_cast<int>(296 * (0.5 + 0.5 * u(rng)));
    std::vector<Vec3> points;
    for (int k = 0; k < count; ++k) points.emplace_back(u(rng), 0.6 * u(rng), 0.4 * u(rng));
    MeshOptions options;
    options.inertia = InertiaModel::convex;
    const Particle p = make_particle(TriangleMesh{points, {}}, "random convex", 1.0, options);
    const auto& verts = p.hull.vertices;
    NearWall near(p.hull);
    Quat q(Eigen::AngleAxisd(3 * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    for (int query = 0; query < 50; ++query) {
      q = (Quat(Eigen::AngleAxisd(0.2 * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized())) * q).normalized();
      const double com_z = 0.5 + 0.5 * u(rng), level = 0.3 * (1 + u(rng));
      const auto height = [&](std::size_t k) { return com_z + (q * verts[k]).z(); };
      std::vector<int> scan;
      int lowest = 0;
      for (std::size_t k = 0; k < verts.size(); ++k) {
        if (height(k) <= level) scan.push_back(static_cast<int>(k));
        if (height(k) < height(static_cast<std::size_t>(lowest))) lowest = static_cast<int>(k);
      }
      const std::vector<int> walked = near.vertices_below(
          q, com_z, level, 1e-12, [&](int k) { return height(static_cast<std::size_t>(k)) <= level; });
      EXPECT_EQ(walked, scan) << "body " << body << ", query " << query;
      const std::vector<int>& candidates = near.near_lowest(q, 1e-12);
      EXPECT_TRUE(std::is_sorted(candidates.begin(), candidates.end()));
      EXPECT_NE(std::find(candidates.begin(), candidates.end(), lowest), candidates.end())
          << "body " << body << ", query " << query;
    }
  }
}

}  // namespace
}  // namespace repose::sim
