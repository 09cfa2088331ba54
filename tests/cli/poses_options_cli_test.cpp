// `repose poses` options checked by their values: --full-settle against early decision, --damping-ratio
// against C = ratio·m·sqrt(g·L³) worked out here, --persistence on a fine ellipsoid, and --max-steps in the
// status counts.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "cli_test_support.hpp"
#include "run_cli.hpp"

namespace {

using nlohmann::json;
using repose::test::numbers;
using repose::test::parse_json;
using repose::test::run_cli;
using ::testing::HasSubstr;

class PosesOptionsCli : public repose::test::TempDirTest {};

// The sanitizer build runs the engine ~200x slower: fewer drops there (the claims hold for any drop count).
#ifdef NDEBUG
constexpr int kOptionDrops = 200;
#else
constexpr int kOptionDrops = 20;
#endif

TEST_F(PosesOptionsCli, FullSettleGivesTheSameCountsDropForDrop) {
  // docs/rest-poses.md: stopping a drop once its energy cannot leave its pose never changes the pose, and a
  // pose's representative orientation is always that of a complete run. So everything but the cost is equal.
  const std::string args =
      "poses irregular:seed=3 -n " + std::to_string(kOptionDrops) + " --seed 2 --threads 2 --json";
  json early = parse_json(run_cli(args));
  json full = parse_json(run_cli(args + " --full-settle"));
  EXPECT_EQ(early["settings"]["decide_early"], true);
  EXPECT_EQ(full["settings"]["decide_early"], false);
  EXPECT_EQ(full["decided_early"], 0);
  EXPECT_GT(early["decided_early"].get<int>(), 0) << "early decision did not stop any drop";
  EXPECT_GT(full["steps"].get<long>(), early["steps"].get<long>());
  for (json* j : {&early, &full}) {
    j->erase("timing");
    j->erase("decided_early");
    j->erase("steps");
    (*j)["settings"].erase("decide_early");
  }
  EXPECT_EQ(early.dump(), full.dump());
  EXPECT_GE(early["poses"].size(), 3u);
}

TEST_F(PosesOptionsCli, DampingRatioSetsTheDocumentedCoefficient) {
  // A 1 x 2 x 3 box of density 2: V = 6, m = 12, L = (6V/π)^(1/3); C = ratio·m·sqrt(g·L³)
  // (docs/rest-poses.md, --help).
  const double m = 12, g = 9.81, length = std::cbrt(36 / std::numbers::pi);
  const std::string args = "poses box:x=1,y=2,z=3 --density 2 -n 4 --json";
  // Measured: 4e-16 relative (the code multiplies in another order). 1e-12 sees any factor.
  for (const double ratio : {0.05, 0.3}) {
    const json j = parse_json(run_cli(args + (ratio == 0.05 ? "" : " --damping-ratio 0.3")));
    const double c = ratio * m * std::sqrt(g * length * length * length);
    EXPECT_NEAR(j["settings"]["damping"].get<double>(), c, 1e-12 * c) << "ratio " << ratio;
    EXPECT_NEAR(j["particle"]["mass"].get<double>(), m, 1e-12);
    EXPECT_NEAR(j["particle"]["characteristic_length"].get<double>(), length, 1e-12);
  }
  // In cgs the same formula holds with g = 981.
  const json cgs = parse_json(run_cli(args + " --units cgs"));
  const double c_cgs = 0.05 * m * std::sqrt(981 * length * length * length);
  EXPECT_NEAR(cgs["settings"]["damping"].get<double>(), c_cgs, 1e-12 * c_cgs);
  // --damping gives C itself; the ratio is then ignored.
  EXPECT_EQ(parse_json(run_cli(args + " --damping 7 --damping-ratio 0.3"))["settings"]["damping"], 7.0);
  EXPECT_EQ(parse_json(run_cli(args + " --damping-ratio 0"))["settings"]["damping"], 0.0);
}

TEST_F(PosesOptionsCli, PersistenceMergesTheFacetsOfAFineEllipsoid) {
  // The triaxial ellipsoid (1.25, 1, 0.57) with 2,000 triangles: 12 stable facets, 6 around each end of the
  // shortest axis (docs/rest-poses.md). --persistence 0 keeps every facet a pose; the default for a smooth
  // particle (0.01·L) merges them into the two true poses, which by the z → −z symmetry of the mesh share the
  // quasi-static probability equally. The catalogue does not depend on the drops: quasi-static drops are
  // enough.
  const std::string args = "poses ellipsoid:a=0.625,b=0.5,c=0.285,n=10 -n 40 --method quasi-static --json";
  const json facets = parse_json(run_cli(args + " --persistence 0"));
  const json merged = parse_json(run_cli(args));
  const double length = merged["particle"]["characteristic_length"].get<double>();
  // L is that of the inscribed mesh, 0.18 % below the smooth 2·(abc)^(1/3) (measured 1.6e-3).
  EXPECT_NEAR(length, 2 * std::cbrt(0.625 * 0.5 * 0.285), 4e-3);
  EXPECT_EQ(facets["settings"]["persistence"], 0.0);
  EXPECT_NEAR(merged["settings"]["persistence"].get<double>(), 0.01 * length, 1e-15);

  ASSERT_EQ(facets["poses"].size(), 12u);
  double total = 0;
  for (const json& p : facets["poses"]) {
    EXPECT_EQ(p["faces"].size(), 1u);
    total += p["quasi_static_probability"].get<double>();
  }
  EXPECT_NEAR(total, 1.0, 1e-12);  // basins tile the sphere; measured 1e-15

  ASSERT_EQ(merged["poses"].size(), 2u);
  int drops = 0;
  for (const json& p : merged["poses"]) {
    EXPECT_EQ(p["faces"].size(), 6u);
    // An end of the shortest (body z) axis; the deepest facet's normal is 2° off the axis (measured
    // |z| = 0.99927).
    EXPECT_GT(std::abs(numbers(p["down_normal_body"])[2]), 0.999);
    EXPECT_NEAR(p["quasi_static_probability"].get<double>(), 0.5, 1e-12);  // measured 3e-15
    drops += p["count"].get<int>();
  }
  EXPECT_EQ(drops, 40);
  // Opposite ends.
  EXPECT_LT(
      numbers(merged["poses"][0]["down_normal_body"])[2] * numbers(merged["poses"][1]["down_normal_body"])[2],
      0);
  // Given explicitly, the default's value gives the same catalogue.
  json explicit_default = parse_json(run_cli(args + " --persistence 0.01"));
  json automatic = merged;
  explicit_default.erase("timing");
  automatic.erase("timing");
  EXPECT_EQ(explicit_default.dump(), automatic.dump());
}

TEST_F(PosesOptionsCli, MaxStepsDropsAreCountedApartAndWarned) {
  // Three steps are too few for any drop of the box to rest: all ten are counted under max_steps, none in a
  // pose; the command prints the result, says so on stderr and exits 3 (not at rest, as settle does).
  const auto r = run_cli("poses box:x=1,y=2,z=3 -n 10 --max-steps 3 --json");
  const json j = parse_json(r, 3);
  EXPECT_EQ(j["status_counts"]["max_steps"], 10);
  EXPECT_EQ(j["status_counts"]["rest"], 0);
  EXPECT_EQ(j["settings"]["max_steps"], 3);
  for (const json& p : j["poses"]) EXPECT_EQ(p["count"], 0);
  EXPECT_THAT(r.err, HasSubstr("10 of 10 drops did not come to rest"));
}

}  // namespace
