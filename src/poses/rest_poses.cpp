#include "repose/poses/rest_poses.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "repose/error.hpp"

namespace repose {

namespace {

// Union-find over stable faces whose root is always the deepest minimum of its set (the "elder rule" of
// persistent homology: when two sublevel-set components meet, the younger one dies).
struct ElderUnionFind {
  std::vector<int> parent;
  explicit ElderUnionFind(int n) : parent(static_cast<std::size_t>(n)) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int root(int f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  }
};

}  // namespace

double default_persistence(const Particle& particle, bool smooth) {
  return smooth ? 0.01 * particle.length : 0.0;
}

RestPoseCatalog catalog_rest_poses(const Particle& particle, const RestLandscape& landscape,
                                   double persistence) {
  if (!(persistence >= 0) || !std::isfinite(persistence))
    throw Error("persistence must be a finite length >= 0, got " + std::to_string(persistence));
  const ConvexHull& hull = particle.hull;
  const int face_count = static_cast<int>(hull.faces.size());
  const auto height = [&](int f) { return hull.faces[f].offset; };
  // Deeper first; ties by index so the order is total and the result deterministic.
  const auto deeper = [&](int a, int b) {
    return height(a) < height(b) || (height(a) == height(b) && a < b);
  };

  // Filtration: saddles in ascending height join the sublevel-set components of their two minima. A minimum
  // that dies with persistence below the threshold follows the elder it merged into.
  std::vector<int> saddle_order(landscape.saddles.size());
  std::iota(saddle_order.begin(), saddle_order.end(), 0);
  std::sort(saddle_order.begin(), saddle_order.end(), [&](int a, int b) {
    const double ha = landscape.saddles[a].height, hb = landscape.saddles[b].height;
    return ha < hb || (ha == hb && a < b);
  });
  ElderUnionFind components(face_count);
  std::vector<int> merged_into(static_cast<std::size_t>(face_count));
  std::iota(merged_into.begin(), merged_into.end(), 0);
  for (int s : saddle_order) {
    const Saddle& saddle = landscape.saddles[s];
    int a = components.root(saddle.rest_a), b = components.root(saddle.rest_b);
    if (a == b) continue;
    if (deeper(b, a)) std::swap(a, b);  // a is the elder, b dies here
    components.parent[b] = a;
    if (saddle.height - height(b) < persistence) merged_into[b] = a;
  }
  // Resolve chains (b merged into a, which later merged into c); each step goes to a strictly deeper face.
  std::vector<int> cluster(static_cast<std::size_t>(face_count), -1);
  for (int f = 0; f < face_count; ++f) {
    if (landscape.face_rest[f] != f) continue;  // unstable face
    int c = f;
    for (int guard = 0; merged_into[c] != c; ++guard) {
      if (guard > face_count)
        throw Error(particle.name + ": rest-pose merge did not terminate (internal error)");
      c = merged_into[c];
    }
    cluster[f] = c;
  }

  // One pose per cluster root, ordered by height then face.
  std::vector<int> roots;
  for (int f = 0; f < face_count; ++f)
    if (cluster[f] == f) roots.push_back(f);
  std::sort(roots.begin(), roots.end(), deeper);
  RestPoseCatalog catalog;
  catalog.persistence = persistence;
  std::vector<int> root_pose(static_cast<std::size_t>(face_count), -1);
  for (int root : roots) {
    root_pose[root] = static_cast<int>(catalog.poses.size());
    RestPose pose;
    pose.face = root;
    pose.down_normal_body = hull.faces[root].normal;
    pose.com_height = height(root);
    pose.barrier = std::numeric_limits<double>::infinity();
    catalog.poses.push_back(pose);
  }
  catalog.face_pose.assign(static_cast<std::size_t>(face_count), -1);
  for (int f = 0; f < face_count; ++f) {
    const int rest = landscape.face_rest[f];
    const int pose = root_pose[cluster[rest]];
    catalog.face_pose[f] = pose;
    if (rest == f) {
      catalog.poses[pose].faces.push_back(f);
      catalog.poses[pose].quasi_static_probability += landscape.basin_probability[f];
    }
  }
  for (const Saddle& saddle : landscape.saddles) {
    const int pa = catalog.face_pose[saddle.rest_a], pb = catalog.face_pose[saddle.rest_b];
    if (pa == pb) continue;
    for (int p : {pa, pb}) catalog.poses[p].barrier = std::min(catalog.poses[p].barrier, saddle.height);
  }
  return catalog;
}

}  // namespace repose
