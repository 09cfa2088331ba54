// Tosses and rebounds at the command line (issue 14): `settle --velocity --spin --restitution --friction`
// and its JSON, `poses` with a toss distribution (identical for any thread count and split, early decision
// exact), and one-line errors for bad values.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.hpp"
#include "run_cli.hpp"

namespace {

using nlohmann::json;
using repose::test::parse_json;
using repose::test::run_cli;
using repose::test::without_timing;
using ::testing::HasSubstr;

class TossCli : public repose::test::TempDirTest {};

#ifdef NDEBUG
constexpr int kTossDrops = 200;
#else
constexpr int kTossDrops = 20;  // the sanitizer build is ~200x slower; the claims hold for any count
#endif

TEST_F(TossCli, SettleJsonListsTheImpactsAndTheFlights) {
  // A cube dropped flat from 0.5 m with E = 0.5: the first impact at sqrt(2·g·0.5) m/s, rebounding at half
  // that; the flights appear among the phases; nothing is below the wall.
  const auto r = run_cli(
      "settle box:x=1,y=1,z=1 --drop-height 0.5 --restitution 0.5 --friction 0.3 --spin 0,0,0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = parse_json(r);
  const double v = std::sqrt(2 * 9.81 * 0.5);
  ASSERT_GE(j["impacts"].size(), 3u);
  const json& first = j["impacts"][0];
  EXPECT_NEAR(first["normal_speed_before"].get<double>(), -v, 1e-12 * v);
  EXPECT_NEAR(first["normal_speed_after"].get<double>(), 0.5 * v, 1e-12 * v);
  EXPECT_EQ(first["points"], 4);
  EXPECT_EQ(first["rebound"], true);
  for (const char* key : {"t", "point", "tangential_speed_before", "tangential_speed_after", "stick",
                          "energy_before", "energy_after"})
    EXPECT_TRUE(first.contains(key)) << key;
  int rebounds = 0;
  for (const auto& i : j["impacts"]) rebounds += i["rebound"].get<bool>();
  EXPECT_EQ(j["bounces"].get<int>(), rebounds);
  int flights = 0;
  for (const json& ph : j["phases"]) flights += ph["contact"] == "flight";
  EXPECT_EQ(flights, 1);  // one phase of bouncing (a straight rebound never turns)
  EXPECT_EQ(j["parameters"]["restitution"], 0.5);
  EXPECT_EQ(j["parameters"]["friction"], 0.3);
  EXPECT_LE(j["max_penetration"].get<double>(), 1e-9 * j["particle"]["characteristic_length"].get<double>());
  EXPECT_EQ(j["status"], "rest");
}

TEST_F(TossCli, DefaultsKeepThePapersTouch) {
  const json j = parse_json(run_cli("settle box:x=1,y=2,z=3 --drop-height 0.4 --json"));
  EXPECT_TRUE(j["impacts"].empty());
  EXPECT_EQ(j["bounces"], 0);
  EXPECT_EQ(j["parameters"]["restitution"], 0.0);
  EXPECT_TRUE(j["parameters"]["friction"].is_null());  // no slip
  EXPECT_EQ(j["phases"][0]["contact"], "free-fall");
}

TEST_F(TossCli, TossedPosesAreTheSameForAnyThreadCountAndSplit) {
  const std::string base =
      "poses box:x=1,y=2,z=3 --seed 5 --drop-height 0.5 --restitution 0.6 --friction 0.4 "
      "--velocity-max 1.5 --spin-max 4 ";
  const std::string n = std::to_string(kTossDrops), half = std::to_string(kTossDrops / 2);
  const json one = without_timing(parse_json(run_cli(base + "-n " + n + " --threads 1 --json")));
  const json two = without_timing(parse_json(run_cli(base + "-n " + n + " --threads 2 --json")));
  EXPECT_EQ(one.dump(), two.dump());
  EXPECT_EQ(one["settings"]["velocity_max"], 1.5);
  EXPECT_EQ(one["settings"]["spin_max"], 4.0);
  EXPECT_EQ(one["settings"]["restitution"], 0.6);
  ASSERT_EQ(run_cli(base + "--range 0:" + half + " --out " + (dir_ / "a").string()).exit_code, 0);
  ASSERT_EQ(
      run_cli(base + "--range " + half + ":" + n + " --threads 1 --out " + (dir_ / "b").string()).exit_code,
      0);
  const json merged = without_timing(parse_json(run_cli("merge " + (dir_ / "a/poses.json").string() + " " +
                                                        (dir_ / "b/poses.json").string() + " --json")));
  EXPECT_EQ(one.dump(), merged.dump());
  // A different toss distribution is a different study: it does not merge.
  ASSERT_EQ(run_cli("poses box:x=1,y=2,z=3 --seed 5 --drop-height 0.5 --restitution 0.6 --friction 0.4 "
                    "--velocity-max 1 --spin-max 4 --range " +
                    half + ":" + n + " --out " + (dir_ / "c").string())
                .exit_code,
            0);
  const auto bad =
      run_cli("merge " + (dir_ / "a/poses.json").string() + " " + (dir_ / "c/poses.json").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("settings"));
}

TEST_F(TossCli, EarlyDecisionIsExactWithRebounds) {
  // No impact creates energy and nothing goes below the wall, so a drop whose energy is below its pose's
  // barrier stays in it through any rebound: --full-settle gives the same pose for every drop.
  const std::string args = "poses tetrahedron:edge=1 -n " + std::to_string(kTossDrops) +
                           " --seed 3 --drop-height 0.3 --restitution 0.7 --friction 0.5 --velocity-max 1 "
                           "--spin-max 6 --json";
  json early = parse_json(run_cli(args));
  json full = parse_json(run_cli(args + " --full-settle"));
  EXPECT_GT(early["decided_early"].get<int>(), 0);
  for (json* j : {&early, &full}) {
    j->erase("timing");
    j->erase("decided_early");
    j->erase("steps");
    (*j)["settings"].erase("decide_early");
  }
  EXPECT_EQ(early.dump(), full.dump());
}

TEST_F(TossCli, BadTossValuesAreOneLineErrors) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"settle box:x=1,y=1,z=1 --velocity 1,2", "--velocity"},
      {"settle box:x=1,y=1,z=1 --spin 1,x,3", "--spin"},
      {"settle box:x=1,y=1,z=1 --restitution 1.5", "restitution"},
      {"settle box:x=1,y=1,z=1 --friction -1", "--friction"},
      {"settle box:x=1,y=1,z=1 --friction lots", "--friction"},
      {"settle box:x=1,y=1,z=1 --drop-speed 1 --velocity 0,0,-2", "--drop-speed"},
      {"poses box:x=1,y=1,z=1 -n 5 --velocity-max -1", "--velocity-max"},
      {"poses box:x=1,y=1,z=1 -n 5 --spin-max nan", "--spin-max"},
      {"poses box:x=1,y=1,z=1 -n 5 --method quasi-static --restitution 0.5", "--method dynamic"}};
  for (const auto& [args, needle] : cases) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_THAT(r.err, HasSubstr(needle)) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << args;
  }
}

}  // namespace
