// The paper's scenario files (scenarios/paper/*.json) are the one definition of each case: these tests load
// them and check the behaviour section 3 of the paper describes; `repose paper` runs the same files.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <repose/error.hpp>
#include <repose/model/particle.hpp>
#include <repose/model/scenario.hpp>
#include <repose/sim/settle.hpp>
#include <string>
#include <utility>
#include <vector>

#include "../support/equilibrium_oracle.hpp"

namespace repose {
namespace {

std::string paper(const std::string& name) {
  return std::string(REPOSE_SOURCE_DIR) + "/scenarios/paper/" + name + ".json";
}

struct Outcome {
  Particle particle;
  SettleResult result;
};

// Rest heights are compared with closed forms to 1e-12·L: the engine sets the supporting face exactly flush
// (docs/method.md), so only round-off of the final rotation remains (measured ≤ 1.1e-16·L). This is a
// round-off margin, not 1 ulp; a face left tilted by 1e-10 rad, or the wrong face, fails.
constexpr double kFlush = 1e-12;

Outcome run_scenario(const std::string& name) {
  const Scenario s = load_scenario(paper(name));
  Particle p = load_particle(s.particle, s.density);
  SettleResult r = settle(p, s.params, s.orientation);
  return {std::move(p), r};
}

TEST(PaperScenarios, CylindersGoOppositeWays) {
  const Outcome base = run_scenario("cylinder-1106");
  const Outcome side = run_scenario("cylinder-1108");
  ASSERT_EQ(base.result.status, Status::rest);
  ASSERT_EQ(side.result.status, Status::rest);
  EXPECT_NEAR(base.result.com.z(), 0.335, kFlush * base.particle.length);  // on its base: h/2
  // On a side face: the apothem.
  EXPECT_NEAR(side.result.com.z(), 0.67 * std::cos(std::numbers::pi / 64), kFlush * side.particle.length);
}

TEST(PaperScenarios, TetrahedronGoesPointLineSurface) {
  const Outcome t = run_scenario("tetrahedron");
  ASSERT_EQ(t.result.status, Status::rest);
  ASSERT_EQ(t.result.phases.size(), 3u);
  EXPECT_EQ(t.result.phases[0].contact, ContactType::point);
  EXPECT_EQ(t.result.phases[1].contact, ContactType::line);
  EXPECT_EQ(t.result.phases[2].contact, ContactType::surface);
  EXPECT_NEAR(t.result.com.z(), std::sqrt(2.0 / 3.0) / 4, kFlush * t.particle.length);  // inradius a·√6/12
}

TEST(PaperScenarios, EllipsoidsRestAtTheMinimum) {
  const Outcome low = run_scenario("ellipsoid-c075");
  const Outcome high = run_scenario("ellipsoid-c150");
  for (const Outcome* o : {&low, &high}) {
    ASSERT_EQ(o->result.status, Status::rest);
    EXPECT_TRUE(o->result.smooth);
    // The lowest rest of the mesh, from its triangles' planes (the mesh is convex).
    const double lowest = oracle::lowest_rest_height(o->particle.mesh.vertices, o->particle.mesh.triangles);
    EXPECT_NEAR(o->result.com.z(), lowest, kFlush * o->particle.length);
  }
  EXPECT_LE(high.result.time, low.result.time);  // more damping settles sooner
}

TEST(PaperScenarios, IrregularParticleRestsOnIsolatedTips) {
  const Outcome g = run_scenario("irregular");
  ASSERT_EQ(g.result.status, Status::rest);
  EXPECT_EQ(g.result.rest, RestKind::points);
  EXPECT_GE(g.result.contact_points.size(), 3u);
  const oracle::RestCheck eq =
      oracle::check_rest(g.particle.mesh.vertices, g.result.orientation, g.result.com, g.particle.length);
  EXPECT_TRUE(eq.problem.empty()) << eq.problem;
  // The axis changes on the way: more than one line phase.
  int lines = 0;
  for (const Phase& ph : g.result.phases) lines += ph.contact == ContactType::line;
  EXPECT_GE(lines, 2);
}

TEST(ScenarioFile, RejectsTyposAndBadValues) {
  const auto message = [](const std::string& json) {
    try {
      parse_scenario(json, "case.json");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(R"({"particle": "box:x=1,y=1,z=1", "dampnig": 1})").find("unknown field 'dampnig'"),
            std::string::npos);
  EXPECT_NE(message(R"({"density": 1})").find("missing field 'particle'"), std::string::npos);
  EXPECT_NE(message(R"({"particle": 3})").find("'particle' must be a string"), std::string::npos);
  EXPECT_NE(message(R"({"particle": "box:x=1,y=1,z=1", "units": "imperial"})").find("units"),
            std::string::npos);
  EXPECT_NE(
      message(R"({"particle": "box:x=1,y=1,z=1", "orientation": "quat:0,0,0,0"})").find("zero quaternion"),
      std::string::npos);
  EXPECT_NE(message(R"({"particle": "box:x=1,y=1,z=1", "dt": -1})").find("dt"), std::string::npos);
  EXPECT_NE(message("{not json").find("case.json: invalid JSON"), std::string::npos);
  // Found by fuzz_scenario: a number too large for a double escaped as json::out_of_range.
  EXPECT_NE(message(R"({"particle": "box:x=1,y=1,z=1", "density": 1e400})").find("case.json: invalid JSON"),
            std::string::npos);
  EXPECT_EQ(message(R"({"particle": "box:x=1,y=1,z=1", "units": "cgs", "damping": 0.5})"), "accepted");
  EXPECT_NE(message(R"({"particle": "box:x=1,y=1,z=1", "integrator": "rk4"})")
                .find("case.json: unknown integrator 'rk4' (expected paper or adaptive)"),
            std::string::npos);
  EXPECT_NE(message(R"({"particle": "box:x=1,y=1,z=1", "tolerance": 0.1})").find("tolerance"),
            std::string::npos);
  // smooth: one of auto, on, off.
  for (const char* mode : {"auto", "on", "off"})
    EXPECT_EQ(message(std::string(R"({"particle": "box:x=1,y=1,z=1", "smooth": ")") + mode + "\"}"),
              "accepted")
        << mode;
  EXPECT_NE(message(R"({"particle": "box:x=1,y=1,z=1", "smooth": "maybe"})").find("smooth"),
            std::string::npos);
}

// The integrator and its tolerance are scenario fields; absent, the library's defaults.
TEST(ScenarioFile, ReadsTheIntegratorAndItsTolerance) {
  const Scenario s = parse_scenario(
      R"({"particle": "box:x=1,y=1,z=1", "integrator": "paper", "tolerance": 1e-9})", "s.json");
  EXPECT_EQ(s.params.integrator, Integrator::paper);
  EXPECT_EQ(s.params.tolerance, 1e-9);
  const Scenario d = parse_scenario(R"({"particle": "box:x=1,y=1,z=1"})", "d.json");
  EXPECT_EQ(d.params.integrator, SettleParams{}.integrator);
  EXPECT_EQ(d.params.tolerance, SettleParams{}.tolerance);
}

// A toss is a scenario too: velocity and spin as [x, y, z], restitution and friction as numbers.
TEST(ScenarioFile, ReadsATossAndRejectsMalformedVectors) {
  const Scenario s = parse_scenario(
      R"({"particle": "box:x=1,y=1,z=1", "velocity": [1, 0, 2], "spin": [0, 3, 0], "restitution": 0.4,
          "friction": 0.3})",
      "t.json");
  EXPECT_EQ(s.params.velocity, Vec3(1, 0, 2));
  EXPECT_EQ(s.params.spin, Vec3(0, 3, 0));
  EXPECT_EQ(s.params.restitution, 0.4);
  EXPECT_EQ(s.params.friction, 0.3);
  EXPECT_TRUE(std::isinf(parse_scenario(R"({"particle": "box:x=1,y=1,z=1"})", "d.json").params.friction));
  for (const char* bad : {R"({"particle": "box:x=1,y=1,z=1", "velocity": [1, 2]})",
                          R"({"particle": "box:x=1,y=1,z=1", "spin": "1,2,3"})",
                          R"({"particle": "box:x=1,y=1,z=1", "velocity": [1, "a", 2]})"}) {
    try {
      parse_scenario(bad, "t.json");
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("array of three numbers"), std::string::npos) << e.what();
    }
  }
  try {
    parse_scenario(R"({"particle": "box:x=1,y=1,z=1", "restitution": 2})", "t.json");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("restitution"), std::string::npos);
  }
}

// How the mesh is read is a scenario field too; absent, the library's defaults (a closed solid as it is).
TEST(ScenarioFile, ReadsTheMeshOptionsAndRejectsBadOnes) {
  EXPECT_EQ(parse_scenario(R"({"particle": "box:x=1,y=1,z=1"})", "d.json").mesh, MeshOptions{});
  const Scenario s = parse_scenario(
      R"({"particle": "grain.stl", "mesh_units": "mm", "inertia": "shell", "repair": true, "com": [1, 2, 3]})",
      "s.json");
  EXPECT_EQ(s.mesh_units, "mm");
  EXPECT_EQ(s.mesh.scale, 1e-3);
  EXPECT_EQ(s.mesh.inertia, InertiaModel::shell);
  EXPECT_TRUE(s.mesh.repair);
  EXPECT_FALSE(s.mesh.largest_component);
  EXPECT_TRUE(
      parse_scenario(R"({"particle": "g.stl", "largest_component": true})", "c.json").mesh.largest_component);
  EXPECT_EQ(s.mesh.center_of_mass, Vec3(1, 2, 3));
  // In cgs a millimetre is 0.1 of the run's length unit; an inch 2.54.
  EXPECT_EQ(
      parse_scenario(R"({"particle": "g.stl", "units": "cgs", "mesh_units": "mm"})", "c.json").mesh.scale,
      0.1);
  EXPECT_EQ(
      parse_scenario(R"({"particle": "g.stl", "units": "cgs", "mesh_units": "in"})", "c.json").mesh.scale,
      2.54);
  EXPECT_EQ(parse_scenario(R"({"particle": "g.stl", "scale": 0.25})", "c.json").mesh.scale, 0.25);
  for (const auto& [bad, names] : std::vector<std::pair<const char*, const char*>>{
           {R"({"particle": "g.stl", "mesh_units": "mm", "scale": 2})", "not both"},
           {R"({"particle": "g.stl", "mesh_units": "furlong"})", "mm, cm, m or in"},
           {R"({"particle": "g.stl", "mesh_units": ""})", "mesh_units"},
           {R"({"particle": "g.stl", "scale": -1})", "scale"},
           {R"({"particle": "g.stl", "scale": 0})", "scale"},
           {R"({"particle": "g.stl", "scale": "2"})", "scale"},
           {R"({"particle": "g.stl", "inertia": "hollow"})", "exact, convex or shell"},
           {R"({"particle": "g.stl", "repair": "yes"})", "true or false"},
           {R"({"particle": "g.stl", "com": [1, 2]})", "array of three numbers"}}) {
    try {
      parse_scenario(bad, "m.json");
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(names), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("m.json: ", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace repose
