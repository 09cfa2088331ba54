// Attraction of outcomes whose faces are all unstable (attraction.hpp).
#include "attraction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "../model/surface_facts.hpp"
#include "design_point.hpp"
#include "solid_centroid.hpp"

namespace repose::detail {

namespace {

// The stability margin of `face` with the hull's vertices at `x` and the centre of mass at `com` (body
// frame): the face's normal by Newell's formula from its loop, then the model's polygon margin (the
// vertices free to move).
double margin(const std::vector<Vec3>& x, const HullFace& face, const Vec3& com) {
  Vec3 normal = Vec3::Zero();
  const std::size_t n = face.loop.size();
  for (std::size_t i = 0; i < n; ++i)
    normal +=
        x[static_cast<std::size_t>(face.loop[i])].cross(x[static_cast<std::size_t>(face.loop[(i + 1) % n])]);
  normal.normalize();
  return polygon_margin(x, face.loop, normal, com);
}

// The outcome's face with the best (largest) margin, and that margin less the floor (× L: min_margin);
// face −1 if the attraction is 0.
std::pair<int, double> critical_face(const Particle& particle, const RestLandscape& landscape,
                                     const DesignOutcome& outcome, double min_margin) {
  if (!(outcome.probability > 0)) return {-1, 0};
  const double floor = min_margin * particle.length;
  int best = -1;
  double best_margin = -INFINITY;
  for (const int f : outcome.faces) {
    // With no floor any stable face will do (its margin is positive: the landscape's own test).
    if (floor == 0 && landscape.face_rest[static_cast<std::size_t>(f)] == f) return {-1, 0};
    const double m = particle.face_stability_margin[static_cast<std::size_t>(f)];
    if (m > best_margin) best_margin = m, best = f;
  }
  if (best_margin >= floor) return {-1, 0};
  return {best, best_margin - floor};
}

}  // namespace

std::vector<double> attraction(const Particle& particle, const RestLandscape& landscape,
                               const DesignTarget& target, const std::vector<double>& margin_floor) {
  std::vector<double> out;
  for (std::size_t k = 0; k < target.outcomes.size(); ++k) {
    const DesignOutcome& o = target.outcomes[k];
    const auto [face, m] = critical_face(particle, landscape, o, margin_floor[k]);
    out.push_back(face < 0 ? 0.0 : o.probability * -m / (kAttractionLength * particle.length));
  }
  return out;
}

Eigen::MatrixXd attraction_rows(const Point& p, MassModel mass, ShapeFreedom shape) {
  const ConvexHull& hull = p.particle.hull;
  const std::size_t outcomes = p.target.outcomes.size();
  const auto vertices = static_cast<Eigen::Index>(hull.vertices.size());
  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(outcomes), 3 * vertices + 3);
  const double h = 1e-7 * p.particle.length;
  const Vec3 centroid = solid_centroid<double>(hull.vertices, hull);
  for (std::size_t o = 0; o < outcomes; ++o) {
    const DesignOutcome& outcome = p.target.outcomes[o];
    const int f = critical_face(p.particle, p.landscape, outcome, p.margin_floor[o]).first;
    if (f < 0) continue;
    const HullFace& face = hull.faces[static_cast<std::size_t>(f)];
    const double scale = -outcome.probability / kAttractionLength;  // a = scale · m / L
    const auto r = static_cast<Eigen::Index>(o);
    // The centre of mass (body frame: at the origin).
    for (int k = 0; k < 3; ++k) {
      Vec3 e = Vec3::Zero();
      e[k] = h;
      rows(r, 3 * vertices + k) = scale * (margin(hull.vertices, face, e) - margin(hull.vertices, face, -e)) /
                                  (2 * h * p.particle.length);
    }
    if (shape == ShapeFreedom::none) continue;
    // Every vertex: the face's own move its margin, every one the volume (L, the residual's unit) and, with
    // the centre of mass following the shape, the solid's centroid.
    std::vector<Vec3> x = hull.vertices;
    for (Eigen::Index j = 0; j < vertices; ++j)
      for (int k = 0; k < 3; ++k) {
        double side[2];
        for (int s = 0; s < 2; ++s) {
          x[static_cast<std::size_t>(j)][k] += s == 0 ? h : -h;
          const Vec3 com = mass == MassModel::follows_shape ? Vec3(solid_centroid<double>(x, hull) - centroid)
                                                            : Vec3::Zero();
          const double length = std::cbrt(6 * solid_volume<double>(x, hull) / std::numbers::pi);
          side[s] = margin(x, face, com) / length;
          x[static_cast<std::size_t>(j)] = hull.vertices[static_cast<std::size_t>(j)];
        }
        rows(r, 3 * j + k) = scale * (side[0] - side[1]) / (2 * h);
      }
  }
  return design_columns(p, rows, shape);
}

}  // namespace repose::detail
