// Design points and flat faces (src/design/design_point.hpp, flat_faces.hpp): the Jacobian's columns belong
// to the design's own points even when some lie inside the hull, and a flat face stays flat, so that the
// probabilities' one-sided derivatives along a step agree with the Jacobian on both sides.
#include "../../src/design/design_point.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "../../src/design/attraction.hpp"
#include "../../src/design/descent.hpp"
#include "../../src/design/design_step.hpp"
#include "../../src/design/flat_faces.hpp"
#include "repose/design/design.hpp"
#include "repose/design/target.hpp"
#include "repose/model/particle.hpp"

namespace repose {
namespace {

const DesignTarget kAxes = parse_design_target(
    "[[[1,0,0],0.2],[[-1,0,0],0.2],[[0,1,0],0.2],[[0,-1,0],0.15],[[0,0,1],0.15],[[0,0,-1],0.1]]", "axes");

DesignOptions every_face() {
  DesignOptions o;
  o.outcome_angle = std::numbers::pi;  // every face to its nearest axis
  return o;
}

detail::Point point(const std::vector<Vec3>& points, const DesignOptions& options) {
  DesignTarget target = kAxes;
  ConvexHull hull = compute_convex_hull(points);
  assign_outcome_faces(target, hull, options.outcome_angle, "--outcome-angle");
  return detail::evaluate(points, {}, Vec3::Zero(), "points", target, options);
}

// A box's corners, off-centre (no symmetry makes a derivative vanish by accident).
std::vector<Vec3> box_corners() {
  std::vector<Vec3> corners;
  for (const double x : {-0.5, 0.5})
    for (const double y : {-0.55, 0.55})
      for (const double z : {-0.45, 0.45}) corners.emplace_back(x + 0.03, y, z - 0.02);
  return corners;
}

// The box as a design point, its Jacobian (vertices; scaled variables: × L) and its residuals.
struct BoxStep {
  detail::Point at;
  Eigen::MatrixXd jac;
  Eigen::VectorXd residual;
  // The Levenberg–Marquardt step (λ = 1e-6, no metric) within `bounds`.
  Eigen::VectorXd step(const detail::Bounds& bounds) const {
    return detail::lm_step(jac, residual, 1e-6, at, bounds, ShapeFreedom::vertices, at.particle.length,
                           nullptr);
  }
};
BoxStep box_step() {
  BoxStep out{point(box_corners(), every_face()), {}, {}};
  const detail::Point& at = out.at;
  out.jac = detail::jacobian(at, MassModel::fixed, ShapeFreedom::vertices) * at.particle.length;
  out.jac.rightCols<3>().setZero();
  out.residual.resize(static_cast<Eigen::Index>(at.achieved.size()));
  for (Eigen::Index o = 0; o + 1 < out.residual.size(); ++o)
    out.residual[o] = at.achieved[static_cast<std::size_t>(o)] -
                      at.target.outcomes[static_cast<std::size_t>(o)].probability;
  out.residual[out.residual.size() - 1] = at.achieved.back();
  return out;
}

// Points inside the hull (first in the list, and among the others) are design points too: the Jacobian's
// columns for every point on the hull equal five-point central differences of the outcomes' probabilities
// with that point moved (h = 4e-5·L, the tolerance of BasinGradient's vertex test, whose noise argument
// applies), and an inside point's columns are zero. The particle counts only the points on the hull, so a
// column placed by the particle's own indices lands on the wrong point after the first inside one.
TEST(DesignPoint, JacobianColumnsBelongToTheirPointsWhenSomeAreInsideTheHull) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> radius(0.8, 1.0);
  std::vector<Vec3> points;
  for (int k = 0; k < 34; ++k) {
    const bool inside = k == 0 || k == 9 || k == 20 || k == 33;
    const Vec3 u = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    points.push_back(u * (inside ? 0.2 : radius(rng)) + Vec3(0.05, -0.03, 0.02));
  }
  const DesignOptions options = every_face();
  const detail::Point at = point(points, options);
  ASSERT_LE(at.particle.hull.vertices.size(), 30u);  // the four inside, and any other the hull covers
  ASSERT_GE(at.particle.hull.vertices.size(), 20u);
  for (const HullFace& f : at.particle.hull.faces) ASSERT_EQ(f.loop.size(), 3u);
  const Eigen::MatrixXd jac = detail::jacobian(at, MassModel::fixed, ShapeFreedom::vertices);
  const double h = 4e-5 * at.particle.length;
  int compared = 0, skipped = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool on_hull = std::find(at.design_index.begin(), at.design_index.end(), static_cast<int>(i)) !=
                         at.design_index.end();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index col = 3 * static_cast<Eigen::Index>(i) + k;
      if (!on_hull) {
        EXPECT_EQ(jac.col(col).cwiseAbs().maxCoeff(), 0.0) << "inside point " << i;
        continue;
      }
      bool same = true;
      auto moved = [&](double s) {
        std::vector<Vec3> q = points;
        q[i][k] += s * h;
        const detail::Point x = point(q, options);
        same = same && x.landscape.face_rest == at.landscape.face_rest &&
               x.particle.hull.faces.size() == at.particle.hull.faces.size();
        return Eigen::Map<const Eigen::VectorXd>(x.achieved.data(),
                                                 static_cast<Eigen::Index>(x.achieved.size()))
            .eval();
      };
      const Eigen::VectorXd fd = (8 * (moved(1) - moved(-1)) - (moved(2) - moved(-2))) / (12 * h);
      if (!same) {
        ++skipped;
        continue;
      }
      for (Eigen::Index o = 0; o < fd.size(); ++o) {
        const double scale = std::abs(fd[o]) + 1e-2 / at.particle.length;
        EXPECT_NEAR(jac(o, col), fd[o], 1e-6 * scale) << "point " << i << " axis " << k << " outcome " << o;
        ++compared;
      }
    }
  }
  std::printf("compared %d derivatives, %d coordinates skipped (structure changes within 2h)\n", compared,
              skipped);
  EXPECT_LT(skipped, static_cast<int>(3 * at.design_index.size() / 8));
}

// A cube's points jittered by 1e-3·L are put back on planes: each face's four corners coplanar to round-off,
// so the hull is a hexahedron of six quadrilaterals again; the move is of the jitter's order.
TEST(FlatFaces, FlattenPutsEachFacesCornersBackOnAPlane) {
  const ConvexHull cube = compute_convex_hull(
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}});
  const std::vector<detail::FlatFace> flat = detail::flat_faces(cube);
  ASSERT_EQ(flat.size(), 6u);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-1e-3, 1e-3);
  std::vector<Vec3> points = cube.vertices;
  for (Vec3& p : points) p += Vec3(jitter(rng), jitter(rng), jitter(rng));
  EXPECT_GT(compute_convex_hull(points).faces.size(), 6u);  // folded
  std::vector<Vec3> flattened = points;
  ASSERT_TRUE(detail::flatten(flattened, flat, 1e-14));
  const ConvexHull after = compute_convex_hull(flattened);
  ASSERT_EQ(after.faces.size(), 6u);
  for (const HullFace& f : after.faces) EXPECT_EQ(f.loop.size(), 4u);
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_LT((flattened[i] - points[i]).norm(), 4e-3);
}

// With flat faces kept flat a step's one-sided derivatives agree: along a random direction within the
// faces' planes (projected on the constraints' null space) the probabilities of the cube's outcomes change
// at the Jacobian's rate forwards and backwards (t = 1e-6·L; a one-sided difference's error is t times the
// curvature, ~1e-6 here; tolerance 1e-4 of the rate's scale). Moving one corner off its faces would fold them
// (the kink: one-sided rates of a quadrilateral differ by ~30 %).
TEST(FlatFaces, AStepWithinTheFacesPlanesHasOneDerivative) {
  const DesignOptions options = every_face();
  const detail::Point at = point(box_corners(), options);
  const std::vector<detail::FlatFace> flat = detail::flat_faces(at.particle.hull);
  ASSERT_EQ(flat.size(), 6u);
  const Eigen::MatrixXd jac = detail::jacobian(at, MassModel::fixed, ShapeFreedom::vertices);
  const Eigen::MatrixXd c = detail::flatness_rows(flat, at.points, jac.cols());
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  const double t = 1e-6 * at.particle.length;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd d(jac.cols());
    for (Eigen::Index k = 0; k < d.size(); ++k) d[k] = normal(rng);
    d.tail<3>().setZero();
    d -= c.transpose() * (c * c.transpose()).ldlt().solve(c * d);  // within the planes, to first order
    d /= d.norm();
    const Eigen::VectorXd rate = jac * d;
    for (const double s : {1.0, -1.0}) {
      std::vector<Vec3> q = at.points;
      for (std::size_t i = 0; i < q.size(); ++i)
        q[i] += s * t * d.segment<3>(3 * static_cast<Eigen::Index>(i));
      ASSERT_TRUE(detail::flatten(q, flat, 1e-14 * at.particle.length));
      DesignTarget target = at.target;
      const detail::Point x = detail::evaluate(q, {}, at.com, "moved", target, options);
      ASSERT_EQ(x.particle.hull.faces.size(), 6u);
      for (Eigen::Index o = 0; o < rate.size(); ++o) {
        const double one_sided =
            s * (x.achieved[static_cast<std::size_t>(o)] - at.achieved[static_cast<std::size_t>(o)]) / t;
        EXPECT_NEAR(one_sided, rate[o], 1e-4 * (rate.cwiseAbs().maxCoeff() + 1e-3))
            << "trial " << trial << " side " << s << " outcome " << o;
      }
    }
  }
}

// The Levenberg–Marquardt step keeps the flat faces flat to first order (their rows' residual C·d is
// round-off against |d|), while the same step without them folds the faces (C·d ~1e-2 of |d|): the
// constraint rows are what keeps a step within the planes, not the flattening after it.
TEST(FlatFaces, TheStepSolvesWithinTheFacesPlanes) {
  const BoxStep box = box_step();
  const detail::Point& at = box.at;
  const double length = at.particle.length;
  detail::Bounds bounds{0, 10 * length, 0, 0, at.points, detail::flat_faces(at.particle.hull)};
  const Eigen::MatrixXd c = detail::flatness_rows(bounds.flat, at.points, box.jac.cols());
  const Eigen::VectorXd d = box.step(bounds);
  ASSERT_GT(d.norm(), 1e-3);
  EXPECT_LT((c * d).norm(), 1e-9 * d.norm());
  bounds.flat.clear();
  const Eigen::VectorXd free = box.step(bounds);
  EXPECT_GT((c * free).norm(), 1e-3 * free.norm());  // 8e-3 here: six orders above the constrained step
}

// The printability bounds are held in the step: with the bounds at the box's own smallest face and shortest
// edge, the step's first-order change (a finite difference of the hull moved by 1e-6 of the step, faces
// matched by normal; the faces kept flat) leaves every face and edge at or above its bound, while the step
// without the bounds takes some below. Tolerance: 1e-6 of the bound (the difference's truncation, ~1e-6 of
// the change).
TEST(FlatFaces, ThePrintabilityBoundsHoldTheStep) {
  const BoxStep box = box_step();
  const detail::Point& at = box.at;
  const double length = at.particle.length;
  const std::vector<detail::FlatFace> flat = detail::flat_faces(at.particle.hull);
  double least_area = INFINITY, least_edge = INFINITY;
  for (const HullFace& f : at.particle.hull.faces) least_area = std::min(least_area, f.area);
  for (std::size_t v = 0; v < at.particle.hull.vertices.size(); ++v)
    for (const int w : at.particle.hull.neighbors(static_cast<int>(v)))
      least_edge = std::min(
          least_edge,
          (at.particle.hull.vertices[v] - at.particle.hull.vertices[static_cast<std::size_t>(w)]).norm());
  // The least face area and edge length after the step, to first order.
  auto after = [&](const Eigen::VectorXd& d) {
    const double eps = 1e-6;
    std::vector<Vec3> q = at.points;
    for (std::size_t i = 0; i < q.size(); ++i)
      q[i] += eps * length * d.segment<3>(3 * static_cast<Eigen::Index>(i));
    EXPECT_TRUE(detail::flatten(q, flat, 1e-15));  // the faces' second-order fold, so that they stay whole
    const ConvexHull moved = compute_convex_hull(q);
    const ConvexHull here = compute_convex_hull(at.points);
    double area = INFINITY, edge = INFINITY;
    for (const HullFace& f : here.faces)
      for (const HullFace& g : moved.faces)
        if (g.normal.dot(f.normal) > 1 - 1e-6) area = std::min(area, f.area + (g.area - f.area) / eps);
    for (std::size_t v = 0; v < here.vertices.size(); ++v)
      for (const int w : here.neighbors(static_cast<int>(v))) {
        const double was = (here.vertices[v] - here.vertices[static_cast<std::size_t>(w)]).norm();
        const double now = (moved.vertices[v] - moved.vertices[static_cast<std::size_t>(w)]).norm();
        edge = std::min(edge, was + (now - was) / eps);
      }
    return std::make_pair(area, edge);
  };
  detail::Bounds free{0, 10 * length, 0, 0, at.points, flat};
  const auto unbounded = after(box.step(free));
  ASSERT_TRUE(unbounded.first < least_area * 0.99 || unbounded.second < least_edge * 0.99);
  detail::Bounds bounds{0, 10 * length, least_edge, least_area, at.points, flat};
  const Eigen::VectorXd d = box.step(bounds);
  ASSERT_GT(d.norm(), 1e-3);
  const auto held = after(d);
  EXPECT_GE(held.first, least_area * (1 - 1e-6));
  EXPECT_GE(held.second, least_edge * (1 - 1e-6));
  std::printf("least face %g -> %g (unbounded %g); least edge %g -> %g (unbounded %g)\n", least_area,
              held.first, unbounded.first, least_edge, held.second, unbounded.second);
}

// The centre of mass is pushed inside the shrunk hull along the violated face's normal, exactly onto the
// margin: a unit cube's centre moved 0.7 along +x (0.2 beyond the face at x = 0.5) with a margin of 0.1 ends
// at x = 0.4 (to the push's 1e-9 overshoot), its other coordinates unchanged.
TEST(DesignPoint, TheCentreOfMassIsPushedOntoTheMargin) {
  std::vector<Vec3> corners;
  for (const double x : {-0.5, 0.5})
    for (const double y : {-0.5, 0.5})
      for (const double z : {-0.5, 0.5}) corners.emplace_back(x, y, z);
  const ConvexHull cube = compute_convex_hull(corners);
  Vec3 com(0.7, 0.1, -0.2);
  ASSERT_TRUE(detail::push_inside(cube, 0.1, com));
  EXPECT_NEAR(com.x(), 0.4, 1e-9);
  EXPECT_EQ(com.y(), 0.1);
  EXPECT_EQ(com.z(), -0.2);
  Vec3 inside(0.1, 0.2, 0.3);
  ASSERT_TRUE(detail::push_inside(cube, 0.1, inside));
  EXPECT_EQ(inside, Vec3(0.1, 0.2, 0.3));
}

// An outcome whose faces are all unstable (the +x end of an ellipsoid's hull, the outcome's faces within 20°
// of +x) is attracted: its residual t·(−m)/(0.1·L) from the best margin m among its faces
// (independently, the model's face_stability_margin of the particle rebuilt by evaluate()), and its rows
// equal central differences of that residual of the rebuilt point (h = 1e-6·L; the same structure on both
// sides; tolerance 1e-5 of the row's scale: the differences' truncation, the margin being smooth within one
// structure).
TEST(Attraction, AnOutcomeWithNoStableFaceIsPulledTowardStability) {
  // The built-in ellipsoid's hull, its points jittered (general position): its ends roll over.
  std::vector<Vec3> points = load_particle("ellipsoid:a=1,b=0.8,c=0.6,n=4", 1.0).hull.vertices;
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> jitter(-1e-3, 1e-3);
  for (Vec3& p : points) p += Vec3(jitter(rng), jitter(rng), jitter(rng));
  DesignOptions options;
  options.outcome_angle = 20 * std::numbers::pi / 180;
  DesignTarget target = parse_design_target("[[[1,0,0],0.1],[[0,0,1],0.45],[[0,0,-1],0.45]]", "ends");
  const ConvexHull hull = compute_convex_hull(points);
  assign_outcome_faces(target, hull, options.outcome_angle, "--outcome-angle");
  const detail::Point at = detail::evaluate(points, {}, Vec3::Zero(), "ends", target, options);
  ASSERT_EQ(at.achieved[0], 0.0);
  ASSERT_GT(at.attraction[0], 0.0);
  EXPECT_EQ(at.attraction[1], 0.0);
  double best = -INFINITY;
  for (const int f : at.target.outcomes[0].faces)
    best = std::max(best, at.particle.face_stability_margin[static_cast<std::size_t>(f)]);
  EXPECT_NEAR(at.attraction[0], 0.1 * -best / (0.1 * at.particle.length), 1e-15);
  const Eigen::MatrixXd rows = detail::attraction_rows(at, MassModel::fixed, ShapeFreedom::vertices);
  const double h = 1e-6 * at.particle.length;
  int compared = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      double side[2];
      bool same = true;
      for (int s = 0; s < 2; ++s) {
        std::vector<Vec3> q = points;
        q[i][k] += s == 0 ? h : -h;
        const detail::Point x = detail::evaluate(q, {}, Vec3::Zero(), "ends", target, options);
        same = same && x.particle.hull.faces.size() == at.particle.hull.faces.size() &&
               x.landscape.face_rest == at.landscape.face_rest;
        side[s] = x.attraction[0];
      }
      if (!same) continue;
      const double fd = (side[0] - side[1]) / (2 * h);
      const double scale = rows.row(0).cwiseAbs().maxCoeff();
      EXPECT_NEAR(rows(0, 3 * static_cast<Eigen::Index>(i) + k), fd, 1e-5 * scale)
          << "point " << i << " axis " << k;
      ++compared;
    }
  EXPECT_GT(compared, 100);
  EXPECT_EQ(rows.row(1).cwiseAbs().maxCoeff(), 0.0);
}

// With a margin floor m₀ (DesignOptions::min_margin) a stable outcome whose best face lies closer than m₀
// to the edge is drawn too: residual t·(m₀ − m)/(0.1·L), m the model's face_stability_margin of the rebuilt
// particle; an outcome whose best face has m ≥ m₀ gets none. The box's faces have m = 0.5 (a unit cube),
// L = (6/π)^(1/3); floors on either side of it.
TEST(Attraction, AMarginFloorDrawsAStableFaceInward) {
  const std::vector<Vec3> points = load_particle("box:x=1,y=1,z=1", 1.0).hull.vertices;
  const DesignTarget target = parse_design_target("[[[0,0,1],0.5],[[0,0,-1],0.5]]", "cube");
  DesignOptions options;
  options.outcome_angle = std::numbers::pi / 2;
  const double length = std::cbrt(6 / std::numbers::pi);
  for (const double floor : {0.0, 0.4, 0.5 / length, 0.6}) {
    options.min_margin = floor;
    const detail::Point at = detail::evaluate(points, {}, Vec3::Zero(), "cube", target, options);
    ASSERT_NEAR(at.particle.length, length, 1e-12);
    const double expected = std::max(0.0, 0.5 * (floor - 0.5 / length) / 0.1);
    EXPECT_NEAR(at.attraction[0], expected, 1e-12) << "floor " << floor;
    EXPECT_NEAR(at.attraction[1], expected, 1e-12) << "floor " << floor;
  }
  // A design that starts here with a floor above its faces' margins leaves them free (floor 0): a start
  // built that way is the user's, not drawn inward; one below them keeps its floor.
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  for (const double floor : {0.4, 0.6}) {
    options.min_margin = floor;
    const detail::DesignSetup setup = detail::design_setup(cube, options);
    const detail::Point start = detail::start_point(setup, target, options);
    const double kept = floor < 0.5 / length ? floor : 0.0;
    EXPECT_EQ(start.margin_floor, std::vector<double>(2, kept)) << "floor " << floor;
    EXPECT_EQ(start.attraction, std::vector<double>(2, 0.0)) << "floor " << floor;
    // Every trial point keeps the start's floors (not the option's): a step that shrinks the cube's bottom
    // face (its four bottom corners toward the axis) is scored against them.
    Eigen::VectorXd d = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(start.points.size()) + 3);
    for (std::size_t i = 0; i < start.points.size(); ++i)
      if (start.points[i].z() < 0)
        d.segment<2>(3 * static_cast<Eigen::Index>(i)) = -0.05 * start.points[i].head<2>();
    DesignStep step;
    double moved = 0;
    const std::optional<detail::Point> next =
        detail::trial_point(start, d, MassModel::follows_shape, ShapeFreedom::vertices, setup.bounds, "cube",
                            start.target, options, step, moved);
    ASSERT_TRUE(next.has_value());
    EXPECT_EQ(next->margin_floor, start.margin_floor) << "floor " << floor;
  }
}

// The design starts such outcomes: the ellipsoid's ends, 0.1 each within 20° of ±x, have no stable face at
// the start (probability 0, a zero gradient: without the attraction the design stalled there at 0.1); the
// design gives both ends a probability and gets closer than 0.1.
TEST(Attraction, TheDesignStartsOutcomesWithNoStableFace) {
  DesignOptions options;
  options.outcome_angle = 20 * std::numbers::pi / 180;
  options.freedom = parse_design_freedom("vertices");
  const DesignTarget target =
      parse_design_target("[[[1,0,0],0.1],[[-1,0,0],0.1],[[0,0,1],0.4],[[0,0,-1],0.4]]", "ends");
  const DesignResult r =
      design_quasi_static(load_particle("ellipsoid:a=1,b=0.8,c=0.6,n=4", 1.0), target, options);
  ASSERT_EQ(r.start[0], 0.0);
  ASSERT_EQ(r.start[1], 0.0);
  EXPECT_GT(r.achieved[0], 0.02);
  EXPECT_GT(r.achieved[1], 0.02);
  EXPECT_LT(r.max_error(), 0.08);
}

}  // namespace
}  // namespace repose
