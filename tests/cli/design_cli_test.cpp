// `repose design` through the real executable: a design's files and JSON, and every class of bad input
// (a target that does not sum to 1, a normal that is no outcome, an unknown freedom, an option out of range)
// exiting 2 with one line naming it and no files written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.hpp"
#include "run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using repose::test::expect_bad_input;
using repose::test::parse_json;
using repose::test::run_cli;
using repose::test::shell_quote;

class DesignCli : public repose::test::TempDirTest {
 protected:
  std::string target(const std::string& name, const std::string& json) {
    const fs::path path = fs::path(dir_) / name;
    std::ofstream(path) << json;
    return shell_quote(path.string());
  }
  const std::string cube_target =
      "[[[0,0,-1],0.4],[[0,0,1],0.12],[[1,0,0],0.12],[[-1,0,0],0.12],[[0,1,0],0.12],[[0,-1,0],0.12]]";
};

TEST_F(DesignCli, ADesignWritesItsHullAndItsJsonAndMeetsTheTarget) {
  const std::string out = shell_quote(dir_.string() + "/out");
  const auto r = run_cli("design box:x=1,y=1,z=1 --target " + target("t.json", cube_target) + " --out " +
                         out + " --json");
  const nlohmann::json j = parse_json(r);
  EXPECT_TRUE(j["reached"].get<bool>());
  EXPECT_LT(j["max_error"].get<double>(), 1e-4);
  ASSERT_EQ(j["outcomes"].size(), 6u);
  EXPECT_NEAR(j["outcomes"][0]["achieved"].get<double>(), 0.4, 1e-4);
  EXPECT_NEAR(j["outcomes"][0]["start"].get<double>(), 1.0 / 6, 1e-12);  // the cube: 1/6 by symmetry
  EXPECT_FALSE(j["history"].empty());
  EXPECT_EQ(j["options"]["mass"], "follows");  // the default
  EXPECT_EQ(j["options"]["keep_faces_flat"], true);
  // The offset an insert must give: the centre of mass less the solid's centroid, component by component.
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(j["center_of_mass_offset"][k].get<double>(),
                j["center_of_mass"][k].get<double>() - j["centroid"][k].get<double>(), 1e-12)
        << k;
  for (const char* file : {"design.obj", "design.stl", "design.json"})
    EXPECT_TRUE(fs::exists(dir_.string() + "/out/" + file)) << file;
  // The design read back (its OBJ and its centre of mass) lands as the JSON says.
  const auto com = j["center_of_mass"];
  const auto back =
      run_cli("design " + shell_quote(dir_.string() + "/out/design.obj") + " --inertia convex --com " +
              std::to_string(com[0].get<double>()) + "," + std::to_string(com[1].get<double>()) + "," +
              std::to_string(com[2].get<double>()) + " --target " + target("t2.json", cube_target) +
              " --iterations 0 --json");
  const nlohmann::json b = parse_json(back);
  // 1e-5: --com passes the centre of mass with std::to_string's 6 decimals (1e-6 of L ~ 1e-6 in probability).
  for (std::size_t o = 0; o < 6; ++o)
    EXPECT_NEAR(b["outcomes"][o]["start"].get<double>(), j["outcomes"][o]["achieved"].get<double>(), 1e-5)
        << o;
}

TEST_F(DesignCli, BadTargetsAndOptionsAreOneLineErrorsAndWriteNothing) {
  const std::string out = shell_quote(dir_.string() + "/out");
  expect_bad_input(run_cli("design box:x=1,y=1,z=1 --target " +
                           target("sum.json", "[[[0,0,1],0.5],[[0,0,-1],0.2]]") + " --out " + out),
                   {"sum.json", "sum to 0.7"});
  expect_bad_input(run_cli("design box:x=1,y=1,z=1 --target " +
                           target("tilted.json", "[[[0,0,1],0.5],[[0,0.7,-0.7],0.5]]") + " --out " + out),
                   {"tilted.json", "outcome 2", "--outcome-angle"});
  expect_bad_input(
      run_cli("design box:x=1,y=1,z=1 --target " + target("t.json", cube_target) + " --vary shape"),
      {"--vary", "center-of-mass"});
  expect_bad_input(
      run_cli("design box:x=1,y=1,z=1 --target " + target("t.json", cube_target) + " --max-move -1"),
      {"--max-move"});
  expect_bad_input(
      run_cli("design box:x=1,y=1,z=1 --target " + target("t.json", cube_target) + " --min-margin -0.1"),
      {"--min-margin"});
  expect_bad_input(run_cli("design box:x=1,y=1,z=1 --target " + target("t.json", cube_target) +
                           " --outcome-normals moving"),
                   {"--outcome-normals", "moving"});
  expect_bad_input(run_cli("design box:x=1,y=1,z=1 --target " + shell_quote(dir_.string() + "/missing.json")),
                   {"missing.json"});
  EXPECT_FALSE(fs::exists(dir_.string() + "/out/design.json"));
  // The toss's options belong to --model tossed, and its drops must be whole numbers >= 1.
  expect_bad_input(run_cli("design box:x=1,y=1,z=1 --target " + target("t.json", cube_target) +
                           " --restitution 0.1 --out " + out),
                   {"--restitution", "--model tossed"});
  expect_bad_input(run_cli("design box:x=1,y=1,z=1 --target " + target("t.json", cube_target) +
                           " --model tossed --drops 0 --out " + out),
                   {"--drops"});
  expect_bad_input(run_cli("design box:x=1,y=1,z=1 --target " + target("t.json", cube_target) +
                           " --model tossed --friction -1 --out " + out),
                   {"--friction"});
  EXPECT_FALSE(fs::exists(dir_.string() + "/out/design.json"));
}

// A tossed design (few drops: what is checked here is the command, not the physics — see
// DesignForToss.* for that; few enough for the sanitizer build, where this test is the toss design's run
// through every stage: the finite differences, a step, the checks): its JSON holds the toss, both designs'
// checks on the unseen drops, the history and the settles, and its files are the tossed design's.
TEST_F(DesignCli, ATossedDesignReportsItsChecksAndItsSettles) {
  const std::string out = shell_quote(dir_.string() + "/out");
  const auto r = run_cli("design box:x=1,y=1,z=1 --target " + target("t.json", cube_target) +
                         " --model tossed --drop-height 4 --velocity-max 4 --spin-max 4 --restitution 0.1 "
                         "--friction 0.3 --drops 60 --check-drops 80 --toss-iterations 1 --threads 1 --out " +
                         out + " --json");
  const nlohmann::json j = parse_json(r);
  EXPECT_EQ(j["model"], "tossed");
  const nlohmann::json& t = j["tossed"];
  EXPECT_EQ(t["toss"]["drops"], 60);
  EXPECT_EQ(t["toss"]["restitution"], 0.1);
  EXPECT_EQ(t["check"]["drops"], nlohmann::json({60, 140}));
  EXPECT_EQ(t["check_quasi_static_design"]["drops"], nlohmann::json({60, 140}));
  ASSERT_EQ(t["check"]["counts"].size(), 8u);  // six outcomes, other faces, not at rest
  std::uint64_t total = 0;
  for (const auto& c : t["check"]["counts"]) total += c.get<std::uint64_t>();
  EXPECT_EQ(total, 80u);
  // Each frequency inside its own interval, the interval's ends ordered.
  for (std::size_t k = 0; k < t["check"]["probability"].size(); ++k) {
    const double p = t["check"]["probability"][k].get<double>();
    EXPECT_LE(t["check"]["ci95"][k][0].get<double>(), p) << k;
    EXPECT_GE(t["check"]["ci95"][k][1].get<double>(), p) << k;
    EXPECT_LT(t["check"]["ci95"][k][0].get<double>(), t["check"]["ci95"][k][1].get<double>()) << k;
  }
  EXPECT_EQ(t["check"]["fit_drops"].get<std::uint64_t>(), 60u);
  EXPECT_EQ(t["history"][0]["kind"], "start");
  // The start, six finite differences (one per outcome) and a step, then the two checks.
  EXPECT_GE(t["history"].size(), 8u);
  EXPECT_EQ(t["history"][1]["kind"], "difference");
  EXPECT_EQ(t["history"][1]["surrogate_target"].size(),
            6u);  // the quasi-static target it was designed toward
  EXPECT_EQ(t["settles"].get<std::uint64_t>(), 8u * 60u + 2u * 80u);
  EXPECT_TRUE(j.contains("quasi_static_design"));
  EXPECT_TRUE(fs::exists(dir_.string() + "/out/design.obj"));
  // The table names both designs and the check drops.
  const auto table = run_cli("design box:x=1,y=1,z=1 --target " + target("t.json", cube_target) +
                             " --model tossed --drops 40 --check-drops 40 --toss-iterations 0 --threads 1");
  EXPECT_EQ(table.exit_code, 0) << table.err;
  EXPECT_THAT(table.out, ::testing::HasSubstr("never seen by the optimiser"));
  EXPECT_THAT(table.out, ::testing::HasSubstr("chi-square"));
}

// Drops that do not rest (a step limit far too small) are counted as such, and a design whose drops land
// nowhere is never "converged" (its χ² over the landed drops is 0, but the target is not met).
TEST_F(DesignCli, ATossedDesignWhoseDropsDoNotRestIsNotConverged) {
  const auto r = run_cli("design box:x=1,y=1,z=1 --target " + target("t.json", cube_target) +
                         " --model tossed --drop-height 4 --max-steps 3 --drops 20 --check-drops 20 "
                         "--toss-iterations 0 --threads 1 --json");
  const nlohmann::json j = parse_json(r);
  EXPECT_NE(j["tossed"]["stop"], "converged");
  EXPECT_FALSE(j["tossed"]["reached"].get<bool>());
  EXPECT_EQ(j["tossed"]["check"]["counts"].back(), 20);  // every check drop: not at rest
}

// convex_dice's rule: with the normals following, the JSON gives each outcome's normal at the design (a face
// normal of the design's hull, so a unit vector) and the options say so; the outcomes' margins are there.
TEST_F(DesignCli, FollowingNormalsAreInTheJson) {
  // The cube's target with the bottom outcome's normal given 11° off the bottom face.
  const std::string tilted =
      "[[[0,0.2,-1],0.4],[[0,0,1],0.12],[[1,0,0],0.12],[[-1,0,0],0.12],[[0,1,0],0.12],[[0,-1,0],0.12]]";
  const auto r = run_cli("design box:x=1,y=1,z=1 --outcome-normals follow --min-margin 0.02 --target " +
                         target("t.json", tilted) + " --json");
  const nlohmann::json j = parse_json(r);
  EXPECT_EQ(j["options"]["outcome_normals"], "follow");
  EXPECT_EQ(j["options"]["min_margin"], 0.02);
  for (const auto& o : j["outcomes"]) {
    ASSERT_TRUE(o.contains("design_normal"));
    const auto n = o["design_normal"];
    EXPECT_NEAR(std::hypot(n[0].get<double>(), n[1].get<double>(), n[2].get<double>()), 1.0, 1e-12);
    EXPECT_GT(o["margin"].get<double>(), 0.0);
  }
  // The bottom face is the outcome's face, so its normal moved there from the tilted target's.
  EXPECT_TRUE(j["reached"].get<bool>());
  EXPECT_NEAR(j["outcomes"][0]["design_normal"][2].get<double>(), -1.0, 1e-9);
}

TEST_F(DesignCli, AnUnreachableTargetSaysSoAndGivesItsBestAchievable) {
  const auto r =
      run_cli("design box:x=1,y=1,z=1 --vary center-of-mass --target " + target("t.json", cube_target));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, ::testing::HasSubstr("NOT reached"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("best achievable"));
}

}  // namespace
