// Design points (design_point.hpp).
#include "design_point.hpp"

#include <algorithm>
#include <cmath>

#include "attraction.hpp"
#include "basin_tape.hpp"
#include "face_planes.hpp"
#include "repose/error.hpp"
#include "solid_centroid.hpp"

namespace repose::detail {

namespace {
constexpr int kComProjectionRounds = 32;  // rounds pushing the centre of mass inside the shrunk hull
// × L: a flat face's points off its plane by no more than round-off, so that the hull merges it whole.
constexpr double kFlatness = 1e-14;
}  // namespace

// The centre of mass pushed at most kComProjectionRounds times along the most violated face normal until it
// is `margin` inside every face of `hull`; false if it is not.
bool push_inside(const ConvexHull& hull, double margin, Vec3& com) {
  for (int round = 0; round < kComProjectionRounds; ++round) {
    double worst = 0;
    const HullFace* face = nullptr;
    for (const HullFace& f : hull.faces) {
      const double excess = f.normal.dot(com) - f.offset + margin;
      if (excess > worst) worst = excess, face = &f;
    }
    if (face == nullptr) return true;
    com -= (worst * (1 + 1e-9)) * face->normal;
  }
  return false;
}

double shortest_edge(const ConvexHull& hull) {
  double out = INFINITY;
  for (std::size_t v = 0; v < hull.vertices.size(); ++v)
    for (const int w : hull.neighbors(static_cast<int>(v)))
      out = std::min(out, (hull.vertices[v] - hull.vertices[static_cast<std::size_t>(w)]).norm());
  return out;
}

double smallest_face(const ConvexHull& hull) {
  double out = INFINITY;
  for (const HullFace& f : hull.faces) out = std::min(out, f.area);
  return out;
}

Point evaluate(std::vector<Vec3> points, std::vector<Vec3> planes, const Vec3& com, const std::string& name,
               const DesignTarget& target, const DesignOptions& options, const ConvexHull* hull,
               const std::vector<double>* margin_floor) {
  Point p;
  p.points = std::move(points);
  p.planes = std::move(planes);
  p.com = com;
  MeshOptions mesh;
  mesh.inertia = InertiaModel::convex;
  mesh.center_of_mass = com;
  // The particle is made from the hull's vertices (in the points' order), so its hull's source indices count
  // those; through the points' hull they become design points.
  const ConvexHull own = hull != nullptr ? ConvexHull{} : compute_convex_hull(p.points);
  const ConvexHull& outer = hull != nullptr ? *hull : own;
  p.particle = make_particle(TriangleMesh{outer.vertices, {}}, name, 1.0, mesh);
  for (const int v : p.particle.hull.source_index)
    p.design_index.push_back(outer.source_index[static_cast<std::size_t>(v)]);
  p.centroid = detail::solid_centroid<double>(p.particle.hull.vertices, p.particle.hull) + com;
  p.landscape = compute_rest_landscape(p.particle);
  p.target = target;
  if (margin_floor != nullptr)
    p.margin_floor = *margin_floor;
  else
    p.margin_floor.assign(target.outcomes.size(), options.min_margin);
  assign_outcome_faces(p.target, p.particle.hull, options.outcome_angle, "--outcome-angle");
  score(p);
  return p;
}

void score(Point& p) {
  p.achieved = outcome_probabilities(p.target, p.landscape.basin_probability);
  std::vector<int> count(p.target.outcomes.size() + 1, 0);
  for (std::size_t f = 0; f < p.landscape.face_rest.size(); ++f) {
    if (p.landscape.face_rest[f] != static_cast<int>(f)) continue;
    std::size_t o = p.target.outcomes.size();
    for (std::size_t k = 0; k < p.target.outcomes.size(); ++k) {
      const auto& faces = p.target.outcomes[k].faces;
      if (std::binary_search(faces.begin(), faces.end(), static_cast<int>(f))) o = k;
    }
    ++count[o];
  }
  p.stable.clear();
  for (std::size_t o = 0; o < count.size(); ++o) p.stable.insert({static_cast<int>(o), count[o]});
  p.objective = p.max_error = 0;
  for (std::size_t o = 0; o < p.achieved.size(); ++o) {
    const double t = o < p.target.outcomes.size() ? p.target.outcomes[o].probability : 0.0;
    const double r = p.achieved[o] - t;
    p.objective += r * r;
    p.max_error = std::max(p.max_error, std::abs(r));
  }
  p.attraction = attraction(p.particle, p.landscape, p.target, p.margin_floor);
  for (const double a : p.attraction) p.objective += a * a;
}

std::vector<double> outcome_margins(const Point& p) {
  std::vector<double> out;
  for (const DesignOutcome& o : p.target.outcomes) {
    double best = -INFINITY;
    for (const int f : o.faces)
      best = std::max(best, p.particle.face_stability_margin[static_cast<std::size_t>(f)]);
    out.push_back(best / p.particle.length);
  }
  return out;
}

// The outcomes' (then the unassigned faces') probabilities' Jacobian over the design variables: 3 per shape
// variable (a design vertex, zero for one not on the hull; or a plane), then the centre of mass's 3 (the
// offset from the centroid, or the position).
Eigen::MatrixXd jacobian(const Point& p, MassModel mass, ShapeFreedom shape) {
  detail::BasinTape tape(p.particle, p.landscape, mass);
  const std::size_t outcomes = p.target.outcomes.size();
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(outcomes + 1),
                                                  static_cast<Eigen::Index>(p.particle.hull.faces.size()));
  for (std::size_t o = 0; o < outcomes; ++o)
    for (const int f : p.target.outcomes[o].faces) weights(static_cast<Eigen::Index>(o), f) = 1;
  for (const int f : p.target.unassigned_faces) weights(static_cast<Eigen::Index>(outcomes), f) = 1;
  return design_columns(p, tape.gradients(weights), shape);
}

Eigen::MatrixXd design_columns(const Point& p, const Eigen::MatrixXd& rows, ShapeFreedom shape) {
  const Eigen::Index hull_columns = rows.cols() - 3;
  Eigen::MatrixXd shape_columns;
  if (shape == ShapeFreedom::faces) {
    shape_columns = detail::plane_columns(rows.leftCols(hull_columns), p.particle.hull, -p.com, p.planes);
  } else {
    shape_columns = Eigen::MatrixXd::Zero(rows.rows(), 3 * static_cast<Eigen::Index>(p.points.size()));
    for (std::size_t j = 0; j < p.design_index.size(); ++j)
      shape_columns.middleCols<3>(3 * static_cast<Eigen::Index>(p.design_index[j])) =
          rows.middleCols<3>(3 * static_cast<Eigen::Index>(j));
    if (shape == ShapeFreedom::none) shape_columns.setZero();
  }
  Eigen::MatrixXd out(rows.rows(), shape_columns.cols() + 3);
  out << shape_columns, rows.rightCols<3>();
  return out;
}

// The trial point `d` (unscaled: shape variables, then the centre of mass) away from `at`, the shape within
// its move bound and the centre of mass pushed inside the shrunk hull; nothing (counted in `step`) if a
// bound cannot hold or the shape degenerates.
std::optional<Point> trial_point(const Point& at, const Eigen::VectorXd& d, MassModel mass,
                                 ShapeFreedom shape, const Bounds& bounds, const std::string& name,
                                 const DesignTarget& target, const DesignOptions& options, DesignStep& step,
                                 double& moved) {
  std::vector<Vec3> points = at.points, planes = at.planes;
  moved = 0;
  // Clamps x to within max_move of `from`.
  auto within = [&](Vec3 x, const Vec3& from) {
    if ((x - from).norm() > bounds.max_move) x = from + (x - from) * (bounds.max_move / (x - from).norm());
    return x;
  };
  if (shape == ShapeFreedom::vertices) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      points[i] = within(points[i] + d.segment<3>(3 * static_cast<Eigen::Index>(i)), bounds.origin[i]);
    }
    // The step kept the flat faces flat to first order; put their points back on their planes.
    if (!flatten(points, bounds.flat, kFlatness * at.particle.length)) {
      ++step.degenerate;
      return std::nullopt;
    }
    for (std::size_t i = 0; i < points.size(); ++i)
      moved = std::max(moved, (points[i] - at.points[i]).norm());
  } else if (shape == ShapeFreedom::faces) {
    for (std::size_t i = 0; i < planes.size(); ++i) {
      const Vec3 p = planes[i] + d.segment<3>(3 * static_cast<Eigen::Index>(i));
      const Vec3 f = within(foot(p), bounds.origin[i]);
      planes[i] = f / f.squaredNorm();
      moved = std::max(moved, (f - foot(at.planes[i])).norm());
    }
    std::optional<std::vector<Vec3>> corners = detail::plane_vertices(planes);
    if (!corners) {
      ++step.degenerate;
      return std::nullopt;
    }
    points = std::move(*corners);
  }
  try {
    const ConvexHull hull = compute_convex_hull(points);
    if (shortest_edge(hull) < bounds.min_edge * (1 - 1e-9) ||
        smallest_face(hull) < bounds.min_area * (1 - 1e-9)) {
      ++step.unprintable;
      return std::nullopt;
    }
    // The centre of mass carries its offset from the centroid along (follows_shape) or stays (fixed).
    Vec3 com = mass == MassModel::follows_shape
                   ? Vec3(detail::solid_centroid<double>(hull.vertices, hull) + (at.com - at.centroid))
                   : at.com;
    com += d.tail<3>();
    if (!push_inside(hull, bounds.com_margin, com)) {
      ++step.com_outside;
      return std::nullopt;
    }
    moved = std::max(moved, (com - at.com).norm());
    return evaluate(std::move(points), std::move(planes), com, name, target, options, &hull,
                    &at.margin_floor);
  } catch (const Error&) {
    ++step.degenerate;  // the points' hull degenerated, or its faces no longer close
    return std::nullopt;
  }
}

}  // namespace repose::detail
