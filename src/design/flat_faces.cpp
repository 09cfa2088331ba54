// Flat faces (flat_faces.hpp).
#include "flat_faces.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <set>

namespace repose::detail {

namespace {
constexpr int kFlattenRounds = 20;  // Gauss–Newton rounds putting the points back on their faces' planes

// Each constraint: the face, the spanning three (a, b, c) and the point j.
struct Constraint {
  int a, b, c, j;
};

std::vector<Constraint> constraints(const std::vector<FlatFace>& faces) {
  std::vector<Constraint> out;
  for (const FlatFace& f : faces)
    for (std::size_t k = 3; k < f.size(); ++k) out.push_back({f[0], f[1], f[2], f[k]});
  return out;
}

// The signed distance of j from the plane of (a, b, c) and its gradient with respect to the four points
// (the plane's normalisation held: exact where the distance is 0, which is where the rows are used).
double distance(const std::vector<Vec3>& x, const Constraint& k, Vec3 grad[4]) {
  const Vec3 a = x[static_cast<std::size_t>(k.a)];
  const Vec3 u = x[static_cast<std::size_t>(k.b)] - a, w = x[static_cast<std::size_t>(k.c)] - a,
             z = x[static_cast<std::size_t>(k.j)] - a;
  const Vec3 n = u.cross(w);
  const double scale = 1 / n.norm();
  grad[1] = w.cross(z) * scale;  // b
  grad[2] = z.cross(u) * scale;  // c
  grad[3] = n * scale;           // j
  grad[0] = -(grad[1] + grad[2] + grad[3]);
  return n.dot(z) * scale;
}
}  // namespace

std::vector<FlatFace> flat_faces(const ConvexHull& hull) {
  std::vector<FlatFace> out;
  for (const HullFace& f : hull.faces) {
    if (f.loop.size() < 4) continue;
    const auto at = [&](int v) { return hull.vertices[static_cast<std::size_t>(v)]; };
    // The widest triangle's corners span the plane best: the first vertex, the one farthest from it, the one
    // farthest from their line.
    const int a = f.loop[0];
    const int b = *std::max_element(f.loop.begin(), f.loop.end(), [&](int p, int q) {
      return (at(p) - at(a)).norm() < (at(q) - at(a)).norm();
    });
    const auto spread = [&](int p) { return (at(b) - at(a)).cross(at(p) - at(a)).norm(); };
    const int c =
        *std::max_element(f.loop.begin(), f.loop.end(), [&](int p, int q) { return spread(p) < spread(q); });
    FlatFace face{a, b, c};
    for (const int v : f.loop)
      if (v != a && v != b && v != c) face.push_back(v);
    out.push_back(std::move(face));
  }
  return out;
}

std::vector<FlatFace> standing_faces(const std::vector<FlatFace>& faces, const ConvexHull& hull,
                                     const std::vector<int>& design_index) {
  std::set<std::vector<int>> present;
  for (const HullFace& f : hull.faces) {
    std::vector<int> points;
    for (const int v : f.loop) points.push_back(design_index[static_cast<std::size_t>(v)]);
    std::sort(points.begin(), points.end());
    present.insert(std::move(points));
  }
  std::vector<FlatFace> out;
  for (const FlatFace& f : faces) {
    std::vector<int> points = f;
    std::sort(points.begin(), points.end());
    if (present.count(points) != 0) out.push_back(f);
  }
  return out;
}

Eigen::MatrixXd flatness_rows(const std::vector<FlatFace>& faces, const std::vector<Vec3>& points,
                              Eigen::Index columns) {
  const std::vector<Constraint> all = constraints(faces);
  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(all.size()), columns);
  for (std::size_t r = 0; r < all.size(); ++r) {
    Vec3 grad[4];
    distance(points, all[r], grad);
    const int at[4] = {all[r].a, all[r].b, all[r].c, all[r].j};
    for (int k = 0; k < 4; ++k)
      rows.block<1, 3>(static_cast<Eigen::Index>(r), 3 * static_cast<Eigen::Index>(at[k])) +=
          grad[k].transpose();
  }
  return rows;
}

bool flatten(std::vector<Vec3>& points, const std::vector<FlatFace>& faces, double tolerance) {
  const std::vector<Constraint> all = constraints(faces);
  if (all.empty()) return true;
  const auto columns = 3 * static_cast<Eigen::Index>(points.size());
  for (int round = 0; round <= kFlattenRounds; ++round) {
    Eigen::VectorXd off(static_cast<Eigen::Index>(all.size()));
    Vec3 grad[4];
    for (std::size_t r = 0; r < all.size(); ++r)
      off[static_cast<Eigen::Index>(r)] = distance(points, all[r], grad);
    if (off.cwiseAbs().maxCoeff() <= tolerance) return true;
    if (round == kFlattenRounds) break;
    // The least move that zeroes the linearised distances (dependent constraints, e.g. two faces sharing
    // three points' worth of a plane, drop out of the rank).
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> solve;
    solve.setThreshold(1e-10);  // before compute: Eigen applies it while decomposing
    solve.compute(flatness_rows(faces, points, columns));
    const Eigen::VectorXd move = solve.solve(-off);
    for (std::size_t i = 0; i < points.size(); ++i)
      points[i] += move.segment<3>(3 * static_cast<Eigen::Index>(i));
  }
  return false;
}

}  // namespace repose::detail
