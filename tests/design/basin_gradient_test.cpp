// The quasi-static probabilities' exact gradient with respect to the centre of mass
// (include/repose/design/basin_gradient.hpp), against central finite differences of the landscape itself.
#include "repose/design/basin_gradient.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
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
