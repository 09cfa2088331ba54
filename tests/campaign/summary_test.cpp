// The summary tables of a many-particle job.
#include "repose/campaign/summary.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "repose/error.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace {

using namespace repose;
using ::testing::HasSubstr;

// A study of the unit cube with counts set by hand: 3 drops on pose 2, 1 on pose 0, 1 not at rest.
PosesStudy hand_made_study() {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  PosesStudy study = prepare_study(cube, compute_rest_landscape(cube), StudySettings{});
  study.tally.ranges = {{0, 5}};
  study.tally.poses[2].count = 3;
  study.tally.poses[2].first_drop = 1;
  study.tally.poses[0].count = 1;
  study.tally.poses[0].first_drop = 0;
  study.tally.status_counts[1] = 4;
  study.tally.status_counts[3] = 1;
  return study;
}

TEST(Summary, RowsShowTheMostLikelyPoseWithItsInterval) {
  CampaignSummary summary;
  summary.particles = {{"cube", "my \"odd\", name.stl"}, {"none", "box:x=1,y=1,z=1"}};
  summary.studies = {hand_made_study(), hand_made_study()};
  summary.studies[1].tally.poses[2].count = summary.studies[1].tally.poses[0].count = 0;
  summary.result_files = {"cube.poses.json", "none.poses.json"};

  const std::string csv = summary_csv(summary);
  EXPECT_THAT(csv,
              HasSubstr("cube,\"my \"\"odd\"\", name.stl\",cube.poses.json,6,0,5,2,2,0.59999999999999998,"));
  EXPECT_THAT(csv, HasSubstr("none,\"box:x=1,y=1,z=1\",none.poses.json,6,0,5,0,,,,,,,,1\n"));

  const auto j = nlohmann::json::parse(summary_json(summary));
  EXPECT_EQ(j["particles"][0]["top_pose"]["pose"], 2);
  // The Wilson interval of 3/5, evaluated at 30 digits (mpmath) from (x + z²/2 − z·sqrt(x(n − x)/n + z²/4)) /
  // (n + z²), z = sqrt(2)·erfinv(0.95); round-off margin 1e-12 relative (measured 6e-16).
  const double lower = 0.230724281276012932;
  EXPECT_NEAR(j["particles"][0]["top_pose"]["ci95"][0].get<double>(), lower, 1e-12 * lower);
  EXPECT_EQ(j["particles"][0]["poses_seen"], 2);
  EXPECT_EQ(j["particles"][0]["not_at_rest"], 1);
  EXPECT_TRUE(j["particles"][1]["top_pose"].is_null());

  const std::string md = summary_markdown(summary);
  EXPECT_THAT(md, HasSubstr("| cube | 6 | 5 | 2 | 2 | 0.60000 |"));
  EXPECT_THAT(md, HasSubstr("| none | 6 | 5 | 0 | – |"));

  summary.result_files.pop_back();
  EXPECT_THROW(summary_csv(summary), Error);
}

}  // namespace
