// The frictional contact phase's balances (src/sim/phases/frictional_balance.cpp): a still body on an
// edge, or on a face whose stability margin is zero, is turned by the paper's edge-balance rule and goes over
// to the side its centre of mass is on; checked by symmetry and against the rotation about a fixed edge. SI
// units, g = 9.81.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <repose/model/particle.hpp>
#include <repose/poses/sampling.hpp>
#include <repose/sim/settle.hpp>
#include <string>
#include <vector>

#include "../../support/zero_margin_prism.hpp"
#include "gravity.hpp"

namespace repose {
namespace {

// How far inside the polygon of the hull vertices on the wall (within 1e-7·L of it) the centre of mass's
// projection lies at the final pose (negative: outside), from the mesh alone: the footprint's convex hull by
// Andrew's monotone chain and the least distance to its edges (an independent check of a stable rest, not
// the library's own face_stability_margin).
double rest_margin(const Particle& particle, const SettleResult& r) {
  std::vector<Vec2> foot;
  for (const Vec3& v : particle.hull.vertices) {
    const Vec3 w = r.com + r.orientation * v;
    if (w.z() <= 1e-7 * particle.length) foot.push_back(w.head<2>());
  }
  if (foot.size() < 3) return -INFINITY;
  std::sort(foot.begin(), foot.end(),
            [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  const auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Vec2> hull(2 * foot.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < foot.size(); ++i) {  // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], foot[i]) <= 0) --k;
    hull[k++] = foot[i];
  }
  for (std::size_t i = foot.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], foot[i]) <= 0) --k;
    hull[k++] = foot[i];
  }
  hull.resize(k - 1);  // counter-clockwise, the first point not repeated
  double margin = INFINITY;
  const Vec2 g = r.com.head<2>();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec2 a = hull[i], b = hull[(i + 1) % hull.size()];
    margin = std::min(margin, cross(a, b, g) / (b - a).norm());
  }
  return margin;
}

// The 5-sided prism of Baktash et al. 2025 (data/experiments/baktash2025) has a face (2) whose stability
// margin is 0 to round-off (-2e-12·L): its designers put the centre of mass on its boundary. Drop 36 of seed
// 1 tossed with E = 0.1 and μ = 0.1 (docs/experiments.md's toss model) comes to rest balanced on it: the
// forces hold it, the paper's test calls the face unstable. It is tipped off by the paper's rule for an edge
// balance and rests on a stable face; before, it stayed balanced until the frictional phase's time budget
// and the paper's phase then spun at one instant until the 20,000,000-step limit.
TEST(FrictionalContact, BalanceOnAFaceOfZeroMarginIsTippedOff) {
  const Particle prism = load_particle(
      std::string(REPOSE_SOURCE_DIR) + "/data/experiments/baktash2025/meshes/Binom4__opt_test.obj", 1.0);
  ASSERT_NEAR(prism.face_stability_margin[2], 0, 1e-9 * prism.length);
  const double L = prism.length;
  SettleParams p;
  p.restitution = 0.1;
  p.friction = 0.1;
  p.drop_height = 4 * L;
  p.damping = 0.05 * prism.mass.mass * std::sqrt(test::kGravitySI * L * L * L);
  const Toss toss =
      drop_toss(1, 36, {1.5 * std::sqrt(test::kGravitySI * L), 1.5 * std::sqrt(test::kGravitySI / L)});
  p.velocity = toss.velocity;
  p.spin = toss.spin;
  const SettleResult r = settle(prism, p, drop_orientation(1, 36));
  ASSERT_EQ(r.status, Status::rest);
  // At rest on a face that holds it: the centre of mass over the footprint by more than round-off.
  EXPECT_GT(rest_margin(prism, r), 1e-9 * L);
  EXPECT_LT(r.steps, 100000);
}

// A still body balanced on an edge goes over to the side its centre of mass leans to. A unit cube turned
// by π/4 ± 1e-12 about y stands on its bottom edge with its centre of mass 7e-13·L to one side: gravity's
// moment is below the still test's, so the rest check finds it still over the face on that side, which is
// not on the wall, and the paper's edge-balance rule turns it that way (tip_onto_face). By symmetry it must
// rest on that side: its centre of mass ends on the lean's side of the edge, half an edge (plus any slip)
// from it, never on the other.
TEST(FrictionalContact, StillOnAnEdgeGoesOverToTheSideItsCentreOfMassLeansTo) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1000.0);
  for (const double lean : {1e-12, -1e-12}) {
    const Quat q(Eigen::AngleAxisd(std::numbers::pi / 4 + lean, Vec3::UnitY()));
    // The edge on the wall: the lowest vertices (in the frame where the centre of mass is at x = 0).
    double lowest = INFINITY, edge_x = 0;
    for (const Vec3& v : cube.hull.vertices) lowest = std::min(lowest, (q * v).z());
    int on_edge = 0;
    for (const Vec3& v : cube.hull.vertices)
      if ((q * v).z() < lowest + 1e-9) edge_x += (q * v).x(), ++on_edge;
    ASSERT_EQ(on_edge, 2);
    edge_x /= on_edge;
    const double side = -edge_x;  // the centre of mass's offset from the edge
    ASSERT_GT(std::abs(side), 0);
    ASSERT_LT(std::abs(side), 1e-11);
    SettleParams p;
    p.friction = 0.5;
    const SettleResult r = settle(cube, p, q);
    ASSERT_EQ(r.status, Status::rest) << lean;
    const double offset = r.com.x() - edge_x;  // the run starts with the centre of mass at x = 0
    EXPECT_GT(offset * side, 0) << "lean " << lean << ": the cube went over to the other side";
    EXPECT_GT(std::abs(offset), 0.45) << "lean " << lean;
    EXPECT_NEAR(r.com.z(), 0.5, 1e-9);
  }
}

// A face whose stability margin is exactly 0: a triangular prism, cross-section A(0,0), B(1,0), C(2,1) in
// x–z, 1 deep in y. Its centroid's x is (0 + 1 + 2)/3 = 1, over the edge B of the face AB. Started at rest on
// AB it balances there; the paper's test calls the face unstable and the edge-balance rule tips it over the
// edge B (tip_off_balance), onto the face BC, over which its centre of mass stands: the centroid (1, 1/3)
// projects onto BC at 1/6 of its length from B, inside it. The topple about B from rest needs a friction
// ratio of at most 0.12 (rotation about a fixed edge: k = I_B/(m·d²) = 3, d = |BG| = 1/3, the horizontal and
// vertical accelerations of G are (g/k)·sinθ·(3cosθ − 2) and −(g/k)·(sin²θ + 2(1 − cosθ)·cosθ) up to 45°),
// and at μ = 2 the landing of BC cannot slip either (its impulse ratio is at most 1): B stays where it
// started, under the centre of mass, and the centre of mass ends at x = d·sin(π/4) (1e-6·L: the flush snap
// within the contact band). At μ = 0.3 the landing slips; the face is the same.
TEST(FrictionalContact, PrismOnAFaceOfZeroMarginTipsOverTheEdgeUnderItsCentreOfMass) {
  const Particle prism = test_shapes::zero_margin_prism();
  // The hull faces of AB (outward −z) and BC (outward (1, 0, −1)/√2), in the body frame.
  int ab = -1, bc = -1;
  for (std::size_t f = 0; f < prism.hull.faces.size(); ++f) {
    const Vec3 n = prism.hull.faces[f].normal;
    if (n.isApprox(-Vec3::UnitZ(), 1e-12)) ab = static_cast<int>(f);
    if (n.isApprox(Vec3(1, 0, -1).normalized(), 1e-12)) bc = static_cast<int>(f);
  }
  ASSERT_GE(ab, 0);
  ASSERT_GE(bc, 0);
  ASSERT_NEAR(prism.face_stability_margin[static_cast<std::size_t>(ab)], 0, 1e-12 * prism.length);
  for (const double mu : {0.3, 2.0}) {
    SettleParams p;
    p.friction = mu;
    const SettleResult r = settle(prism, p, Quat::Identity());
    ASSERT_EQ(r.status, Status::rest) << mu;
    EXPECT_EQ(r.rest_face, bc) << "mu " << mu;
    if (mu == 2.0) {
      EXPECT_NEAR(r.com.x(), std::sin(std::numbers::pi / 4) / 3, 1e-6 * prism.length);
    }
  }
}

}  // namespace
}  // namespace repose
