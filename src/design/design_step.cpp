// Design steps (design_step.hpp).
#include "design_step.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "face_planes.hpp"
#include "flat_faces.hpp"

namespace repose::detail {

namespace {
constexpr int kActivePasses = 6;      // re-solves of a step as vertices, edges and faces reach their bounds
constexpr double kFlatRidge = 1e-10;  // × λ: the flat faces' rows' ridge (an infinite weight, kept solvable)
constexpr double kPrintableMargin = 1e-3;  // a held edge or face is kept this much (relative) above its bound

// Rows (over the scaled variables) and targets that keep each hull edge and face that the step `d` would take
// below its printability bound at kPrintableMargin above it instead, to first order (vertices): the edge's
// change u·(d_a − d_b) and the face's ½ n̂ × (v_prev − v_next) · d_i, summed over its loop.
struct Held {
  std::set<std::pair<int, int>> edges;  // hull vertex pairs
  std::set<int> faces;
};
void hold_printable(const Point& at, const Bounds& bounds, double length, const Eigen::VectorXd& d,
                    Held& held, Eigen::MatrixXd& rows, Eigen::VectorXd& targets) {
  const ConvexHull& hull = at.particle.hull;
  const auto point = [&](int v) {
    return 3 * static_cast<Eigen::Index>(at.design_index[static_cast<std::size_t>(v)]);
  };
  std::vector<std::pair<Eigen::RowVectorXd, double>> add;
  for (std::size_t v = 0; v < hull.vertices.size(); ++v)
    for (const int w : hull.neighbors(static_cast<int>(v))) {
      if (w < static_cast<int>(v) || held.edges.count({static_cast<int>(v), w}) != 0) continue;
      const Vec3 edge = hull.vertices[v] - hull.vertices[static_cast<std::size_t>(w)];
      const Vec3 u = edge.normalized();
      const Eigen::Index a = point(static_cast<int>(v)), b = point(w);
      const double change = u.dot(Vec3(d.segment<3>(a) - d.segment<3>(b))) * length;
      const double floor = bounds.min_edge * (1 + kPrintableMargin);
      if (edge.norm() + change >= floor) continue;
      Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(d.size());
      row.segment<3>(a) = u.transpose();
      row.segment<3>(b) = -u.transpose();
      add.emplace_back(row, (floor - edge.norm()) / length);
      held.edges.insert({static_cast<int>(v), w});
    }
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    if (held.faces.count(static_cast<int>(f)) != 0) continue;
    const HullFace& face = hull.faces[f];
    // ∂A/∂x_i per corner, and the first-order change ∂A/∂x · Δx (Δx = d·L), over the face's corners only.
    const std::size_t k = face.loop.size();
    const auto gradient = [&](std::size_t i) {
      const Vec3& prev = hull.vertices[static_cast<std::size_t>(face.loop[(i + k - 1) % k])];
      const Vec3& next = hull.vertices[static_cast<std::size_t>(face.loop[(i + 1) % k])];
      return Vec3(0.5 * face.normal.cross(prev - next));
    };
    double change = 0;
    for (std::size_t i = 0; i < k; ++i) change += gradient(i).dot(Vec3(d.segment<3>(point(face.loop[i]))));
    change *= length;
    const double floor = bounds.min_area * (1 + kPrintableMargin);
    if (face.area + change >= floor) continue;
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(d.size());
    for (std::size_t i = 0; i < k; ++i) row.segment<3>(point(face.loop[i])) += gradient(i).transpose();
    // Dimensionless: ∂A/∂s · d = (floor − A), s = x/L, divided by L².
    add.emplace_back(row / length, (floor - face.area) / (length * length));
    held.faces.insert(static_cast<int>(f));
  }
  if (add.empty()) return;
  const Eigen::Index old = rows.rows();
  rows.conservativeResize(old + static_cast<Eigen::Index>(add.size()), d.size());
  targets.conservativeResize(old + static_cast<Eigen::Index>(add.size()));
  for (std::size_t r = 0; r < add.size(); ++r) {
    rows.row(old + static_cast<Eigen::Index>(r)) = add[r].first;
    targets[old + static_cast<Eigen::Index>(r)] = add[r].second;
  }
}
}  // namespace

// The shape's metric M = I + αΛ over its variables (per coordinate), Λ the graph Laplacian of the hull's
// vertices (vertices) or of its faces' adjacency (faces): steps are measured in a Sobolev norm, so that a
// fine hull moves as a smooth deformation over about `smoothing` (× L) instead of vertex by vertex (which
// folds its tiny faces and changes the basins' structure at every step). α = (smoothing·L / mean spacing)².
using Metric = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;
std::unique_ptr<Metric> shape_metric(const Point& at, ShapeFreedom shape, double smoothing, double length) {
  if (shape == ShapeFreedom::none || !(smoothing > 0)) return nullptr;
  const ConvexHull& hull = at.particle.hull;
  std::vector<std::pair<int, int>> links;  // in design-variable indices
  double spacing = 0;
  if (shape == ShapeFreedom::vertices) {
    for (std::size_t v = 0; v < hull.vertices.size(); ++v)
      for (const int w : hull.neighbors(static_cast<int>(v)))
        if (static_cast<int>(v) < w) {
          links.emplace_back(at.design_index[v], at.design_index[static_cast<std::size_t>(w)]);
          spacing += (hull.vertices[v] - hull.vertices[static_cast<std::size_t>(w)]).norm();
        }
  } else {
    const std::vector<int> plane_of = detail::plane_indices(hull, at.planes);
    std::map<std::pair<int, int>, int> edge_face;  // directed loop edge → face
    for (std::size_t f = 0; f < hull.faces.size(); ++f) {
      const auto& loop = hull.faces[f].loop;
      for (std::size_t k = 0; k < loop.size(); ++k)
        edge_face[{loop[k], loop[(k + 1) % loop.size()]}] = static_cast<int>(f);
    }
    for (const auto& [edge, f] : edge_face) {
      const auto other = edge_face.find({edge.second, edge.first});
      if (other == edge_face.end() || f > other->second) continue;
      const int a = plane_of[static_cast<std::size_t>(f)],
                b = plane_of[static_cast<std::size_t>(other->second)];
      if (a < 0 || b < 0 || a == b) continue;
      links.emplace_back(a, b);
      spacing += (hull.faces[static_cast<std::size_t>(f)].centroid -
                  hull.faces[static_cast<std::size_t>(other->second)].centroid)
                     .norm();
    }
  }
  if (links.empty()) return nullptr;
  spacing /= static_cast<double>(links.size());
  const double alpha = std::pow(smoothing * length / spacing, 2);
  const auto n =
      static_cast<Eigen::Index>(shape == ShapeFreedom::vertices ? at.points.size() : at.planes.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index i = 0; i < n; ++i) entries.emplace_back(i, i, 1.0);
  for (const auto& [a, b] : links) {
    entries.emplace_back(a, a, alpha);
    entries.emplace_back(b, b, alpha);
    entries.emplace_back(a, b, -alpha);
    entries.emplace_back(b, a, -alpha);
  }
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(entries.begin(), entries.end());
  auto out = std::make_unique<Metric>(m);
  if (out->info() != Eigen::Success) return nullptr;
  return out;
}

// M⁻¹ applied to the shape rows of `t` (variables × columns; the centre of mass's last 3 rows untouched).
Eigen::MatrixXd apply_inverse(const Metric* metric, Eigen::MatrixXd t) {
  if (metric == nullptr) return t;
  const Eigen::Index n = (t.rows() - 3) / 3;
  for (int k = 0; k < 3; ++k) {
    Eigen::MatrixXd block(n, t.cols());
    for (Eigen::Index i = 0; i < n; ++i) block.row(i) = t.row(3 * i + k);
    block = metric->solve(block);
    for (Eigen::Index i = 0; i < n; ++i) t.row(3 * i + k) = block.row(i);
  }
  return t;
}

// The Levenberg–Marquardt step −M⁻¹Jᵀ(JM⁻¹Jᵀ + λI)⁻¹r in scaled (dimensionless) variables: the move of least
// M-norm that lowers the linearised residuals (the solve is the outcomes' count square). A vertex (or a
// plane's foot) on its move bound that the step would push further out loses its outward direction and the
// step is solved again (an active set), so that the bound guides the step instead of clipping it.
Eigen::VectorXd lm_step(Eigen::MatrixXd jac, const Eigen::VectorXd& residual, double lambda, const Point& at,
                        const Bounds& bounds, ShapeFreedom shape, double length, const Metric* metric) {
  Eigen::VectorXd d;
  std::vector<char> held(bounds.origin.size(), 0);
  // Flat faces stay flat to first order: their rows C join the outcomes' with an infinite weight (the limit
  // of a weight μ → ∞ is the ridge λ/μ → 0 on their diagonal; a tiny one keeps dependent rows solvable).
  // Scaled variables are the unscaled ones times L throughout, so C's rows serve as they are.
  // Edges and faces the step would take below their printability bounds are held at them the same way
  // (rows with a target: the change that leaves them just above the bound).
  Eigen::MatrixXd constraints = shape == ShapeFreedom::vertices
                                    ? flatness_rows(bounds.flat, at.points, jac.cols())
                                    : Eigen::MatrixXd(0, jac.cols());
  Eigen::VectorXd targets = Eigen::VectorXd::Zero(constraints.rows());
  Held printable;
  for (int pass = 0; pass < kActivePasses; ++pass) {
    const Eigen::Index outcomes = jac.rows(), rows = outcomes + constraints.rows();
    Eigen::MatrixXd all(rows, jac.cols());
    all << jac, constraints;
    Eigen::VectorXd ridge = Eigen::VectorXd::Constant(rows, lambda);
    ridge.tail(constraints.rows()).setConstant(kFlatRidge * lambda);
    Eigen::VectorXd rhs(rows);
    rhs << residual, -targets;
    const Eigen::MatrixXd g = apply_inverse(metric, all.transpose());
    Eigen::MatrixXd a = all * g;
    a.diagonal() += ridge;
    d = -(g * a.ldlt().solve(rhs));
    if (shape == ShapeFreedom::none) break;
    const Eigen::Index before = constraints.rows();
    if (shape == ShapeFreedom::vertices)
      hold_printable(at, bounds, length, d, printable, constraints, targets);
    bool changed = constraints.rows() != before;
    for (std::size_t i = 0; i < bounds.origin.size(); ++i) {
      // The bounded point (a vertex, or a plane's foot), and the direction in this variable's space that
      // moves it outward.
      const Vec3 x = shape == ShapeFreedom::vertices ? at.points[i] : foot(at.planes[i]);
      const Vec3 out = x - bounds.origin[i];
      if (held[i] || out.norm() < bounds.max_move - 1e-6 * length) continue;
      Vec3 u = out.normalized();
      if (shape == ShapeFreedom::faces) {
        const Vec3 p = at.planes[i].normalized();  // ∂foot/∂p ∝ I − 2 p̂p̂ᵀ (symmetric)
        u = (u - 2 * p.dot(u) * p).normalized();
      }
      const auto col = 3 * static_cast<Eigen::Index>(i);
      if (d.segment<3>(col).dot(u) <= 0) continue;
      held[i] = changed = true;
      jac.middleCols<3>(col) = jac.middleCols<3>(col) * (Mat3::Identity() - u * u.transpose());
      constraints.middleCols<3>(col) =
          constraints.middleCols<3>(col) * (Mat3::Identity() - u * u.transpose());
    }
    if (!changed) break;
  }
  return d;
}

}  // namespace repose::detail
