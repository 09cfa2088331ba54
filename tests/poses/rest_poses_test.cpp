// The rest-pose catalogue: stable faces, persistence merging, barriers, exact quasi-static probabilities.
#include "repose/poses/rest_poses.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "../support/equilibrium_oracle.hpp"
#include "repose/error.hpp"
#include "repose/poses/landscape.hpp"
#include "repose/sim/settle.hpp"

namespace {

using namespace repose;

RestPoseCatalog catalog_of(const Particle& p, double persistence_fraction) {
  return catalog_rest_poses(p, compute_rest_landscape(p), persistence_fraction * p.length);
}

// Cube: six faces, each a pose at height a/2, left over an edge at height a/√2 (COM to edge line), 1/6 each
// by symmetry (1e-12: round-off of a sum of spherical areas).
TEST(RestPoses, CubeHasSixPosesWithTheEdgeBarrier) {
  const Particle cube = load_particle("box:x=2,y=2,z=2", 1.0);
  const RestPoseCatalog c = catalog_of(cube, 0);
  ASSERT_EQ(c.poses.size(), 6u);
  for (const RestPose& pose : c.poses) {
    EXPECT_NEAR(pose.com_height, 1.0, 1e-12);
    EXPECT_NEAR(pose.barrier, std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(pose.quasi_static_probability, 1.0 / 6, 1e-12);
    EXPECT_EQ(pose.faces.size(), 1u);
    EXPECT_NEAR(pose.down_normal_body.cwiseAbs().maxCoeff(), 1.0, 1e-12);
  }
  for (int f = 0; f < 6; ++f) EXPECT_EQ(c.poses[c.face_pose[f]].face, f);
}

// Poses come ordered by rest height: box 1×2×3 rests lowest on its 2×3 faces (height 0.5).
TEST(RestPoses, OrderedByHeight) {
  const RestPoseCatalog c = catalog_of(load_particle("box:x=1,y=2,z=3", 1.0), 0);
  ASSERT_EQ(c.poses.size(), 6u);
  for (std::size_t p = 1; p < c.poses.size(); ++p)
    EXPECT_LE(c.poses[p - 1].com_height, c.poses[p].com_height);
  EXPECT_NEAR(c.poses[0].com_height, 0.5, 1e-12);
  EXPECT_NEAR(c.poses[5].com_height, 1.5, 1e-12);
}

// A triaxial ellipsoid's COM height has exactly two minima, the ends of its shortest axis; its mesh has many
// nearly flat stable facets around each. With 1 % of L persistence they merge into the two true poses, each
// with probability 1/2 (mirror symmetry of the mesh; round-off, measured 2.8e-15). Each rests on the lowest
// facet of its side, found here from the triangles' planes: height and normal to 1e-12 (round-off, measured
// 1.1e-16). Against the smooth ellipsoid: the inscribed polyhedron is lower everywhere, so the rest is below
// c (measured by 0.073 %) and the barrier, the saddle at the middle axis, below b (by 0.12 %); 0.5 % bands.
TEST(RestPoses, SmoothEllipsoidMergesIntoItsTwoTruePoses) {
  const Particle e = load_particle("ellipsoid:a=0.625,b=0.5,c=0.285,n=10", 1.0);
  const RestPoseCatalog raw = catalog_of(e, 0);
  const RestPoseCatalog merged = catalog_of(e, 0.01);
  EXPECT_GT(raw.poses.size(), 2u) << "the mesh should have spurious facet minima for this test to mean much";
  ASSERT_EQ(merged.poses.size(), 2u);
  for (const RestPose& pose : merged.poses) {
    EXPECT_NEAR(pose.quasi_static_probability, 0.5, 1e-12);
    // The lowest triangle plane on the pose's side (z of the normal), from the mesh alone.
    const bool up = pose.down_normal_body.z() > 0;
    double lowest = INFINITY;
    std::vector<std::pair<double, Vec3>> planes;
    for (const Triangle& t : e.mesh.triangles) {
      const Vec3 a = e.mesh.vertices[t[0]], b = e.mesh.vertices[t[1]], c = e.mesh.vertices[t[2]];
      const Vec3 n = (b - a).cross(c - a).normalized();
      if ((n.z() > 0) != up) continue;
      planes.emplace_back(n.dot(a - e.mass.center_of_mass), n);
      lowest = std::min(lowest, planes.back().first);
    }
    EXPECT_NEAR(pose.com_height, lowest, 1e-12);
    bool normal_found = false;  // ties (mirror-image facets at the same height) may give either
    for (const auto& [h, n] : planes)
      normal_found |= h < lowest + 1e-12 && (n - pose.down_normal_body).norm() < 1e-12;
    EXPECT_TRUE(normal_found) << pose.down_normal_body.transpose();
    EXPECT_LT(pose.com_height, 0.285);
    EXPECT_NEAR(pose.com_height, 0.285, 0.005 * 0.285);
    EXPECT_LT(pose.barrier, 0.5);
    EXPECT_NEAR(pose.barrier, 0.5, 0.005 * 0.5);
  }
  double total = 0;
  for (const RestPose& pose : raw.poses) total += pose.quasi_static_probability;
  EXPECT_NEAR(total, 1.0, 1e-12);
}

TEST(RestPoses, EveryFaceMapsToAPoseAndUnstableFacesRollOn) {
  const Particle p = load_particle("irregular:seed=5", 1.0);
  const RestLandscape l = compute_rest_landscape(p);
  const RestPoseCatalog c = catalog_rest_poses(p, l, 0);
  for (std::size_t f = 0; f < p.hull.faces.size(); ++f) {
    ASSERT_GE(c.face_pose[f], 0);
    std::vector<Vec3> corners;
    for (int k : p.hull.faces[f].loop) corners.push_back(p.hull.vertices[k]);
    if (oracle::face_margin(corners, p.hull.faces[f].normal) > 0)  // stable, by the test's own check
      EXPECT_EQ(c.poses[c.face_pose[f]].face, static_cast<int>(f));
    else
      EXPECT_EQ(c.face_pose[f], c.face_pose[l.face_rest[f]]);
  }
  for (const RestPose& pose : c.poses) EXPECT_GE(pose.barrier, pose.com_height);
}

// A particle with a single pose (all others merged away) has no barrier.
TEST(RestPoses, HugePersistenceLeavesOnePoseWithoutBarrier) {
  const Particle p = load_particle("irregular:seed=2", 1.0);
  const RestPoseCatalog c = catalog_of(p, 10.0);
  ASSERT_EQ(c.poses.size(), 1u);
  EXPECT_EQ(c.poses[0].barrier, std::numeric_limits<double>::infinity());
  EXPECT_NEAR(c.poses[0].quasi_static_probability, 1.0, 1e-12);
}

TEST(RestPoses, RejectsNegativePersistence) {
  const Particle p = load_particle("box:x=1,y=1,z=1", 1.0);
  EXPECT_THROW(catalog_rest_poses(p, compute_rest_landscape(p), -1), Error);
  EXPECT_THROW(catalog_rest_poses(p, compute_rest_landscape(p), std::nan("")), Error);
}

}  // namespace
