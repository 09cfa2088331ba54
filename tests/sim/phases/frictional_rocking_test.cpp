// Rocking in the frictional contact phase (issue 34): a block rocking on its base loses energy at each
// impact by Housner's coefficient and its impacts come at the times of Housner's series, an accumulation of
// ever smaller impacts (Zeno) that must end; a block that rocks while it slides keeps the momentum balance of
// sliding friction. References worked out here (Housner 1963: the rigid block rocking about its base edges,
// plastic impacts, no slip). SI units, g = 9.81.
#include <gtest/gtest.h>

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <repose/model/particle.hpp>
#include <repose/sim/settle.hpp>
#include <vector>

#include "gravity.hpp"

namespace repose {
namespace {

// A rectangular block with half-width w (across its rocking edges) and half-height c, rocking about one base
// edge then the other (Housner): R = sqrt(w² + c²), α = atan(w/c), I_O = 4/3·m·R², p² = m·g·R/I_O. Rotating
// by φ about an edge raises the centre of mass to R·cos(α − φ), so ½·I_O·φ'² + m·g·R·cos(α − φ) is constant
// between impacts. At an impact on the other edge (plastic, no slip) the angular momentum about that edge is
// kept: φ' is multiplied by r = 1 − 3/2·sin²α.
struct Housner {
  double alpha, p2, r;
  Housner(double w, double c)
      : alpha(std::atan(w / c)),
        p2(3 * test::kGravitySI / (4 * std::hypot(w, c))),
        r(1 - 1.5 * std::pow(std::sin(alpha), 2)) {}

  // Released at rest at tilt φ0: the time to fall flat, ∫0^φ0 dφ / sqrt(2p²·(cos(α − φ0) − cos(α − φ))). With
  // φ = φ0 − s² the turning point's inverse square root goes: cos(α − φ0) − cos(α − φ) =
  // 2·sin(α − φ0 + s²/2)·sin(s²/2), and the integrand 2 / sqrt(2p²·sin(α − φ0 + s²/2)·sinc(s²/2)) is smooth.
  double fall_time(double phi0) const {
    boost::math::quadrature::tanh_sinh<double> quad;
    return quad.integrate(
        [&](double s) {
          const double x = 0.5 * s * s, sinc = x > 0 ? std::sin(x) / x : 1.0;
          return 2 / std::sqrt(2 * p2 * std::sin(alpha - phi0 + x) * sinc);
        },
        0.0, std::sqrt(phi0));
  }
  double flat_speed(double phi0) const {
    return std::sqrt(2 * p2 * (std::cos(alpha - phi0) - std::cos(alpha)));
  }
  // From flat at angular speed ω about an edge up to the turning tilt, where cos(α − top) = cos α + ω²/(2p²),
  // and back down onto the other edge: twice the fall from the top.
  double swing_time(double omega) const {
    return 2 * fall_time(alpha - std::acos(std::cos(alpha) + omega * omega / (2 * p2)));
  }
};

// A 1 × 1 × 3 block on its end, tilted by φ0 = α/10 about x (standing on one base edge), released at rest;
// μ = 5 (no slip), E = 0, no damping. Housner: r = 0.85; the k-th impact at t_k = fall + Σ_{j<k}
// swing(r^j·ω1) with the kinetic energy multiplied by r² at each. The engine's impacts are located on
// Dormand–Prince's dense output at its tolerance: measured within 6e-7 s of the series over 35 impacts (the
// quadrature is good to 1e-12); tolerance 1e-5·sqrt(L/g) = 4e-6 s. The kinetic energy after an impact is r²
// times that before by the impact law's algebra; the energies are taken with the potential energy of the flat
// pose, where the impact is located to ~1e-12·L of height: tolerance 10·m·g·1e-12·L. The rocking ends at the
// rest test, when the kinetic energy is below m·g·1e-7·L (the contact band's potential energy): the run rests
// at the first impact that leaves less, with Housner's remaining swings, a convergent series, still to come.
TEST(FrictionalRocking, BlockRocksToHousnersSeriesAndItsAccumulationEnds) {
  const Particle block = load_particle("box:x=1,y=1,z=3", 1000.0);
  const double m = block.mass.mass, L = block.length, tau = std::sqrt(L / test::kGravitySI);
  const Housner h(0.5, 1.5);
  ASSERT_NEAR(h.r, 0.85, 1e-12);
  const double phi0 = 0.1 * h.alpha;
  SettleParams p;
  p.friction = 5;
  p.restitution = 0;
  const SettleResult res = settle(block, p, Quat(Eigen::AngleAxisd(phi0, Vec3::UnitX())));
  ASSERT_EQ(res.status, Status::rest);
  const double flat = m * test::kGravitySI * 1.5, rest_energy = m * test::kGravitySI * 1e-7 * L;
  const double inertia_edge = 4.0 / 3 * m * (0.25 + 2.25);
  // Housner's impacts up to the first that leaves less than the rest energy.
  std::vector<double> times{h.fall_time(phi0)};
  double omega = h.flat_speed(phi0);
  while (0.5 * inertia_edge * std::pow(h.r * omega, 2) > rest_energy) {
    omega *= h.r;
    times.push_back(times.back() + h.swing_time(omega));
  }
  ASSERT_EQ(res.impacts.size(), times.size()) << "one impact per Housner impact, and the accumulation ends";
  for (std::size_t k = 0; k < times.size(); ++k) {
    const ImpactRecord& imp = res.impacts[k];
    EXPECT_NEAR(imp.t, times[k], 1e-5 * tau) << "impact " << k;
    EXPECT_NEAR(imp.energy_after - flat, h.r * h.r * (imp.energy_before - flat),
                1e-11 * m * test::kGravitySI * L)
        << "impact " << k;
  }
  // The rest comes at the last impact; Housner's remaining swings after it sum to less than a geometric
  // series of the next swing.
  omega *= h.r;
  const double remaining = h.swing_time(omega) / (1 - h.r);
  EXPECT_GE(res.time, times.back() - 1e-5 * tau);
  EXPECT_LE(res.time, times.back() + remaining);
  EXPECT_NEAR(res.orientation.angularDistance(Quat::Identity()), 0, 1e-6) << "flat on its end";
}

// The same block standing on its end, started sliding at v0 = 1.5 along y with a rocking spin ω_x, μ = 0.2
// (below 1/3: sliding alone would not tip it), E = 0.5. However it rocks, the wall's normal impulse over the
// run (forces and impacts) is m·g·t, since the block starts and ends with no vertical velocity, and while the
// base slides forward friction's impulse is μ times it: the block stops at t = v0/(μg) exactly. Zeno's
// accumulation of small rocking impacts is closed by a normal impulse (frictional_impulses.cpp) once the
// leaving edge would turn back within 1e-10·L; its pull, at most the centre of mass's vertical velocity then
// (below sqrt(2·g·1e-10·L) = 6e-5 m/s), shifts the stop by at most that over g per closing: tolerance
// 2e-5 s. Before the closing, a spin of 1e-4 rad/s rocked at the integrator's noise without end.
TEST(FrictionalRocking, BlockRockingWhileItSlidesStopsAtTheMomentumBalance) {
  const Particle block = load_particle("box:x=1,y=1,z=3", 1000.0);
  const double mu = 0.2, v0 = 1.5;
  for (const double spin : {1e-6, 1e-4, 1e-2, 1e-1}) {
    SettleParams p;
    p.friction = mu;
    p.restitution = 0.5;
    p.velocity = Vec3(0, v0, 0);
    p.spin = Vec3(spin, 0, 0);
    const SettleResult r = settle(block, p, Quat::Identity());
    ASSERT_EQ(r.status, Status::rest) << spin;
    EXPECT_NEAR(r.time, v0 / (mu * test::kGravitySI), 2e-5) << "spin " << spin;
    EXPECT_NEAR(r.com.x(), 0, 1e-12) << "no sideways motion";
    EXPECT_LT(r.impacts.size(), 100u) << "spin " << spin << ": the accumulation of impacts ends";
    EXPECT_LT(r.steps, 200) << "spin " << spin;
    EXPECT_NEAR(r.orientation.angularDistance(Quat::Identity()), 0, 1e-6) << "spin " << spin;
  }
}

}  // namespace
}  // namespace repose
