// The design target's forms, its checks, and its outcomes' faces (include/repose/design/target.hpp).
#include "repose/design/target.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "repose/error.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace repose {
namespace {

std::string error_of(const std::string& json) {
  try {
    parse_design_target(json, "t.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(DesignTarget, ReadsConvexDicePairsOutcomeObjectsAndFairLists) {
  const DesignTarget pairs = parse_design_target("[[[0, 0, -2], 0.25], [[1, 0, 0], 0.75]]", "t.json");
  ASSERT_EQ(pairs.outcomes.size(), 2u);
  EXPECT_EQ(pairs.outcomes[0].normal, Vec3(0, 0, -1));  // normalised
  EXPECT_EQ(pairs.outcomes[1].probability, 0.75);
  const DesignTarget named = parse_design_target(
      R"({"outcomes": [{"normal": [0, 1, 0], "probability": 0.4}, {"normal": [0, -1, 0], "probability": 0.6}]})",
      "t.json");
  ASSERT_EQ(named.outcomes.size(), 2u);
  EXPECT_EQ(named.outcomes[1].normal, Vec3(0, -1, 0));
  EXPECT_EQ(named.outcomes[0].probability, 0.4);
  const DesignTarget fair = parse_design_target(R"({"fair": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]})", "t.json");
  ASSERT_EQ(fair.outcomes.size(), 3u);
  for (const auto& o : fair.outcomes) EXPECT_EQ(o.probability, 1.0 / 3);
}

TEST(DesignTarget, BadTargetsGetOneLineErrorsNamingTheProblem) {
  EXPECT_NE(error_of("[[[0, 0, 1], 0.5], [[1, 0, 0], 0.4]]").find("sum to 0.9, not 1"), std::string::npos);
  EXPECT_NE(error_of("[[[0, 0, 1], 1.5], [[1, 0, 0], -0.5]]").find("outcome 1: probability 1.5"),
            std::string::npos);
  EXPECT_NE(error_of("[[[0, 0, 0], 1]]").find("outcome 1: the normal is zero"), std::string::npos);
  EXPECT_NE(error_of("[[[0, 0], 1]]").find("not three numbers"), std::string::npos);
  EXPECT_NE(error_of("[[[0, 0, 1], 0.5], [[0, 0, 2], 0.5]]").find("outcomes 1 and 2 have the same normal"),
            std::string::npos);
  EXPECT_NE(error_of("[[[0, 0, 1], \"half\"]]").find("the probability is not a number"), std::string::npos);
  EXPECT_NE(error_of("{\"fair\": [[0, 0, 1]").find("not valid JSON"), std::string::npos);
  EXPECT_NE(error_of("{\"faces\": []}").find("expected"), std::string::npos);
  EXPECT_NE(error_of("[]").find("no outcomes"), std::string::npos);
  for (const char* bad : {"[[[0, 0, 1], 0.5], [[1, 0, 0], 0.4]]", "[]", "{"}) {
    const std::string message = error_of(bad);
    EXPECT_EQ(message.rfind("design target t.json: ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// A cube's six faces are alike under its symmetries, so each rests with probability 1/6 exactly; a fair
// target over its six normals assigns each face to its own outcome.
TEST(DesignTarget, AFairCubeTargetGivesEachFaceItsOwnOutcome) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  DesignTarget target =
      parse_design_target(R"({"fair": [[1,0,0],[-1,0,0],[0,1,0],[0,-1,0],[0,0,1],[0,0,-1]]})", "cube.json");
  assign_outcome_faces(target, cube.hull, 10 * std::numbers::pi / 180, "--outcome-angle");
  for (const auto& o : target.outcomes) {
    ASSERT_EQ(o.faces.size(), 1u);
    EXPECT_NEAR(cube.hull.faces[static_cast<std::size_t>(o.faces[0])].normal.dot(o.normal), 1.0, 1e-12);
  }
  EXPECT_TRUE(target.unassigned_faces.empty());
  const std::vector<double> p = outcome_probabilities(target, compute_rest_landscape(cube).basin_probability);
  ASSERT_EQ(p.size(), 7u);
  for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(p[k], 1.0 / 6, 1e-12);
  EXPECT_EQ(p[6], 0.0);
}

// Faces beyond the angle belong to no outcome and count apart; a normal with no face near it is an error
// naming the nearest face's angle and the option that would accept it.
TEST(DesignTarget, FacesBeyondTheAngleAreUnassignedAndANormalWithNoFaceIsAnError) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  DesignTarget target = parse_design_target("[[[0, 0, 1], 0.5], [[0, 0, -1], 0.5]]", "t.json");
  assign_outcome_faces(target, cube.hull, 30 * std::numbers::pi / 180, "--outcome-angle");
  EXPECT_EQ(target.unassigned_faces.size(), 4u);
  const std::vector<double> p = outcome_probabilities(target, compute_rest_landscape(cube).basin_probability);
  EXPECT_NEAR(p[0], 1.0 / 6, 1e-12);
  EXPECT_NEAR(p[2], 4.0 / 6, 1e-12);

  DesignTarget tilted = parse_design_target("[[[0, 1, 1], 1]]", "t.json");  // 45° from two faces
  try {
    assign_outcome_faces(tilted, cube.hull, 30 * std::numbers::pi / 180, "--outcome-angle");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("is no outcome of this hull: its nearest face is 45 degrees away (at most 30: "
                           "--outcome-angle)"),
              std::string::npos)
        << message;
  }
}

}  // namespace
}  // namespace repose
