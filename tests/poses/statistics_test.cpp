// Rest-pose statistics against values the library does not compute: symmetry (a cube's 6 faces, a regular
// tetrahedron's 4, the mirror pairs of faces of a 1 × 2 × 3 box), the closed-form quasi-static basins of a
// box (which the overdamped dynamic method must reproduce), and the cylinder's h/sqrt(h² + d²).
//
// Every comparison is a goodness-of-fit test (χ² or exact binomial) at a stated false-alarm rate α, on a
// fixed seed, so a test passes or fails deterministically; α is the probability that a correct engine fails
// it on a seed drawn at random (seed 1 was not chosen to pass). The χ² and binomial tail probabilities are
// computed here (regularized incomplete gamma, log-gamma sums), and checked against published tables first.
//
// Power: each test states the bias it detects with probability 0.9 at the optimised build's N (noncentral χ²:
// λ90 = 26.8 for 1 degree of freedom at α = 1e-4, 29.5 at α = 3.3e-5, 30.2 at 2.5e-5, 32.3 for 3 at
// 1e-4, 35.9 for 5 at 1e-4; a bias moving probability δ from one outcome to another has λ = N·δ²·(1/p_a +
// 1/p_b)). The sanitizer build (NDEBUG undefined) runs the engine ~200x slower: the same tests run at N/40
// (dynamic) or N/100 (quasi-static), with the power that leaves (also stated).
// Measured at the reduced N (built without NDEBUG): every p ≥ 0.015 (smallest: tetrahedron, dynamic,
// counts 99 69 64 68).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "repose/poses/ensemble.hpp"
#include "repose/poses/landscape.hpp"
#include "repose/poses/rest_poses.hpp"

namespace {

using namespace repose;

#ifdef NDEBUG
constexpr std::uint64_t kDynamicDivisor = 1, kQuasiStaticDivisor = 1;
#else
constexpr std::uint64_t kDynamicDivisor = 40, kQuasiStaticDivisor = 100;
#endif

// ---- tail probabilities
// ------------------------------------------------------------------------------------

// Regularized upper incomplete gamma Q(a, x) = Γ(a, x)/Γ(a): series for x < a + 1, Lentz's continued
// fraction otherwise (Numerical Recipes §6.2). Relative accuracy ~1e-14, far below what a test decision
// needs.
double gamma_q(double a, double x) {
  if (x <= 0) return 1.0;
  const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1) {
    double term = 1.0 / a, sum = term;
    for (double ap = a; std::abs(term) > 1e-17 * std::abs(sum);) {
      ap += 1;
      term *= x / ap;
      sum += term;
    }
    return 1.0 - sum * std::exp(log_prefactor);
  }
  constexpr double tiny = 1e-300;
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1) < 1e-16) break;
  }
  return std::exp(log_prefactor) * h;
}

// P(χ²_dof > x).
double chi_square_tail(double x, int dof) { return gamma_q(0.5 * dof, 0.5 * x); }

// Two-sided exact binomial p-value: 2·min(P(X ≤ k), P(X ≥ k)) for X ~ Bin(n, p), capped at 1.
double binomial_two_sided(std::uint64_t k, std::uint64_t n, double p) {
  const auto log_pmf = [&](std::uint64_t i) {
    return std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) + i * std::log(p) +
           (n - i) * std::log1p(-p);
  };
  double lower = 0, upper = 0;
  for (std::uint64_t i = 0; i <= k; ++i) lower += std::exp(log_pmf(i));
  for (std::uint64_t i = k; i <= n; ++i) upper += std::exp(log_pmf(i));
  return std::min(1.0, 2 * std::min(lower, upper));
}

// Pearson's χ² of `counts` against probabilities `expected` (which sum to 1).
double chi_square(const std::vector<std::uint64_t>& counts, const std::vector<double>& expected) {
  std::uint64_t n = 0;
  for (const std::uint64_t c : counts) n += c;
  double x = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const double e = expected[i] * static_cast<double>(n);
    x += (static_cast<double>(counts[i]) - e) * (static_cast<double>(counts[i]) - e) / e;
  }
  return x;
}

// The tails must reproduce the printed tables before any decision rests on them: χ² upper quantiles from
// Abramowitz & Stegun, Table 26.8 (also NIST/SEMATECH e-Handbook §1.3.6.7.4), and a binomial tail summed by
// hand.
TEST(Statistics, TailProbabilitiesMatchPublishedTables) {
  struct Row {
    double x;
    int dof;
    double tail;
  };
  for (const Row& r : {Row{3.841, 1, 0.05}, Row{6.635, 1, 0.01}, Row{10.828, 1, 0.001}, Row{7.815, 3, 0.05},
                       Row{11.345, 3, 0.01}, Row{16.266, 3, 0.001}, Row{11.070, 5, 0.05},
                       Row{15.086, 5, 0.01}, Row{20.515, 5, 0.001}, Row{63.691, 40, 0.01}})
    EXPECT_NEAR(chi_square_tail(r.x, r.dof) / r.tail, 1.0, 2e-3) << r.x << " dof " << r.dof;  // 4-5 digits
  // X ~ Bin(10, 1/2): P(X ≤ 2) = (1 + 10 + 45)/1024; two-sided doubles it.
  EXPECT_NEAR(binomial_two_sided(2, 10, 0.5), 2 * 56.0 / 1024, 1e-14);
  EXPECT_NEAR(binomial_two_sided(8, 10, 0.5), 2 * 56.0 / 1024, 1e-14);
  EXPECT_EQ(binomial_two_sided(5, 10, 0.5), 1.0);
  // X ~ Bin(3, 0.2): P(X = 3) = 0.008, P(X ≥ 3) is the smaller tail.
  EXPECT_NEAR(binomial_two_sided(3, 3, 0.2), 0.016, 1e-15);
}

// ---- running drops
// -----------------------------------------------------------------------------------------

struct Drops {
  Particle particle;
  RestLandscape landscape;
  RestPoseCatalog catalog;
  EnsembleTally tally;
};

// `damping_ratio` ζ sets C = ζ·m·sqrt(g·L³) (the CLI's --damping-ratio); `dt` is in units of sqrt(L/g).
Drops drop(const std::string& spec, PoseMethod method, std::uint64_t n, double damping_ratio = 0.05,
           double dt = 5e-3, bool decide_early = true) {
  Drops d{load_particle(spec, 1.0), {}, {}, {}};
  d.landscape = compute_rest_landscape(d.particle);
  d.catalog = catalog_rest_poses(d.particle, d.landscape, 0);
  EnsembleOptions o;
  o.seed = 1;
  o.drops = {0, n};
  o.method = method;
  o.decide_early = decide_early;
  const double length = d.particle.length;
  o.params.damping = damping_ratio * d.particle.mass.mass * std::sqrt(o.params.gravity * std::pow(length, 3));
  o.params.dt = dt * std::sqrt(length / o.params.gravity);
  d.tally = run_ensemble(d.particle, d.landscape, d.catalog, o);
  EXPECT_EQ(d.tally.status_counts[static_cast<int>(Status::rest)], n) << spec << ": every drop must rest";
  return d;
}

// The catalogue pose whose body-frame down normal is `normal` (used only to name the faces).
int pose_with_normal(const Drops& d, const Vec3& normal) {
  for (std::size_t p = 0; p < d.catalog.poses.size(); ++p)
    if ((d.catalog.poses[p].down_normal_body - normal).norm() < 1e-9) return static_cast<int>(p);
  ADD_FAILURE() << "no pose with down normal " << normal.transpose();
  return 0;
}

std::vector<std::uint64_t> counts(const Drops& d) {
  std::vector<std::uint64_t> c;
  for (const PoseTally& t : d.tally.poses) c.push_back(t.count);
  return c;
}

std::string show(const std::vector<std::uint64_t>& c) {
  std::string s;
  for (const std::uint64_t x : c) s += std::to_string(x) + " ";
  return s;
}

// χ² goodness of fit of every pose's count against `expected`, rejected at p < alpha.
void expect_fit(const std::string& what, const std::vector<std::uint64_t>& c,
                const std::vector<double>& expected, double alpha) {
  const double x = chi_square(c, expected);
  const int dof = static_cast<int>(c.size()) - 1;
  const double p = chi_square_tail(x, dof);
  std::printf("%s: counts %s chi2 = %.3f (%d dof), p = %.4f\n", what.c_str(), show(c).c_str(), x, dof, p);
  EXPECT_GE(p, alpha) << what << ": counts " << show(c) << "chi2 = " << x << " with " << dof << " dof";
}

// Face i of a box of half-sizes h, the closed-form quasi-static basin (docs/rest-poses.md): from a corner v
// the down direction d moves along the great circle away from v̂ until a second corner touches (d reaches a
// coordinate plane: the box rolls on an edge), then along that plane's arc to the face its side of the saddle
// leads to. The saddle of the edge parallel to axis k, between faces i and j, is at (h_i e_i + h_j e_j)
// normalised. So in one octant face i's basin is the spherical quadrilateral v̂, s_ij, e_i, s_ik; face i
// touches 4 octants, and P_i = 4·area/(4π). The area of a spherical triangle is Van Oosterom & Strackee's
// (IEEE Trans. Biomed. Eng. 30:125, 1983) tan(E/2) = |a·(b×c)| / (1 + a·b + b·c + c·a).
double box_face_probability(const std::array<double, 3>& h, int i) {
  const auto triangle = [](const Vec3& a, const Vec3& b, const Vec3& c) {
    return 2 * std::atan2(std::abs(a.dot(b.cross(c))), 1 + a.dot(b) + b.dot(c) + c.dot(a));
  };
  const int j = (i + 1) % 3, k = (i + 2) % 3;
  const Vec3 corner = Vec3(h[0], h[1], h[2]).normalized();
  Vec3 face = Vec3::Zero(), saddle_j = Vec3::Zero(), saddle_k = Vec3::Zero();
  face[i] = 1;
  saddle_j[i] = saddle_k[i] = h[i];
  saddle_j[j] = h[j];
  saddle_k[k] = h[k];
  const double area =
      triangle(corner, saddle_j.normalized(), face) + triangle(corner, face, saddle_k.normalized());
  return area / std::numbers::pi;
}

// ---- symmetry
// ----------------------------------------------------------------------------------------------

// A cube lands on each face with probability 1/6: the Haar measure is invariant under the cube's rotations,
// which permute the faces. χ² with 5 dof at α = 1e-4 (critical value 25.74).
// Dynamic: N = 12,000 (ζ = 0.05, dt = 5e-3·sqrt(L/g), ~4 s on 2 cores); power 0.9 against a bias moving
// δ = 0.016 of probability from one face to another (λ = 12Nδ²); sanitizer N = 300: δ = 0.10.
// Measured (seed 1): counts 2022 2001 1982 2067 1974 1954, χ² = 4.05, p = 0.54.
TEST(Statistics, CubeFacesEquallyLikelyDynamic) {
  const Drops d = drop("box:x=1,y=1,z=1", PoseMethod::dynamic, 12000 / kDynamicDivisor);
  ASSERT_EQ(d.catalog.poses.size(), 6u);
  expect_fit("cube, dynamic", counts(d), std::vector<double>(6, 1.0 / 6), 1e-4);
}

// Quasi-static rolling of sampled drops: N = 400,000 (0.2 s): δ = 0.0027; sanitizer N = 4,000: δ = 0.027.
// Measured: counts 66611 66860 66644 66951 66317 66617, χ² = 3.70, p = 0.59.
TEST(Statistics, CubeFacesEquallyLikelyQuasiStatic) {
  const Drops d = drop("box:x=1,y=1,z=1", PoseMethod::quasi_static, 400000 / kQuasiStaticDivisor);
  ASSERT_EQ(d.catalog.poses.size(), 6u);
  expect_fit("cube, quasi-static", counts(d), std::vector<double>(6, 1.0 / 6), 1e-4);
}

// A regular tetrahedron: 1/4 per face. χ² with 3 dof at α = 1e-4 (critical value 21.11).
// Dynamic N = 12,000 (~3 s): power 0.9 against δ = 0.018 (λ = 8Nδ²); sanitizer N = 300: δ = 0.12.
// Measured: counts 3014 2933 3062 2991, χ² = 2.87, p = 0.41.
TEST(Statistics, TetrahedronFacesEquallyLikelyDynamic) {
  const Drops d = drop("tetrahedron:edge=1", PoseMethod::dynamic, 12000 / kDynamicDivisor);
  ASSERT_EQ(d.catalog.poses.size(), 4u);
  expect_fit("tetrahedron, dynamic", counts(d), std::vector<double>(4, 0.25), 1e-4);
}

// Quasi-static, N = 400,000: δ = 0.0032; sanitizer N = 4,000: δ = 0.032. Measured: counts 100030 99971
// 99835 100164, χ² = 0.56, p = 0.91.
TEST(Statistics, TetrahedronFacesEquallyLikelyQuasiStatic) {
  const Drops d = drop("tetrahedron:edge=1", PoseMethod::quasi_static, 400000 / kQuasiStaticDivisor);
  ASSERT_EQ(d.catalog.poses.size(), 4u);
  expect_fit("tetrahedron, quasi-static", counts(d), std::vector<double>(4, 0.25), 1e-4);
}

// A 1 × 2 × 3 box at the default damping (ζ = 0.05), where inertia makes the dynamic probabilities differ
// from the quasi-static ones (docs/rest-poses.md) and nothing is known in closed form, except that the box's
// half-turns (about each axis) exchange the faces of each pair ±x, ±y, ±z, so the two faces of a pair are
// equally likely. Given the pair's total m, the +face's count is Bin(m, 1/2): an exact two-sided binomial
// test per pair at α = 1e-4/3 (Bonferroni: at most 1e-4 over the three).
// N = 16,000 (~5 s on 2 cores; m ≈ 10,200, 3,900, 1,800): power 0.9 against a shift of the +face's share of
// its pair by 0.027, 0.043, 0.064; sanitizer N = 400: 0.17, 0.27, 0.40.
// Measured: ±x 4971/5127 p = 0.12, ±y 2056/2004 p = 0.42, ±z 940/902 p = 0.39.
TEST(Statistics, BoxMirrorFacesEquallyLikelyDynamic) {
  const Drops d = drop("box:x=1,y=2,z=3", PoseMethod::dynamic, 16000 / kDynamicDivisor);
  ASSERT_EQ(d.catalog.poses.size(), 6u);
  for (int axis = 0; axis < 3; ++axis) {
    const Vec3 e = Vec3::Unit(axis);
    const std::uint64_t plus = d.tally.poses[pose_with_normal(d, e)].count;
    const std::uint64_t minus = d.tally.poses[pose_with_normal(d, -e)].count;
    const double p = binomial_two_sided(plus, plus + minus, 0.5);
    std::printf("box 1x2x3, dynamic, axis %d: +%llu -%llu, p = %.4f\n", axis,
                static_cast<unsigned long long>(plus), static_cast<unsigned long long>(minus), p);
    EXPECT_GE(p, 1e-4 / 3) << "axis " << axis << ": " << plus << " on +, " << minus << " on -";
  }
}

// ---- closed forms
// ------------------------------------------------------------------------------------------

// The closed form itself: the six basins of any box sum to 1, a cube's are 1/6, and for 1 × 2 × 3 they are
// the values docs/rest-poses.md quotes. (The library's exact landscape is checked against the same closed
// form in landscape_test.cpp; here it is only the reference for the sampled tests below.)
TEST(Statistics, BoxClosedFormIsAPartition) {
  for (const auto& h : {std::array<double, 3>{0.5, 1, 1.5}, std::array<double, 3>{0.5, 0.5, 0.5},
                        std::array<double, 3>{0.1, 3, 7}}) {
    double total = 0;
    for (int i = 0; i < 3; ++i) total += 2 * box_face_probability(h, i);
    EXPECT_NEAR(total, 1.0, 1e-14);
  }
  EXPECT_NEAR(box_face_probability({0.5, 0.5, 0.5}, 2), 1.0 / 6, 1e-15);
  EXPECT_NEAR(box_face_probability({0.5, 1, 1.5}, 0), 0.322511, 5e-7);
  EXPECT_NEAR(box_face_probability({0.5, 1, 1.5}, 1), 0.121364, 5e-7);
  EXPECT_NEAR(box_face_probability({0.5, 1, 1.5}, 2), 0.0561256, 5e-8);
}

std::vector<double> box_expected(const Drops& d, const std::array<double, 3>& h) {
  std::vector<double> e(d.catalog.poses.size(), 0.0);
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {1.0, -1.0})
      e[pose_with_normal(d, sign * Vec3::Unit(axis))] = box_face_probability(h, axis);
  return e;
}

// Overdamped, C·ω balances the weight's moment and ω is parallel to it: the down direction follows the
// steepest descent of the centre-of-mass height, which is the quasi-static rolling whose basins have the
// closed form above. So at large damping the dynamic method must give the closed-form probabilities. ζ = 3:
// the inertial relaxation time I/C ≈ 0.05·sqrt(L/g) is ~1/100 of a roll's duration (measured: ζ = 1 and
// ζ = 3 differ in 1 of 2,000 drops). dt = 1e-2·sqrt(L/g) keeps the implicit step's fixed-point iteration
// contracting (dt·C/2I ≈ 0.1). Every drop is simulated to rest (decide_early off), so the pose comes from the
// engine alone, not from the library's quasi-static rolling that early decision consults.
// χ² with 5 dof at α = 1e-4 against the closed form. N = 10,000 (~5 s on 2 cores): power 0.9 against moving
// δ = 0.013 of probability between a large (0.32) and a small (0.056) face (λ = Nδ²(1/0.32 + 1/0.056));
// sanitizer N = 250: δ = 0.083. Not enough to see the default damping's departure from the limit (ζ = 0.05:
// 0.251 and 0.115 for the ±y and ±z pairs against 0.243 and 0.112; χ² = 20.8 at N = 40,000), which would
// need N ≈ 90,000; it catches a dynamic method that does not reduce to steepest descent when inertia is
// negligible (a lever arm, a frame or a torque direction wrong).
// Measured: counts 3162 3235 1267 1209 569 558, χ² = 3.76, p = 0.59.
TEST(Statistics, BoxOverdampedDynamicMatchesClosedForm) {
  const Drops d = drop("box:x=1,y=2,z=3", PoseMethod::dynamic, 10000 / kDynamicDivisor, 3.0, 1e-2, false);
  ASSERT_EQ(d.catalog.poses.size(), 6u);
  expect_fit("box 1x2x3, overdamped dynamic", counts(d), box_expected(d, {0.5, 1, 1.5}), 1e-4);
}

// The same closed form for quasi-static rolling of sampled drops, N = 400,000: power 0.9 against
// δ = 0.0021 between the 0.32 and the 0.056 faces; sanitizer N = 4,000: δ = 0.021. Measured: counts 129005
// 129270 48586 48483 22101 22555, χ² = 6.58, p = 0.25.
TEST(Statistics, BoxQuasiStaticMatchesClosedForm) {
  const Drops d = drop("box:x=1,y=2,z=3", PoseMethod::quasi_static, 400000 / kQuasiStaticDivisor);
  ASSERT_EQ(d.catalog.poses.size(), 6u);
  expect_fit("box 1x2x3, quasi-static", counts(d), box_expected(d, {0.5, 1, 1.5}), 1e-4);
}

// A cylinder of diameter d released from rest on its rim falls on its side when its axis is tilted past the
// angle at which the centre of mass is above the rim: P(side) = h/sqrt(h² + d²) for a uniform axis direction
// (Yong & Mahadevan, Am. J. Phys. 79:1195, 2011, for drops without bounce; repose's impacts do not bounce).
// A polygonal cylinder differs by its rim: the exact quasi-static value of a 64-gon is within 3e-4 and of a
// 256-gon within 1e-5 of it (docs/rest-poses.md), negligible beside the tests' standard errors (≥ 0.0011).
// Exact two-sided binomial tests at α = 1e-4/4 each (Bonferroni: 1e-4 over the four).
// Quasi-static, 256-gon, N = 200,000 per h/d: power 0.9 against a shift of 0.0058 (h/d = 0.354) or 0.0056
// (h/d = 1); sanitizer N = 2,000: 0.058, 0.056.
// Dynamic (ζ = 0.05, the default; dt = 5e-3·sqrt(L/g)), 64-gon, N = 5,000 per h/d (~2 s each on 2 cores):
// 0.037, 0.035; sanitizer N = 125: 0.23, 0.22.
// Measured: quasi-static side 0.3331 and 0.7068 (p = 0.86, 0.78), dynamic 0.3386 and 0.7144 (p = 0.44,
// 0.26).
TEST(Statistics, CylinderSideMatchesClosedForm) {
  for (const double ratio : {1 / std::sqrt(8.0), 1.0}) {  // 1/sqrt(8): the "fair three-way coin", side 1/3
    const double expected = ratio / std::sqrt(ratio * ratio + 1);
    for (const PoseMethod method : {PoseMethod::quasi_static, PoseMethod::dynamic}) {
      const bool dynamic = method == PoseMethod::dynamic;
      const std::string spec = "cylinder:r=0.5,h=" + std::to_string(ratio) + (dynamic ? ",n=64" : ",n=256");
      const std::uint64_t n = dynamic ? 5000 / kDynamicDivisor : 200000 / kQuasiStaticDivisor;
      const Drops d = drop(spec, method, n);
      std::uint64_t side = 0;
      for (std::size_t p = 0; p < d.catalog.poses.size(); ++p)
        if (std::abs(d.catalog.poses[p].down_normal_body.z()) < 0.5) side += d.tally.poses[p].count;
      const double p = binomial_two_sided(side, n, expected);
      std::printf("%s %s: side %llu of %llu = %.4f, expected %.4f, p = %.4f\n", spec.c_str(),
                  to_string(method), static_cast<unsigned long long>(side),
                  static_cast<unsigned long long>(n), static_cast<double>(side) / static_cast<double>(n),
                  expected, p);
      EXPECT_GE(p, 1e-4 / 4) << spec << " " << to_string(method) << ": side " << side << " of " << n
                             << ", expected " << expected;
    }
  }
}

}  // namespace
