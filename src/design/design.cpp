// design_quasi_static (design.hpp): Levenberg–Marquardt on the outcomes' residuals with the tape's exact
// Jacobian; every trial point is a new hull and a new landscape, kept only if the objective falls and the
// bounds hold. The shape's variables are its vertices or its face planes (face_planes.hpp).
#include "repose/design/design.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <sstream>

#include "basin_tape.hpp"
#include "face_planes.hpp"
#include "repose/error.hpp"
#include "repose/poses/landscape.hpp"
#include "solid_centroid.hpp"

namespace repose {

DesignFreedom parse_design_freedom(const std::string& text) {
  DesignFreedom out{false, ShapeFreedom::none};
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, '+')) {
    if (item == "center-of-mass" && !out.center_of_mass) {
      out.center_of_mass = true;
    } else if ((item == "vertices" || item == "faces") && out.shape == ShapeFreedom::none) {
      out.shape = item == "vertices" ? ShapeFreedom::vertices : ShapeFreedom::faces;
    } else {
      throw Error(
          "--vary '" + text +
          "': expected center-of-mass, vertices or faces, or one shape and center-of-mass joined by '+'");
    }
  }
  if (!out.center_of_mass && out.shape == ShapeFreedom::none)
    throw Error("--vary '" + text + "': nothing to vary");
  return out;
}

double DesignResult::max_error() const {
  double out = 0;
  for (std::size_t o = 0; o < target.size(); ++o) out = std::max(out, std::abs(achieved[o] - target[o]));
  return out;
}

namespace {

constexpr int kComProjectionRounds = 32;  // rounds pushing the centre of mass inside the shrunk hull
constexpr int kActivePasses = 4;          // re-solves of a step as vertices reach their move bound
constexpr int kKinkSamples = 6;           // nearby points whose gradients are sampled when no step descends
constexpr int kKinkRounds = 3;            // sampling rounds, the radius shrinking tenfold each
constexpr double kKinkJitter = 1e-3;      // the first round's radius, per variable (dimensionless: × L)
constexpr double kKinkFirstStep = 0.05;   // the line search's first step: its largest variable's move (× L)
constexpr double kMinDecrease = 1e-9;     // relative fall of the objective that counts as a step

// One design point, evaluated. Frame: the start's body frame (its centre of mass at the origin).
struct Point {
  std::vector<Vec3>
      points;  // the shape's points (vertices: one per start vertex; faces: the planes' vertices)
  std::vector<Vec3> planes;  // faces: p_f (face_planes.hpp)
  Vec3 com = Vec3::Zero();
  Vec3 centroid = Vec3::Zero();  // the solid hull's
  Particle particle;             // body frame: points − com
  RestLandscape landscape;
  DesignTarget target;
  std::vector<double> achieved;
  double objective = 0, max_error = 0;
  std::set<std::pair<int, int>> stable;  // (outcome, count) of stable faces: the structure's coarse summary
};

struct Bounds {
  double com_margin, max_move, min_edge, min_area;  // lengths and an area
  std::vector<Vec3> origin;                         // where each vertex (faces: each plane's foot) started
};

Vec3 foot(const Vec3& plane) { return plane / plane.squaredNorm(); }  // the plane's point nearest the origin

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
               const DesignTarget& target, const DesignOptions& options) {
  Point p;
  p.points = std::move(points);
  p.planes = std::move(planes);
  p.com = com;
  MeshOptions mesh;
  mesh.inertia = InertiaModel::convex;
  mesh.center_of_mass = com;
  p.particle = make_particle(TriangleMesh{p.points, {}}, name, 1.0, mesh);
  p.centroid = detail::solid_centroid<double>(p.particle.hull.vertices, p.particle.hull) + com;
  p.landscape = compute_rest_landscape(p.particle);
  p.target = target;
  assign_outcome_faces(p.target, p.particle.hull, options.outcome_angle, "--outcome-angle");
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
  for (std::size_t o = 0; o < count.size(); ++o) p.stable.insert({static_cast<int>(o), count[o]});
  for (std::size_t o = 0; o < p.achieved.size(); ++o) {
    const double t = o < target.outcomes.size() ? target.outcomes[o].probability : 0.0;
    const double r = p.achieved[o] - t;
    p.objective += r * r;
    p.max_error = std::max(p.max_error, std::abs(r));
  }
  return p;
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
  const Eigen::MatrixXd rows = tape.gradients(weights);
  const Eigen::Index hull_columns = rows.cols() - 3;
  Eigen::MatrixXd shape_columns;
  if (shape == ShapeFreedom::faces) {
    shape_columns = detail::plane_columns(rows.leftCols(hull_columns), p.particle.hull, -p.com, p.planes);
  } else {
    shape_columns = Eigen::MatrixXd::Zero(rows.rows(), 3 * static_cast<Eigen::Index>(p.points.size()));
    const auto& source = p.particle.hull.source_index;
    for (std::size_t j = 0; j < source.size(); ++j)
      shape_columns.middleCols<3>(3 * source[j]) = rows.middleCols<3>(3 * static_cast<Eigen::Index>(j));
    if (shape == ShapeFreedom::none) shape_columns.setZero();
  }
  Eigen::MatrixXd out(rows.rows(), shape_columns.cols() + 3);
  out << shape_columns, rows.rightCols<3>();
  return out;
}

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
          links.emplace_back(hull.source_index[v], hull.source_index[static_cast<std::size_t>(w)]);
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
  for (int pass = 0; pass < kActivePasses; ++pass) {
    const Eigen::MatrixXd g = apply_inverse(metric, jac.transpose());
    const Eigen::MatrixXd a = jac * g + lambda * Eigen::MatrixXd::Identity(jac.rows(), jac.rows());
    d = -(g * a.ldlt().solve(residual));
    if (shape == ShapeFreedom::none) break;
    bool changed = false;
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
    }
    if (!changed) break;
  }
  return d;
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
      moved = std::max(moved, (points[i] - at.points[i]).norm());
    }
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
    return evaluate(std::move(points), std::move(planes), com, name, target, options);
  } catch (const Error&) {
    ++step.degenerate;  // the points' hull degenerated, or its faces no longer close
    return std::nullopt;
  }
}

// The weights w ≥ 0, Σw = 1 minimising wᵀGw (G the sampled gradients' Gram matrix): over every support set,
// the equality-constrained minimum where its weights are nonnegative (a handful of gradients: at most 2^7
// small solves).
Eigen::VectorXd least_norm_weights(const Eigen::MatrixXd& gram) {
  const auto m = static_cast<int>(gram.rows());
  Eigen::VectorXd best = Eigen::VectorXd::Zero(m);
  best[0] = 1;
  double best_value = gram(0, 0);
  for (unsigned set = 1; set < (1u << m); ++set) {
    std::vector<int> in;
    for (int i = 0; i < m; ++i)
      if (set & (1u << i)) in.push_back(i);
    const auto k = static_cast<Eigen::Index>(in.size());
    Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(k + 1, k + 1);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(k + 1);
    for (Eigen::Index a = 0; a < k; ++a) {
      for (Eigen::Index b = 0; b < k; ++b)
        kkt(a, b) = gram(in[static_cast<std::size_t>(a)], in[static_cast<std::size_t>(b)]);
      kkt(a, k) = kkt(k, a) = 1;
    }
    rhs[k] = 1;
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(kkt);
    if (!lu.isInvertible()) continue;
    const Eigen::VectorXd sol = lu.solve(rhs);
    if ((sol.head(k).array() < 0).any()) continue;
    Eigen::VectorXd w = Eigen::VectorXd::Zero(m);
    for (Eigen::Index a = 0; a < k; ++a) w[in[static_cast<std::size_t>(a)]] = sol[a];
    const double value = w.dot(gram * w);
    if (value < best_value) best_value = value, best = w;
  }
  return best;
}

void check(const DesignOptions& o) {
  if (!(o.outcome_angle > 0 && o.outcome_angle <= std::numbers::pi))
    throw Error("design: --outcome-angle must be in (0, 180] degrees");
  if (!(o.com_margin >= 0) || !(o.max_vertex_move >= 0) || !(o.min_edge >= 0) || !(o.min_face_area >= 0) ||
      !(o.smoothing >= 0))
    throw Error(
        "design: the bounds (--com-margin, --max-move, --min-edge, --min-face) and --smoothing must be "
        "numbers "
        ">= 0");
  if (!(o.tolerance > 0) || o.max_iterations < 0 || o.max_trials < 1)
    throw Error("design: --tolerance must be > 0 and --iterations >= 0");
  if (!o.freedom.center_of_mass && o.freedom.shape == ShapeFreedom::none)
    throw Error("design: nothing to vary");
}

}  // namespace

DesignResult design_quasi_static(const Particle& start, DesignTarget target, const DesignOptions& options) {
  check(options);
  // The outcomes must be outcomes of the starting hull (the error names the option).
  assign_outcome_faces(target, start.hull, options.outcome_angle, "--outcome-angle");

  const double length = start.length;
  const ShapeFreedom shape = options.freedom.shape;
  // With a fixed shape the centre of mass is simply the variable; MassModel matters when the shape moves.
  const MassModel mass = shape != ShapeFreedom::none ? options.mass : MassModel::fixed;
  std::vector<Vec3> planes = detail::face_planes(start.hull, Vec3::Zero());
  Bounds bounds{options.com_margin * length,
                options.max_vertex_move * length,
                std::min(options.min_edge * length, shortest_edge(start.hull)),
                std::min(options.min_face_area * length * length, smallest_face(start.hull)),
                {}};
  if (shape == ShapeFreedom::faces) {
    for (const Vec3& p : planes) bounds.origin.push_back(foot(p));
  } else {
    bounds.origin = start.hull.vertices;
  }
  // The start's centre of mass is the body frame's origin.
  Point at = evaluate(start.hull.vertices, planes, Vec3::Zero(), start.name, target, options);

  DesignResult result;
  result.start = at.achieved;
  for (const auto& o : target.outcomes) result.target.push_back(o.probability);
  result.target.push_back(0);
  result.stop = "iterations";
  double lambda = -1;
  // Levenberg–Marquardt trials from `from` with its Jacobian, λ raised after each rejection and lowered after
  // an acceptance: the first trial point with an objective below `best`'s.
  // The linearised problem at a point, in dimensionless variables (so that λ weighs every kind of move
  // alike: lengths per L, planes (per length) times L).
  struct System {
    Eigen::MatrixXd jac;
    Eigen::VectorXd residual, scale;
  };
  auto system = [&](const Point& from) {
    System out;
    out.jac = jacobian(from, mass, shape);
    if (!options.freedom.center_of_mass) out.jac.rightCols<3>().setZero();
    out.residual.resize(static_cast<Eigen::Index>(from.achieved.size()));
    for (Eigen::Index o = 0; o < out.residual.size(); ++o)
      out.residual[o] =
          from.achieved[static_cast<std::size_t>(o)] - result.target[static_cast<std::size_t>(o)];
    out.scale = Eigen::VectorXd::Constant(out.jac.cols(), shape == ShapeFreedom::faces ? 1 / length : length);
    out.scale.tail<3>().setConstant(length);
    out.jac = out.jac * out.scale.asDiagonal();
    return out;
  };
  auto descend = [&](const Point& from, const Point& best, double& lam,
                     DesignStep& step) -> std::optional<Point> {
    const System sys = system(from);
    const Eigen::VectorXd& residual = sys.residual;
    const Eigen::VectorXd& scale = sys.scale;
    const std::unique_ptr<Metric> metric = shape_metric(from, shape, options.smoothing, length);
    if (lam < 0)
      lam = 1e-3 * (sys.jac * apply_inverse(metric.get(), sys.jac.transpose())).diagonal().maxCoeff();
    // The trials move every variable together first; if none lowers the objective, the centre of mass alone,
    // then the shape alone (a block step: on a fine hull the joint least-norm step is mostly the vertices',
    // whose many changes of structure can defeat it where the centre of mass's share alone would descend).
    const Eigen::Index n = sys.jac.cols() - 3;
    const double first_lam = lam;
    const bool both = options.freedom.center_of_mass && shape != ShapeFreedom::none;
    for (int block = 0; block < (both ? 3 : 1); ++block) {
      Eigen::MatrixXd jac = sys.jac;
      if (block == 1) jac.leftCols(n).setZero();
      if (block == 2) jac.rightCols<3>().setZero();
      double block_lam = first_lam;  // each block from this call's λ (block 0's has grown by its rejections)
      const int trials = block == 0 ? options.max_trials : std::max(1, options.max_trials / 2);
      for (int trial = 0; trial < trials; ++trial) {
        ++step.trials;
        Eigen::VectorXd d = lm_step(jac, residual, block_lam, from, bounds, shape, length, metric.get());
        // A trust region: no shape variable moves more than max_step (× L) in one iteration, so that the
        // shape follows its gradient's path instead of jumping across many changes of structure at once (the
        // centre of mass, whose probabilities vary smoothly over much longer moves, is not held back).
        const double longest = d.head(n).cwiseAbs().maxCoeff();
        if (longest > options.max_step) d *= options.max_step / longest;
        d = d.cwiseProduct(scale);
        double moved = 0;
        std::optional<Point> next =
            trial_point(from, d, mass, shape, bounds, start.name, target, options, step, moved);
        // A decrease at round-off is no progress (it would only spin out the iterations).
        if (next && next->objective < best.objective * (1 - kMinDecrease)) {
          step.step = std::max(moved, (next->com - best.com).norm()) / length;
          lam = block_lam / 3;
          return next;
        }
        if (next) ++step.rose;
        block_lam *= 4;
      }
      if (block == 0) lam = block_lam;
    }
    return std::nullopt;
  };
  for (int iteration = 0; iteration <= options.max_iterations; ++iteration) {
    if (at.max_error <= options.tolerance) {
      result.stop = "converged";
      break;
    }
    if (iteration == options.max_iterations) break;
    DesignStep step;
    std::optional<Point> next = descend(at, at, lambda, step);
    // No step lowers the objective: the point may sit on a kink (a face exactly planar, a tie of the
    // rolling), where the current structure's gradient is one side's and no side's step descends far.
    // Gradient sampling (Burke, Lewis & Overton 2005): the objective's gradients at the point and at
    // kKinkSamples deterministic jitters within a radius; the least-norm convex combination (in the shape's
    // metric) is a descent direction across the kink; a backtracking line search along it. The radius
    // shrinks tenfold each round.
    for (int round = 0; !next && round < kKinkRounds; ++round) {
      const double radius = kKinkJitter * std::pow(0.1, round);
      const std::unique_ptr<Metric> metric = shape_metric(at, shape, options.smoothing, length);
      const System here = system(at);
      std::vector<Eigen::VectorXd> gradients = {2 * here.jac.transpose() * here.residual};
      for (int k = 0; k < kKinkSamples; ++k) {
        std::mt19937 bits(static_cast<unsigned>(1000 * iteration + 10 * round + k));
        Eigen::VectorXd jitter(here.scale.size());
        for (Eigen::Index i = 0; i < jitter.size(); ++i)
          jitter[i] = radius * (2.0 * static_cast<double>(bits()) / 4294967295.0 - 1.0);
        if (!options.freedom.center_of_mass) jitter.tail<3>().setZero();
        if (shape == ShapeFreedom::none) jitter.head(jitter.size() - 3).setZero();
        DesignStep scratch;
        double moved = 0;
        const std::optional<Point> near = trial_point(at, jitter.cwiseProduct(here.scale), mass, shape,
                                                      bounds, start.name, target, options, scratch, moved);
        if (!near) continue;
        ++step.kink_samples;
        const System there = system(*near);
        gradients.push_back(2 * there.jac.transpose() * there.residual);
      }
      Eigen::MatrixXd g(here.scale.size(), static_cast<Eigen::Index>(gradients.size()));
      for (std::size_t k = 0; k < gradients.size(); ++k) g.col(static_cast<Eigen::Index>(k)) = gradients[k];
      const Eigen::MatrixXd mg = apply_inverse(metric.get(), g);
      const Eigen::VectorXd direction = -(mg * least_norm_weights(g.transpose() * mg));
      const double longest = direction.cwiseAbs().maxCoeff();
      if (!(longest > 0)) break;  // a stationary point of every sampled piece
      for (double t = kKinkFirstStep / longest; t * longest > 1e-12 && !next; t /= 2) {
        ++step.trials;
        double moved = 0;
        std::optional<Point> trial = trial_point(at, (t * direction).cwiseProduct(here.scale), mass, shape,
                                                 bounds, start.name, target, options, step, moved);
        if (trial && trial->objective < at.objective * (1 - kMinDecrease)) {
          step.step = moved / length;
          next = std::move(trial);
        } else if (trial) {
          ++step.rose;
        }
      }
    }
    const bool accepted = next.has_value();
    if (accepted) {
      step.structure_changed = next->stable != at.stable;
      at = std::move(*next);
    }
    step.accepted = accepted;
    step.objective = at.objective;
    step.max_error = at.max_error;
    for (std::size_t f = 0; f < at.landscape.face_rest.size(); ++f)
      step.stable_faces += at.landscape.face_rest[f] == static_cast<int>(f);
    result.history.push_back(step);
    if (!accepted) {
      result.stop = "stalled";
      break;
    }
  }

  const Vec3 frame = start.input_offset;
  for (const Vec3& v : at.particle.hull.vertices) result.vertices.push_back(v + at.com + frame);
  result.mesh.vertices = result.vertices;
  for (const HullFace& f : at.particle.hull.faces)
    for (std::size_t k = 1; k + 1 < f.loop.size(); ++k)
      result.mesh.triangles.push_back({f.loop[0], f.loop[k], f.loop[k + 1]});
  result.center_of_mass = at.com + frame;
  result.centroid = at.centroid + frame;
  result.length = at.particle.length;
  result.achieved = at.achieved;
  return result;
}

}  // namespace repose
