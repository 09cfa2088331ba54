// The quasi-static design (include/repose/design/design.hpp), checked by repose's own Monte Carlo of
// quasi-static rolling rather than by the exact basins it optimises; and the face planes' chain rule
// (src/design/face_planes.hpp) against central differences.
#include "repose/design/design.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "../../src/design/face_planes.hpp"
#include "repose/error.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace repose {
namespace {

// A uniform convex solid from points, with the given centre of mass (input frame) if any.
Particle convex(const std::vector<Vec3>& points, std::optional<Vec3> com = std::nullopt) {
  MeshOptions options;
  options.inertia = InertiaModel::convex;
  options.center_of_mass = com;
  return make_particle(TriangleMesh{points, {}}, "points", 1.0, options);
}

// Each outcome's frequency among `samples` uniformly random body-frame down directions, rolled one by one
// (quasi_static_rest_face: the rolling rules step by step, not the basins' areas), faces assigned to outcomes
// as the design assigns them. The last entry: faces of no outcome.
std::vector<double> sampled(const Particle& p, DesignTarget target, double angle, int samples) {
  const RestLandscape land = compute_rest_landscape(p);
  assign_outcome_faces(target, p.hull, angle, "--outcome-angle");
  std::vector<int> outcome_of(p.hull.faces.size(), static_cast<int>(target.outcomes.size()));
  for (std::size_t o = 0; o < target.outcomes.size(); ++o)
    for (const int f : target.outcomes[o].faces)
      outcome_of[static_cast<std::size_t>(f)] = static_cast<int>(o);
  std::vector<double> count(target.outcomes.size() + 1, 0);
  std::mt19937_64 rng(2026);
  std::normal_distribution<double> normal;
  int vertex = 0;
  for (int i = 0; i < samples; ++i) {
    const Vec3 down(normal(rng), normal(rng), normal(rng));
    const int face = quasi_static_rest_face(p, land, down, vertex);
    count[static_cast<std::size_t>(outcome_of[static_cast<std::size_t>(face)])] += 1;
  }
  for (double& c : count) c /= samples;
  return count;
}

// The design as a particle of its own: its hull's vertices and its centre of mass, read back as a user would.
Particle built(const DesignResult& r) { return convex(r.vertices, r.center_of_mass); }

std::string normals_json(const std::vector<Vec3>& normals, const std::vector<double>& p) {
  std::string s = "[";
  for (std::size_t k = 0; k < normals.size(); ++k) {
    char item[160];
    std::snprintf(item, sizeof item, "%s[[%.17g, %.17g, %.17g], %.17g]", k ? ", " : "", normals[k][0],
                  normals[k][1], normals[k][2], p[k]);
    s += item;
  }
  return s + "]";
}

// A pentagonal prism (radius 0.5, half-length 0.35) with pyramid tips at ±0.9 on its axis: the binomial
// prisms' kind of start (convex_dice's have pointed ends, so that only the sides are outcomes).
std::vector<Vec3> tipped_prism() {
  std::vector<Vec3> out;
  for (const double z : {-0.35, 0.35})
    for (int k = 0; k < 5; ++k)
      out.emplace_back(0.5 * std::cos(2 * std::numbers::pi * k / 5),
                       0.5 * std::sin(2 * std::numbers::pi * k / 5), z);
  out.emplace_back(0, 0, -0.9);
  out.emplace_back(0, 0, 0.9);
  return out;
}

// The acceptance: the cube with 0.4 on one face and 0.12 on each other, and the pentagonal prism with
// the binomial target (1, 4, 6, 4, 1)/16 over its sides, designed (vertices and centre of mass, the default
// bounds), are within 0.005 of every target by 10⁶ sampled drops. Tolerance: 0.005 is the issue's; the
// sampling's standard error is at most 0.0005 (binomial, p = 0.5), so a design 0.004 off would still pass
// with probability ~0.98 and one 0.006 off fail by 2 standard errors — the exact basins' residual is what
// the design prints (≤ 1e-3 here), far inside.
TEST(DesignQuasiStatic, CubeAndBinomialPrismMeetTheirTargetsBySampledDrops) {
  const double angle = 30 * std::numbers::pi / 180;
  DesignOptions options;
  options.outcome_angle = angle;
  {
    const std::vector<Vec3> normals = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
    const std::vector<double> p = {0.4, 0.12, 0.12, 0.12, 0.12, 0.12};
    const DesignTarget target = parse_design_target(normals_json(normals, p), "cube");
    const DesignResult r = design_quasi_static(load_particle("box:x=1,y=1,z=1", 1.0), target, options);
    EXPECT_TRUE(r.reached()) << r.stop << " " << r.max_error();
    const std::vector<double> mc = sampled(built(r), target, angle, 1000000);
    for (std::size_t o = 0; o < p.size(); ++o) EXPECT_NEAR(mc[o], p[o], 0.005) << "cube outcome " << o;
    EXPECT_LT(mc.back(), 0.005);
  }
  {
    std::vector<Vec3> normals;
    for (int k = 0; k < 5; ++k) {
      const double a = 2 * std::numbers::pi * (0.1 + k / 5.0);  // side k's outward normal: between corners
      normals.emplace_back(std::cos(a), std::sin(a), 0);
    }
    const std::vector<double> p = {6 / 16.0, 4 / 16.0, 1 / 16.0, 1 / 16.0, 4 / 16.0};
    const DesignTarget target = parse_design_target(normals_json(normals, p), "prism");
    // The sides must change a lot (the 1/16 faces shrink): within the default 0.15·L move the design stalls
    // at 0.0023, stated as its best achievable; 0.3·L lets it through.
    options.max_vertex_move = 0.3;
    const DesignResult r = design_quasi_static(convex(tipped_prism()), target, options);
    EXPECT_TRUE(r.reached()) << r.stop << " " << r.max_error();
    const std::vector<double> mc = sampled(built(r), target, angle, 1000000);
    for (std::size_t o = 0; o < p.size(); ++o) EXPECT_NEAR(mc[o], p[o], 0.005) << "prism outcome " << o;
    EXPECT_LT(mc.back(), 0.005);
  }
}

// Plane by plane (--vary faces, the centre of mass the solid's): a unit cube asked for 0.3 on ±z and 0.1 on
// each side becomes a box shorter along z (the planes moved: its height below 0.9 of the start's), still a
// box of six faces, and lands as asked by 10⁶ drops rolled one by one (the same tolerance as above).
TEST(DesignQuasiStatic, FacePlanesMoveToFlattenABox) {
  const double angle = 30 * std::numbers::pi / 180;
  DesignOptions options;
  options.outcome_angle = angle;
  options.freedom = parse_design_freedom("faces");
  const std::vector<Vec3> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  const std::vector<double> p = {0.3, 0.3, 0.1, 0.1, 0.1, 0.1};
  const DesignTarget target = parse_design_target(normals_json(normals, p), "flat box");
  const DesignResult r = design_quasi_static(load_particle("box:x=1,y=1,z=1", 1.0), target, options);
  ASSERT_TRUE(r.reached()) << r.stop << " " << r.max_error();
  double low = INFINITY, high = -INFINITY;
  for (const Vec3& v : r.vertices) low = std::min(low, v.z()), high = std::max(high, v.z());
  EXPECT_LT(high - low, 0.9);
  EXPECT_EQ(r.vertices.size(), 8u);
  const std::vector<double> mc = sampled(built(r), target, angle, 1000000);
  for (std::size_t o = 0; o < p.size(); ++o) EXPECT_NEAR(mc[o], p[o], 0.005) << "outcome " << o;
}

// A fine hull moves as a smooth deformation (the Sobolev metric, DesignOptions::smoothing): a 1,442-vertex
// ellipsoid designed for 0.35 / 0.65 on ±z (every face to the nearer pole) reaches the tolerance; with every
// vertex moving on its own (smoothing 0) the same design stalls at ~0.02, its tiny faces folding at every
// step. (On the 362-vertex one both reach ~1e-4: the metric matters as the hull gets finer.)
TEST(DesignQuasiStatic, AFineHullMovesAsASmoothDeformation) {
  DesignOptions options;
  options.outcome_angle = std::numbers::pi / 2;
  const DesignTarget target = parse_design_target("[[[0,0,1],0.35],[[0,0,-1],0.65]]", "poles");
  const Particle ellipsoid = load_particle("ellipsoid:a=1,b=0.8,c=0.6,n=12", 1.0);
  ASSERT_GT(ellipsoid.hull.vertices.size(), 1000u);
  const DesignResult r = design_quasi_static(ellipsoid, target, options);
  EXPECT_TRUE(r.reached()) << r.stop << " " << r.max_error();
  ASSERT_LE(r.history.size(), 5u);
  options.smoothing = 0;
  options.max_iterations = 10;  // twice what the smooth design took
  const DesignResult rough = design_quasi_static(ellipsoid, target, options);
  EXPECT_GT(rough.max_error(), 2 * options.tolerance) << rough.stop;
}

// The printability bounds hold: with every face at least 0.15·L² (the start's smallest is 0.177·L², so the
// bound is the option's) the pentagonal prism's 1/16 sides cannot shrink as freely as the binomial target
// would have them, and no face of the result is smaller than the bound. (The step holds faces at the bound,
// FlatFaces.ThePrintabilityBoundsHoldTheStep; here the design still meets the target, converged.)
TEST(DesignQuasiStatic, TheMinimumFaceBoundHolds) {
  std::vector<Vec3> normals;
  for (int k = 0; k < 5; ++k) {
    const double a = 2 * std::numbers::pi * (0.1 + k / 5.0);
    normals.emplace_back(std::cos(a), std::sin(a), 0);
  }
  const DesignTarget target =
      parse_design_target(normals_json(normals, {6 / 16.0, 4 / 16.0, 1 / 16.0, 1 / 16.0, 4 / 16.0}), "prism");
  const Particle start = convex(tipped_prism());
  DesignOptions options;
  options.max_vertex_move = 0.3;
  options.min_face_area = 0.15;
  double smallest = INFINITY;
  for (const HullFace& f : start.hull.faces) smallest = std::min(smallest, f.area);
  ASSERT_GT(smallest, options.min_face_area * start.length * start.length);
  const DesignResult r = design_quasi_static(start, target, options);
  const Particle design = built(r);
  const double bound = options.min_face_area * start.length * start.length;
  double least = INFINITY;
  for (const HullFace& f : design.hull.faces) {
    EXPECT_GE(f.area, bound * (1 - 1e-6));
    least = std::min(least, f.area);
  }
  EXPECT_TRUE(r.reached()) << r.stop << " " << r.max_error();
  std::printf("stop %s, max error %g, smallest face %g of the bound\n", r.stop.c_str(), r.max_error(),
              least / bound);
}

// An unreachable target gets the best achievable answer, said so, in bounded time: the cube's centre of mass
// alone cannot give 0.4 on one face and 0.12 on each other (by symmetry the four sides stay equal and moving
// along the axis trades the bottom against the top).
// The history's count of stable faces is the design's: the last step's count equals the stable faces of
// the design read back as a particle (its own landscape), and the cube started with six.
TEST(DesignQuasiStatic, TheHistoryCountsTheDesignsStableFaces) {
  const DesignTarget target = parse_design_target(
      "[[[0,0,-1],0.4],[[0,0,1],0.12],[[1,0,0],0.12],[[-1,0,0],0.12],[[0,1,0],0.12],[[0,-1,0],0.12]]", "t");
  const DesignResult r = design_quasi_static(load_particle("box:x=1,y=1,z=1", 1.0), target);
  ASSERT_FALSE(r.history.empty());
  const Particle design = built(r);
  const RestLandscape land = compute_rest_landscape(design);
  int stable = 0;
  for (std::size_t f = 0; f < land.face_rest.size(); ++f) stable += land.face_rest[f] == static_cast<int>(f);
  EXPECT_EQ(r.history.back().stable_faces, stable);
  EXPECT_GE(stable, 6);
}

TEST(DesignQuasiStatic, AnUnreachableTargetStopsWithItsBestAchievable) {
  DesignOptions options;
  options.freedom = parse_design_freedom("center-of-mass");
  const DesignTarget target = parse_design_target(
      "[[[0,0,-1],0.4],[[0,0,1],0.12],[[1,0,0],0.12],[[-1,0,0],0.12],[[0,1,0],0.12],[[0,-1,0],0.12]]", "t");
  const DesignResult r = design_quasi_static(load_particle("box:x=1,y=1,z=1", 1.0), target, options);
  EXPECT_FALSE(r.reached());
  EXPECT_NE(r.stop, "converged");
  EXPECT_GT(r.max_error(), 0.01);
  EXPECT_LT(r.max_error(), 0.1);  // yet much better than the start's 0.233
  EXPECT_LE(r.history.size(), static_cast<std::size_t>(options.max_iterations));
}

TEST(DesignQuasiStatic, FreedomAndOptionErrorsNameTheOption) {
  EXPECT_THROW(parse_design_freedom("vertices+faces"), Error);
  EXPECT_THROW(parse_design_freedom("com"), Error);
  EXPECT_EQ(parse_design_freedom("faces+center-of-mass").shape, ShapeFreedom::faces);
  DesignOptions bad;
  bad.max_vertex_move = -1;
  const DesignTarget target = parse_design_target("{\"fair\": [[0,0,1],[0,0,-1]]}", "t");
  try {
    design_quasi_static(load_particle("box:x=1,y=1,z=1", 1.0), target, bad);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--max-move"), std::string::npos) << e.what();
  }
  // A tolerance of 0 could never be met (the descent would run all its iterations), a negative margin floor
  // means nothing: each is named.
  for (const auto& [option, set] : std::vector<std::pair<std::string, void (*)(DesignOptions&)>>{
           {"--tolerance", [](DesignOptions& o) { o.tolerance = 0; }},
           {"--min-margin", [](DesignOptions& o) { o.min_margin = -0.01; }}}) {
    DesignOptions options;
    set(options);
    try {
      design_quasi_static(load_particle("box:x=1,y=1,z=1", 1.0), target, options);
      ADD_FAILURE() << "no error for " << option;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(option), std::string::npos) << e.what();
    }
  }
}

// The face planes' chain rule: on a simple polytope (tangent planes of an ellipsoid at random points: three
// faces at every vertex), the probabilities' derivatives with respect to each plane's three numbers (through
// the vertices, plane_columns) equal five-point central differences of the landscape rebuilt from the moved
// planes (h = 4e-5 of |p|; tolerances as BasinGradient's vertex test, whose noise argument they share).
TEST(DesignFacePlanes, PlaneDerivativesAreTheCentralDifferenceOfTheRebuiltPolytope) {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  std::vector<Vec3> planes;
  for (int k = 0; k < 14; ++k) {
    const Vec3 u = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const Vec3 x(0.6 * u[0], 0.5 * u[1], 0.4 * u[2]);  // on the ellipsoid
    const Vec3 n = Vec3(u[0] / 0.6, u[1] / 0.5, u[2] / 0.4).normalized();
    planes.push_back(n / n.dot(x));
  }
  const auto corners = detail::plane_vertices(planes);
  ASSERT_TRUE(corners);
  // The start's centre of mass fixed at the planes' origin (MassModel::fixed), so that only the planes move.
  const Particle at = convex(*corners, Vec3::Zero());
  const RestLandscape land = compute_rest_landscape(at);
  for (std::size_t v = 0; v < at.hull.vertices.size(); ++v)
    ASSERT_EQ(at.hull.neighbors(static_cast<int>(v)).size(), 3u);
  const BasinGradient grad = basin_gradient(at, land, MassModel::fixed);
  const Eigen::MatrixXd columns = detail::plane_columns(grad.d_vertices, at.hull, -at.input_offset, planes);
  int compared = 0, skipped = 0;
  double worst = 0;
  for (std::size_t f = 0; f < planes.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const double h = 4e-5 * planes[f].norm();
      bool same = true;
      auto moved = [&](double s) {
        std::vector<Vec3> q = planes;
        q[f][k] += s * h;
        const Particle x = convex(*detail::plane_vertices(q), Vec3::Zero());
        const RestLandscape l = compute_rest_landscape(x);
        same = same && x.hull.faces.size() == at.hull.faces.size();
        std::vector<double> p(at.hull.faces.size(), NAN);
        for (std::size_t a = 0; a < at.hull.faces.size(); ++a)
          for (std::size_t b = 0; b < x.hull.faces.size(); ++b)
            if (x.hull.faces[b].normal.dot(at.hull.faces[a].normal) > 1 - 1e-5) p[a] = l.basin_probability[b];
        std::vector<int> rest = l.face_rest;
        return std::make_pair(p, rest);
      };
      const auto p1 = moved(1), m1 = moved(-1), p2 = moved(2), m2 = moved(-2);
      if (!same || p1.second != land.face_rest || m1.second != land.face_rest ||
          p2.second != land.face_rest || m2.second != land.face_rest) {
        ++skipped;
        continue;
      }
      for (std::size_t a = 0; a < at.hull.faces.size(); ++a) {
        const double fd = (8 * (p1.first[a] - m1.first[a]) - (p2.first[a] - m2.first[a])) / (12 * h);
        const double ad = columns(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(3 * f) + k);
        const double scale = std::abs(fd) + 1e-2 * planes[f].norm();
        worst = std::max(worst, std::abs(ad - fd) / scale);
        EXPECT_NEAR(ad, fd, 1e-6 * scale) << "face " << a << " plane " << f << " axis " << k;
        ++compared;
      }
    }
  }
  std::printf("compared %d, skipped %d of %zu, worst %g\n", compared, skipped, 3 * planes.size(), worst);
  EXPECT_LT(skipped, static_cast<int>(planes.size()));
}

}  // namespace
}  // namespace repose
