// The quasi-static design's descent (descent.hpp).
#include "descent.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

#include "attraction.hpp"
#include "design_step.hpp"
#include "face_planes.hpp"
#include "repose/error.hpp"

namespace repose::detail {

namespace {

constexpr double kMinDecrease = 1e-9;  // relative fall of the objective that counts as a step

void check(const DesignOptions& o) {
  if (!(o.outcome_angle > 0 && o.outcome_angle <= std::numbers::pi))
    throw Error("design: --outcome-angle must be in (0, 180] degrees");
  if (!(o.com_margin >= 0) || !(o.max_vertex_move >= 0) || !(o.min_edge >= 0) || !(o.min_face_area >= 0) ||
      !(o.smoothing >= 0) || !(o.min_margin >= 0))
    throw Error(
        "design: the bounds (--com-margin, --max-move, --min-edge, --min-face, --min-margin) and --smoothing "
        "must be numbers >= 0");
  if (!(o.tolerance > 0) || o.max_iterations < 0 || o.max_trials < 1)
    throw Error("design: --tolerance must be > 0 and --iterations >= 0");
  if (!o.freedom.center_of_mass && o.freedom.shape == ShapeFreedom::none)
    throw Error("design: nothing to vary");
}

// Per outcome, then the unassigned faces' 0.
std::vector<double> target_vector(const DesignTarget& target) {
  std::vector<double> out;
  for (const auto& o : target.outcomes) out.push_back(o.probability);
  out.push_back(0);
  return out;
}

}  // namespace

DesignSetup design_setup(const Particle& start, const DesignOptions& options) {
  check(options);
  DesignSetup s;
  s.start = &start;
  s.length = start.length;
  s.shape = options.freedom.shape;
  // With a fixed shape the centre of mass is simply the variable; MassModel matters when the shape moves.
  s.mass = s.shape != ShapeFreedom::none ? options.mass : MassModel::fixed;
  const double length = s.length;
  s.bounds = Bounds{options.com_margin * length,
                    options.max_vertex_move * length,
                    std::min(options.min_edge * length, shortest_edge(start.hull)),
                    std::min(options.min_face_area * length * length, smallest_face(start.hull)),
                    {},
                    {}};
  if (s.shape == ShapeFreedom::faces) {
    for (const Vec3& p : face_planes(start.hull)) s.bounds.origin.push_back(foot(p));
  } else {
    s.bounds.origin = start.hull.vertices;
    if (s.shape == ShapeFreedom::vertices && options.keep_faces_flat) s.bounds.flat = flat_faces(start.hull);
  }
  return s;
}

Point start_point(const DesignSetup& setup, DesignTarget target, const DesignOptions& options) {
  const Particle& start = *setup.start;
  // The outcomes must be outcomes of the starting hull (the error names the option).
  assign_outcome_faces(target, start.hull, options.outcome_angle, "--outcome-angle");
  // The start's centre of mass is the body frame's origin.
  Point p = evaluate(start.hull.vertices, face_planes(start.hull), Vec3::Zero(), start.name, target, options);
  // The floor keeps a face that starts robust from sliding to the edge of stability; an outcome whose best
  // stable face starts closer to it than options.min_margin is free (a start designed that way).
  const std::vector<double> margins = outcome_margins(p);
  for (std::size_t o = 0; o < margins.size(); ++o)
    if (margins[o] > 0 && margins[o] < p.margin_floor[o]) p.margin_floor[o] = 0;
  score(p);
  return p;
}

Point retarget(const Point& at, const DesignTarget& target) {
  // The same hull, landscape, outcome normals and faces; only the probabilities asked for change.
  Point out = at;
  for (std::size_t k = 0; k < out.target.outcomes.size(); ++k)
    out.target.outcomes[k].probability = target.outcomes[k].probability;
  score(out);
  return out;
}

bool follow_outcome_normals(Point& p, double max_angle, bool& kept) {
  DesignTarget moved = p.target;
  for (DesignOutcome& o : moved.outcomes) {
    int best = -1;
    double most = 0;
    for (const int f : o.faces) {
      const double q = p.landscape.basin_probability[static_cast<std::size_t>(f)];
      if (q > most) most = q, best = f;
    }
    // An outcome with no stable face keeps its normal (the attraction pulls a face toward it).
    if (best >= 0) o.normal = p.particle.hull.faces[static_cast<std::size_t>(best)].normal;
  }
  try {
    assign_outcome_faces(moved, p.particle.hull, max_angle, "--outcome-angle");
  } catch (const Error&) {
    // An outcome with no stable face lost its last face to a moved normal: the normals stay (counted).
    kept = true;
    return false;
  }
  bool changed = moved.unassigned_faces != p.target.unassigned_faces;
  for (std::size_t k = 0; k < moved.outcomes.size(); ++k)
    changed = changed || moved.outcomes[k].faces != p.target.outcomes[k].faces;
  p.target = std::move(moved);
  score(p);
  return changed;
}

Descent descend(Point from, const DesignTarget& target, const DesignSetup& setup,
                const DesignOptions& options) {
  const Particle& start = *setup.start;
  const double length = setup.length;
  const ShapeFreedom shape = setup.shape;
  const MassModel mass = setup.mass;
  const Bounds& bounds = setup.bounds;
  const std::vector<double> goal = target_vector(target);

  Descent out;
  out.at = std::move(from);
  out.stop = "iterations";
  double lambda = -1;
  // The linearised problem at a point, in dimensionless variables (so that λ weighs every kind of move
  // alike: lengths per L, planes (per length) times L).
  struct System {
    Eigen::MatrixXd jac;
    Eigen::VectorXd residual, scale;
  };
  auto system = [&](const Point& at) {
    System sys;
    sys.jac = jacobian(at, mass, shape);
    sys.residual.resize(static_cast<Eigen::Index>(at.achieved.size()));
    for (Eigen::Index o = 0; o < sys.residual.size(); ++o)
      sys.residual[o] = at.achieved[static_cast<std::size_t>(o)] - goal[static_cast<std::size_t>(o)];
    // Outcomes whose faces are all unstable: their attraction residuals and rows join (attraction.hpp).
    if (std::any_of(at.attraction.begin(), at.attraction.end(), [](double a) { return a > 0; })) {
      const Eigen::MatrixXd pull = attraction_rows(at, mass, shape);
      for (std::size_t o = 0; o < at.attraction.size(); ++o) {
        if (!(at.attraction[o] > 0)) continue;
        const Eigen::Index row = sys.jac.rows();
        sys.jac.conservativeResize(row + 1, Eigen::NoChange);
        sys.jac.row(row) = pull.row(static_cast<Eigen::Index>(o));
        sys.residual.conservativeResize(row + 1);
        sys.residual[row] = at.attraction[o];
      }
    }
    if (!options.freedom.center_of_mass) sys.jac.rightCols<3>().setZero();
    sys.scale = Eigen::VectorXd::Constant(sys.jac.cols(), shape == ShapeFreedom::faces ? 1 / length : length);
    sys.scale.tail<3>().setConstant(length);
    sys.jac = sys.jac * sys.scale.asDiagonal();
    return sys;
  };
  // Levenberg–Marquardt trials from `at` with its Jacobian, λ raised after each rejection and lowered after
  // an acceptance: the first trial point with an objective below `at`'s.
  auto step_from = [&](const Point& at, double& lam, DesignStep& step) -> std::optional<Point> {
    const System sys = system(at);
    const Eigen::VectorXd& residual = sys.residual;
    const Eigen::VectorXd& scale = sys.scale;
    // The flat faces that are still faces (a face whose points fell inside the hull constrains nothing).
    Bounds live = bounds;
    live.flat = standing_faces(bounds.flat, at.particle.hull, at.design_index);
    const std::unique_ptr<Metric> metric = shape_metric(at, shape, options.smoothing, length);
    // λ's first value: 1e-3 of the largest diagonal of JM⁻¹Jᵀ (a flat start, J = 0, still gets a positive
    // one, so that the solve stays defined).
    const double typical_lam = std::max(
        1e-3 * (sys.jac * apply_inverse(metric.get(), sys.jac.transpose())).diagonal().maxCoeff(), 1e-12);
    if (lam < 0) lam = typical_lam;
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
        Eigen::VectorXd d = lm_step(jac, residual, block_lam, at, live, shape, length, metric.get());
        // A trust region: no shape variable moves more than max_step (× L) in one iteration, so that the
        // shape follows its gradient's path instead of jumping across many changes of structure at once (the
        // centre of mass, whose probabilities vary smoothly over much longer moves, is not held back).
        const double longest = d.head(n).cwiseAbs().maxCoeff();
        if (longest > options.max_step) d *= options.max_step / longest;
        d = d.cwiseProduct(scale);
        double moved = 0;
        std::optional<Point> next =
            trial_point(at, d, mass, shape, live, start.name, at.target, options, step, moved);
        // A decrease at round-off is no progress (it would only spin out the iterations).
        if (next && next->objective < at.objective * (1 - kMinDecrease)) {
          step.step = std::max(moved, (next->com - at.com).norm()) / length;
          lam = block_lam / 3;
          return next;
        }
        if (next) ++step.rose;
        // After a rejection λ is at least its typical value: a λ lowered by many acceptances would otherwise
        // grow through the trials while the trust region still caps every step at the same length.
        block_lam = std::max(4 * block_lam, typical_lam);
      }
      if (block == 0) lam = block_lam;
    }
    return std::nullopt;
  };
  Point& at = out.at;
  for (int iteration = 0; iteration <= options.max_iterations; ++iteration) {
    if (at.max_error <= options.tolerance) {
      out.stop = "converged";
      break;
    }
    if (iteration == options.max_iterations) break;
    DesignStep step;
    std::optional<Point> next = step_from(at, lambda, step);
    const bool accepted = next.has_value();
    if (accepted) {
      step.structure_changed = next->stable != at.stable;
      at = std::move(*next);
      if (options.follow_outcome_normals)
        step.outcomes_reassigned = follow_outcome_normals(at, options.outcome_angle, step.normals_kept);
    }
    step.accepted = accepted;
    step.objective = at.objective;
    step.max_error = at.max_error;
    for (std::size_t f = 0; f < at.landscape.face_rest.size(); ++f)
      step.stable_faces += at.landscape.face_rest[f] == static_cast<int>(f);
    out.history.push_back(step);
    if (!accepted) {
      out.stop = "stalled";
      break;
    }
  }
  return out;
}

DesignResult design_result(const DesignSetup& setup, const Point& start, const Descent& descent) {
  const Point& at = descent.at;
  DesignResult result;
  result.target = target_vector(at.target);
  for (const DesignOutcome& o : at.target.outcomes) result.outcome_normals.push_back(o.normal);
  result.outcome_margin = outcome_margins(at);
  result.start = start.achieved;
  result.history = descent.history;
  result.stop = descent.stop;
  const Vec3 frame = setup.start->input_offset;
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

}  // namespace repose::detail
