// design_quasi_static (design.hpp): Levenberg–Marquardt on the outcomes' residuals with the tape's exact
// Jacobian; every trial point is a new hull and a new landscape, kept only if the objective falls and the
// bounds hold. The shape's variables are its vertices or its face planes (face_planes.hpp).
#include "repose/design/design.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>

#include "design_point.hpp"
#include "design_step.hpp"
#include "face_planes.hpp"
#include "repose/error.hpp"
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

constexpr double kMinDecrease = 1e-9;  // relative fall of the objective that counts as a step

using detail::apply_inverse;
using detail::Bounds;
using detail::evaluate;
using detail::foot;
using detail::jacobian;
using detail::lm_step;
using detail::Metric;
using detail::Point;
using detail::shape_metric;
using detail::shortest_edge;
using detail::smallest_face;
using detail::trial_point;

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
  std::vector<Vec3> planes = detail::face_planes(start.hull);
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
    // λ's first value: 1e-3 of the largest diagonal of JM⁻¹Jᵀ (a flat start, J = 0, still gets a positive
    // one, so that the solve stays defined).
    if (lam < 0)
      lam = std::max(
          1e-3 * (sys.jac * apply_inverse(metric.get(), sys.jac.transpose())).diagonal().maxCoeff(), 1e-12);
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
