// The campaign's pose counts against an independent tally: every drop simulated on its own with the engine
// (repose::settle from drop_orientation(seed, i)) and its rest face read by the test from the final down
// direction. The campaign's work items, early decisions, merging and pose catalogue do not enter the
// reference, so a wrong count, a lost or doubled item, or a drop credited to the wrong pose fails.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "repose/campaign/campaign.hpp"
#include "repose/campaign/runner.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/sampling.hpp"
#include "repose/sim/settle.hpp"

namespace {

using namespace repose;

#ifdef NDEBUG
constexpr std::uint64_t kOracleDrops = 600;
#else
constexpr std::uint64_t kOracleDrops = 30;  // the sanitizer build is ~100x slower
#endif

// The face of a box a body-frame down direction points at: 0..5 for −x, +x, −y, +y, −z, +z.
int box_face(const Vec3& down) {
  int axis = 0;
  down.cwiseAbs().maxCoeff(&axis);
  EXPECT_NEAR(std::abs(down[axis]), 1.0, 1e-9) << down.transpose();
  return 2 * axis + (down[axis] > 0 ? 1 : 0);
}

TEST(CampaignOracle, PoseCountsEqualDropByDropSettles) {
  const std::string spec = "box:x=1,y=2,z=3";
  CampaignOptions options;
  options.settings.seed = 11;
  options.drops = {0, kOracleDrops};
  options.threads = 2;
  options.chunk = kOracleDrops / 7;  // items of uneven size
  LocalRunner runner;
  const std::vector<PosesStudy> studies = run_campaign(
      [&] {
        return std::vector<CampaignParticle>{{"box", spec}};
      },
      options, runner);
  ASSERT_EQ(studies.size(), 1u);
  const PosesStudy& study = studies[0];

  // The reference: the study's documented defaults written out here, SI units, density 1, from rest
  // touching the wall, damping C = 0.05·m·sqrt(g·L³) (docs/rest-poses.md).
  const Particle box = load_particle(spec, 1.0);
  SettleParams params;
  params.damping = 0.05 * box.mass.mass * std::sqrt(params.gravity * std::pow(box.length, 3));
  std::map<int, std::uint64_t> expected;
  for (std::uint64_t i = 0; i < kOracleDrops; ++i) {
    const SettleResult r = settle(box, params, drop_orientation(options.settings.seed, i));
    ASSERT_EQ(r.status, Status::rest) << "drop " << i;
    ++expected[box_face(r.down_normal_body)];
  }
  std::map<int, std::uint64_t> counted;
  std::uint64_t total = 0;
  for (std::size_t p = 0; p < study.catalog.poses.size(); ++p) {
    counted[box_face(study.catalog.poses[p].down_normal_body)] += study.tally.poses[p].count;
    total += study.tally.poses[p].count;
  }
  EXPECT_EQ(total, kOracleDrops);
  EXPECT_EQ(counted, expected);
}

}  // namespace
