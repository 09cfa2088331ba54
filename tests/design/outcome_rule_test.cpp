// How a design assigns faces to outcomes as its faces turn (DesignOptions::follow_outcome_normals,
// convex_dice's rule) and the stability-margin floor (DesignOptions::min_margin), checked on Baktash et al.'s
// own binomial 5-prism start (data/experiments/baktash2025) by repose's quasi-static Monte Carlo rather than
// by the exact basins the design optimises.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "repose/design/design.hpp"
#include "repose/design/design_json.hpp"
#include "repose/design/design_report.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace repose {
namespace {

std::string baktash(const std::string& name) {
  return std::string(REPOSE_SOURCE_DIR) + "/data/experiments/baktash2025/initial/" + name;
}

DesignTarget read_target(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return parse_design_target(text.str(), path);
}

// Their example's rule: every face to the nearest outcome normal (180°), the centre of mass a uniform part's,
// no move bound (theirs has none); and ours: the outcomes' normals following their faces, a 0.02·L margin.
DesignOptions their_rule() {
  DesignOptions o;
  o.freedom = parse_design_freedom("vertices");
  o.outcome_angle = std::numbers::pi;
  o.max_vertex_move = 1;
  o.follow_outcome_normals = true;
  o.min_margin = 0.02;
  return o;
}

Particle uniform(const std::string& path) {
  MeshOptions mesh;
  mesh.inertia = InertiaModel::convex;
  return load_particle(path, 1.0, mesh);
}

Particle built(const DesignResult& r) {
  MeshOptions options;
  options.inertia = InertiaModel::convex;
  options.center_of_mass = r.center_of_mass;
  return make_particle(r.mesh, "design", 1.0, options);
}

// Each outcome's frequency among `samples` uniformly random down directions rolled one by one
// (quasi_static_rest_face), the faces assigned to the design's outcome normals.
std::vector<double> sampled(const Particle& p, DesignTarget target, int samples) {
  const RestLandscape land = compute_rest_landscape(p);
  assign_outcome_faces(target, p.hull, std::numbers::pi, "--outcome-angle");
  std::vector<int> outcome_of(p.hull.faces.size(), 0);
  for (std::size_t o = 0; o < target.outcomes.size(); ++o)
    for (const int f : target.outcomes[o].faces)
      outcome_of[static_cast<std::size_t>(f)] = static_cast<int>(o);
  std::vector<double> count(target.outcomes.size(), 0);
  std::mt19937_64 rng(50);
  std::normal_distribution<double> normal;
  int vertex = 0;
  for (int i = 0; i < samples; ++i) {
    const Vec3 down(normal(rng), normal(rng), normal(rng));
    count[static_cast<std::size_t>(
        outcome_of[static_cast<std::size_t>(quasi_static_rest_face(p, land, down, vertex))])] += 1;
  }
  for (double& c : count) c /= samples;
  return count;
}

// From their initial 5-prism (every side 0.2) toward (1, 4, 6, 4, 1)/16 with their rule, the design meets
// the target (their printed design: 0.0086 by the exact basins, docs/inverse-design.md), by 10⁶ sampled drops
// within 0.005 of every outcome (the tolerance; the sampling's standard error ≤ 0.0005). Each
// outcome's normal at the design is one of its faces' normals (the rule), and every outcome's face keeps
// its centre of mass's projection at least ~0.02·L inside, by the model's own margins of the rebuilt part
// (the floor is a residual, so it may give up a little: 2 % of it).
TEST(OutcomeRule, BinomialPrismFromTheirStartMeetsTheTargetWithNormalsFollowingTheFaces) {
  const DesignTarget target = read_target(baktash("Binom4__normal_probs_B4.json"));
  const DesignResult r = design_quasi_static(uniform(baktash("Binom4__5_prism.obj")), target, their_rule());
  ASSERT_TRUE(r.reached()) << r.stop << " " << r.max_error();
  const Particle design = built(r);
  DesignTarget followed = target;
  for (std::size_t o = 0; o < target.outcomes.size(); ++o) followed.outcomes[o].normal = r.outcome_normals[o];
  const std::vector<double> mc = sampled(design, followed, 1000000);
  for (std::size_t o = 0; o < mc.size(); ++o)
    EXPECT_NEAR(mc[o], target.outcomes[o].probability, 0.005) << "outcome " << o;
  assign_outcome_faces(followed, design.hull, std::numbers::pi, "--outcome-angle");
  for (std::size_t o = 0; o < followed.outcomes.size(); ++o) {
    double nearest = INFINITY, margin = -INFINITY;
    for (const int f : followed.outcomes[o].faces) {
      const HullFace& face = design.hull.faces[static_cast<std::size_t>(f)];
      nearest = std::min(nearest, (face.normal - r.outcome_normals[o]).norm());
      margin = std::max(margin, design.face_stability_margin[static_cast<std::size_t>(f)]);
    }
    EXPECT_LT(nearest, 1e-9) << "outcome " << o << "'s normal is no face's";
    EXPECT_GT(margin / design.length, 0.98 * 0.02) << "outcome " << o;
    EXPECT_NEAR(r.outcome_margin[o], margin / design.length, 1e-12) << "outcome " << o;
  }
  // The report labels each rest pose with the outcome of the nearest followed normal (by the target's own
  // normals the 4/16 faces, turned to ±63°, would be the 1/16 outcome's).
  const std::string page =
      design_report_html("binom4", target, their_rule(), r, design_json("binom4", target, their_rule(), r));
  const std::string open = "<script id=\"repose-data\" type=\"application/json\">";
  const std::size_t from = page.find(open) + open.size();
  const nlohmann::json data = nlohmann::json::parse(page.substr(from, page.find("</script>", from) - from));
  ASSERT_EQ(data["poses"].size(), 5u);
  for (const auto& pose : data["poses"]) {
    const Vec3 n(pose["down_normal_body"][0].get<double>(), pose["down_normal_body"][1].get<double>(),
                 pose["down_normal_body"][2].get<double>());
    std::size_t nearest = 0;
    for (std::size_t o = 1; o < r.outcome_normals.size(); ++o)
      if (n.dot(r.outcome_normals[o]) > n.dot(r.outcome_normals[nearest])) nearest = o;
    EXPECT_EQ(pose["outcome"].get<int>(), static_cast<int>(nearest)) << "face " << pose["face"];
  }
}

// With the target's normals fixed (the default), the design's outcome normals are the target's, bit for bit.
TEST(OutcomeRule, FixedNormalsStayTheTargets) {
  const DesignTarget target = parse_design_target("[[[0,0,-1],0.4],[[0,0,1],0.6]]", "ends");
  DesignOptions options;
  options.outcome_angle = std::numbers::pi / 2;
  const DesignResult r = design_quasi_static(load_particle("box:x=1,y=1,z=1", 1.0), target, options);
  ASSERT_EQ(r.outcome_normals.size(), 2u);
  EXPECT_EQ(r.outcome_normals[0], target.outcomes[0].normal);
  EXPECT_EQ(r.outcome_normals[1], target.outcomes[1].normal);
}

}  // namespace
}  // namespace repose
