// The quasi-static probabilities' exact gradient with respect to the centre of mass
// (include/repose/design/basin_gradient.hpp), against central finite differences of the landscape itself.
#include "repose/design/basin_gradient.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "../../src/poses/gauss_map.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace repose {
namespace {

// The particle with its centre of mass moved by `shift` (body frame), and its landscape.
struct Shifted {
  Particle particle;
  RestLandscape landscape;
};
Shifted shifted(const std::string& spec, const Particle& base, const Vec3& shift) {
  MeshOptions options;
  options.center_of_mass = base.input_offset + shift;
  Particle p = load_particle(spec, 1.0, options);
  RestLandscape land = compute_rest_landscape(p);
  return {std::move(p), std::move(land)};
}

// Each face of `base` found in `other` by its normal (the hulls are the same up to the translation).
std::vector<int> match_faces(const Particle& base, const Particle& other) {
  std::vector<int> out;
  for (const HullFace& f : base.hull.faces) {
    int best = -1;
    for (std::size_t g = 0; g < other.hull.faces.size(); ++g)
      if (other.hull.faces[g].normal.dot(f.normal) > 1 - 1e-12) best = static_cast<int>(g);
    out.push_back(best);
  }
  return out;
}

TEST(BasinGradient, ValuesAreTheLandscapesAndTheGradientIsTheCentralDifference) {
  int compared = 0;
  double worst = 0;
  for (const char* spec :
       {"irregular:seed=1,n=30", "irregular:seed=2,n=40", "irregular:seed=5,n=25", "box:x=1,y=1.3,z=1.7",
        "tetrahedron:edge=1", "cylinder:r=0.5,h=0.9,n=9", "ellipsoid:a=0.7,b=0.5,c=0.4,n=4"}) {
    const Particle base = load_particle(spec, 1.0);
    // Off-centre, so that no symmetry makes a derivative vanish by itself.
    const Vec3 offset = 0.03 * base.length * Vec3(1, -0.7, 0.4);
    const Shifted at = shifted(spec, base, offset);
    const BasinGradient grad = basin_com_gradient(at.particle, at.landscape);
    ASSERT_EQ(grad.probability.size(), at.landscape.basin_probability.size());
    for (std::size_t f = 0; f < grad.probability.size(); ++f)
      EXPECT_NEAR(grad.probability[f], at.landscape.basin_probability[f], 1e-13) << spec << " face " << f;
    const double h = 1e-6 * base.length;
    for (int k = 0; k < 3; ++k) {
      const Shifted plus = shifted(spec, base, offset + h * Vec3::Unit(k));
      const Shifted minus = shifted(spec, base, offset - h * Vec3::Unit(k));
      const std::vector<int> fp = match_faces(at.particle, plus.particle),
                             fm = match_faces(at.particle, minus.particle);
      for (std::size_t f = 0; f < grad.probability.size(); ++f) {
        ASSERT_GE(fp[f], 0);
        ASSERT_GE(fm[f], 0);
        const double fd = (plus.landscape.basin_probability[static_cast<std::size_t>(fp[f])] -
                           minus.landscape.basin_probability[static_cast<std::size_t>(fm[f])]) /
                          (2 * h);
        const double ad = grad.d_com[f][k];
        const double scale = std::abs(fd) + 1e-2 / base.length;
        worst = std::max(worst, std::abs(ad - fd) / scale);
        EXPECT_NEAR(ad, fd, 1e-6 * scale) << spec << " face " << f << " axis " << k;
        ++compared;
      }
    }
  }
  std::printf("compared %d, worst %g\n", compared, worst);
}

// A convex uniform solid from `points` (its hull's vertices), through the library's own loader: the centre of
// mass is its mass properties' centroid, not the tape's.
Shifted convex_solid(const std::vector<Vec3>& points) {
  MeshOptions options;
  options.inertia = InertiaModel::convex;
  Particle p = make_particle(TriangleMesh{points, {}}, "points", 1.0, options);
  RestLandscape land = compute_rest_landscape(p);
  return {std::move(p), std::move(land)};
}

// Each face of `base` in `other` by its normal, within `cos_tol` (the vertices moved a little).
std::vector<int> nearest_faces(const Particle& base, const Particle& other, double cos_tol) {
  std::vector<int> out;
  for (const HullFace& f : base.hull.faces) {
    int best = -1;
    double best_dot = 1 - cos_tol;
    for (std::size_t g = 0; g < other.hull.faces.size(); ++g) {
      const double d = other.hull.faces[g].normal.dot(f.normal);
      if (d > best_dot) best = static_cast<int>(g), best_dot = d;
    }
    out.push_back(best);
  }
  return out;
}

// The landscape's discrete structure in `base`'s numbering (faces matched by normal, vertices by their
// index in the point set): where every face rolls, and how every edge's arc is crossed or slid.
std::vector<std::array<int, 6>> structure(const Shifted& x, const std::vector<int>& face_of_base) {
  std::vector<int> base_face(x.particle.hull.faces.size(), -1);
  for (std::size_t f = 0; f < face_of_base.size(); ++f)
    if (face_of_base[f] >= 0) base_face[static_cast<std::size_t>(face_of_base[f])] = static_cast<int>(f);
  auto face = [&](int f) { return f < 0 ? -1 : base_face[static_cast<std::size_t>(f)]; };
  auto vertex = [&](int v) { return v < 0 ? -1 : x.particle.hull.source_index[static_cast<std::size_t>(v)]; };
  std::vector<std::array<int, 6>> out;
  for (std::size_t f = 0; f < base_face.size(); ++f)
    out.push_back({0, base_face[f], face(x.landscape.face_rest[f]), 0, 0, 0});
  for (const auto& e : x.landscape.gauss_map->edges)
    out.push_back({1, std::min(vertex(e.a), vertex(e.b)), std::max(vertex(e.a), vertex(e.b)),
                   vertex(e.cross_to), e.top_inside ? face(e.low_face) : -2, e.saddle});
  std::sort(out.begin(), out.end());
  return out;
}

// Points in general position on a lumpy sphere (radius 1 ± 0.25), for hulls of a few dozen vertices.
std::vector<Vec3> random_points(unsigned seed, int count) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> radius(0.75, 1.25);
  std::vector<Vec3> out;
  for (int i = 0; i < count; ++i)
    out.push_back(radius(rng) * Vec3(normal(rng), normal(rng), normal(rng)).normalized());
  return out;
}

// Random convex hulls (every face a triangle in general position, so that moving one vertex keeps every
// face): each face's derivative with respect to each coordinate of each hull vertex, the centre of mass the
// moved solid's centroid, equals the five-point central difference of the landscape of the hull rebuilt with
// that vertex moved by ±h, ±2h (h = 4e-5·L). Why that stencil: a basin summed from many pieces carries
// round-off up to ~1e-13, so a difference over h has noise ~1e-13/h — 1e-7 at h = 1e-6·L, above the
// tolerance's floor (measured: the worst error falls as 1/h, 7.6e-6 at h = 2.5e-6·L, 3.6e-7 at 4e-5·L) —
// while the stencil's truncation error is O(h⁴) (~3e-18). Tolerance: 1e-6 of |fd| + 0.01/L (the
// centre-of-mass test's). A coordinate whose stencil changes the landscape's structure (a topology change
// within 2h, where the probabilities are not differentiable) is skipped and counted: 42 of 471 here.
TEST(BasinGradient, VertexDerivativesAreTheCentralDifferenceOfTheRebuiltHull) {
  int compared = 0, skipped = 0, coordinates = 0;
  double worst = 0;
  for (const unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u}) {
    const Shifted at = convex_solid(random_points(seed, 40));
    const BasinGradient grad = basin_gradient(at.particle, at.landscape, MassModel::follows_shape);
    const ConvexHull& hull = at.particle.hull;
    for (const HullFace& f : hull.faces) ASSERT_EQ(f.loop.size(), 3u) << seed;
    const Shifted base = convex_solid(hull.vertices);
    const auto base_structure = structure(base, nearest_faces(at.particle, base.particle, 1e-12));
    const double h = 4e-5 * at.particle.length;
    for (std::size_t i = 0; i < hull.vertices.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        ++coordinates;
        bool same = true;
        // The probabilities of `at`'s faces with vertex i moved by s·h along axis k.
        auto moved = [&](double s) {
          std::vector<Vec3> points = hull.vertices;
          points[i][k] += s * h;
          const Shifted x = convex_solid(points);
          const std::vector<int> match = nearest_faces(at.particle, x.particle, 1e-5);
          same = same && x.particle.hull.faces.size() == hull.faces.size() &&
                 structure(x, match) == base_structure;
          std::vector<double> p;
          for (const int f : match)
            p.push_back(f >= 0 ? x.landscape.basin_probability[static_cast<std::size_t>(f)] : NAN);
          return p;
        };
        const std::vector<double> p1 = moved(1), m1 = moved(-1), p2 = moved(2), m2 = moved(-2);
        if (!same) {
          ++skipped;
          continue;
        }
        for (std::size_t f = 0; f < hull.faces.size(); ++f) {
          const double fd = (8 * (p1[f] - m1[f]) - (p2[f] - m2[f])) / (12 * h);
          const double ad =
              grad.d_vertices(static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(3 * i) + k);
          const double scale = std::abs(fd) + 1e-2 / at.particle.length;
          worst = std::max(worst, std::abs(ad - fd) / scale);
          EXPECT_NEAR(ad, fd, 1e-6 * scale)
              << "seed " << seed << " face " << f << " vertex " << i << " axis " << k;
          ++compared;
        }
      }
    }
  }
  std::printf(
      "compared %d derivatives; %d of %d coordinates skipped (structure changes within 2h); worst %g\n",
      compared, skipped, coordinates, worst);
  EXPECT_LT(skipped, coordinates / 8);  // the comparison covers most coordinates
}

// The built-in ellipsoid's mirror plane sends flows onto unstable balances (landscape.hpp, "Ties"): with such
// routes in the map, the replay still gives the landscape's values face for face.
TEST(BasinGradient, AMapWithBalanceRoutesIsReplayedFaceForFace) {
  const Particle ellipsoid = load_particle("ellipsoid:a=0.625,b=0.5,c=0.285,n=10", 1.0);
  const RestLandscape land = compute_rest_landscape(ellipsoid);
  int balances = 0;
  for (const auto& r : land.gauss_map->routes) balances += r.balance;
  ASSERT_GT(balances, 0);
  const BasinGradient grad = basin_com_gradient(ellipsoid, land);
  for (std::size_t f = 0; f < grad.probability.size(); ++f)
    EXPECT_NEAR(grad.probability[f], land.basin_probability[f], 1e-13) << "face " << f;
}

}  // namespace
}  // namespace repose
