// A job of work items gives exactly the study of one uninterrupted run, whatever the order the items finish
// in, and a job stopped midway resumes from its checkpoint to the same result.
#include "repose/campaign/campaign.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <stdexcept>

#include "repose/error.hpp"
#include "repose/model/particle.hpp"
#include "repose/output/files.hpp"
#include "repose/poses/landscape.hpp"
#include "repose/poses/sampling.hpp"

namespace {

using namespace repose;
namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;

#ifdef NDEBUG
constexpr std::uint64_t kDrops = 480;
#else
constexpr std::uint64_t kDrops = 48;  // the sanitizer build is ~200x slower
#endif

// The result file without its timing object, the only part allowed to differ between equivalent runs.
std::string without_timing(const PosesStudy& study) {
  json j = json::parse(poses_json(study));
  j.erase("timing");
  return j.dump();
}

// One run_ensemble over all drops, on one thread: the reference.
PosesStudy single_run(const std::string& source, const StudySettings& settings, DropRange drops) {
  const Particle particle = load_particle(source, settings.density);
  const RestLandscape landscape = compute_rest_landscape(particle);
  PosesStudy study = prepare_study(particle, landscape, settings);
  study.tally = run_ensemble(particle, landscape, study.catalog, ensemble_options(study, drops, 1));
  return study;
}

// Finishes the items in a scrambled order, as ranks that run at different speeds would.
class ScrambledRunner final : public LocalRunner {
 public:
  void run(const std::vector<WorkItem>& items, const Work& work, const Absorb& absorb,
           std::atomic<std::uint64_t>* progress) override {
    std::vector<WorkItem> order = items;
    std::shuffle(order.begin(), order.end(), std::mt19937(7));
    for (const WorkItem& item : order) absorb(item, work(item, progress));
  }
};

// Dies after `limit` items, as a killed job would.
class InterruptedRunner final : public LocalRunner {
 public:
  explicit InterruptedRunner(std::size_t limit) : limit_(limit) {}
  void run(const std::vector<WorkItem>& items, const Work& work, const Absorb& absorb,
           std::atomic<std::uint64_t>* progress) override {
    for (std::size_t k = 0; k < items.size(); ++k) {
      if (k == limit_) throw std::runtime_error("killed");
      absorb(items[k], work(items[k], progress));
    }
  }

 private:
  std::size_t limit_;
};

// Runs the items one particle after another, in the particles' order or the reverse, so that the first item
// the root runs is of either particle (the root keeps one particle's model from its checks for its own work).
class ParticleOrderRunner final : public LocalRunner {
 public:
  explicit ParticleOrderRunner(bool reverse) : reverse_(reverse) {}
  void run(const std::vector<WorkItem>& items, const Work& work, const Absorb& absorb,
           std::atomic<std::uint64_t>* progress) override {
    std::vector<WorkItem> order = items;
    std::stable_sort(order.begin(), order.end(), [&](const WorkItem& a, const WorkItem& b) {
      return reverse_ ? a.particle > b.particle : a.particle < b.particle;
    });
    for (const WorkItem& item : order) absorb(item, work(item, progress));
  }

 private:
  bool reverse_;
};

class Campaign : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "repose_campaign_test_XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    options_.settings.seed = 11;
    options_.drops = {0, kDrops};
    options_.threads = 2;
    options_.chunk = kDrops / 12;
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::vector<CampaignParticle> particles_ = {{"box", "box:x=1,y=2,z=3"},
                                              {"prism", "cylinder:r=0.5,h=0.8,n=6"}};
  CampaignOptions options_;
  fs::path dir_;
};

TEST_F(Campaign, ItemsInAnyOrderGiveTheSingleRunExactly) {
  ScrambledRunner runner;
  std::size_t completed = 0;
  options_.on_complete = [&](const std::vector<PosesStudy>& studies) { completed = studies.size(); };
  const auto studies = run_campaign([&] { return particles_; }, options_, runner);
  ASSERT_EQ(studies.size(), 2u);
  EXPECT_EQ(completed, 2u);
  for (std::size_t p = 0; p < 2; ++p) {
    const PosesStudy reference = single_run(particles_[p].source, options_.settings, options_.drops);
    EXPECT_EQ(without_timing(studies[p]), without_timing(reference)) << particles_[p].source;
    ASSERT_EQ(studies[p].tally.ranges.size(), 1u);  // the items coalesced into one range
  }
}

TEST_F(Campaign, EitherParticleFirstGivesTheSingleRunsExactly) {
  for (const bool reverse : {false, true}) {
    ParticleOrderRunner runner(reverse);
    const auto studies = run_campaign([&] { return particles_; }, options_, runner);
    ASSERT_EQ(studies.size(), 2u);
    for (std::size_t p = 0; p < 2; ++p)
      EXPECT_EQ(without_timing(studies[p]),
                without_timing(single_run(particles_[p].source, options_.settings, options_.drops)))
          << particles_[p].source << (reverse ? ", last particle first" : ", first particle first");
  }
}

// The same through a reference that does not go through run_ensemble: with the quasi-static method drop i
// rests on the pose of quasi_static_rest_face for the body-frame down direction of drop_orientation(seed, i),
// counted here drop by drop. Catches a campaign that loses, repeats or shifts drop indices.
TEST_F(Campaign, QuasiStaticCountsMatchADropByDropCount) {
  options_.settings.method = PoseMethod::quasi_static;
  options_.drops = {0, 1200};
  options_.chunk = 100;
  ScrambledRunner runner;
  const auto studies = run_campaign([&] { return particles_; }, options_, runner);
  ASSERT_EQ(studies.size(), 2u);
  for (std::size_t p = 0; p < 2; ++p) {
    const Particle particle = load_particle(particles_[p].source, options_.settings.density);
    const RestLandscape landscape = compute_rest_landscape(particle);
    const std::vector<int>& face_pose = studies[p].catalog.face_pose;
    std::vector<std::uint64_t> count(studies[p].tally.poses.size(), 0);
    std::vector<std::uint64_t> first(count.size(), UINT64_MAX);
    for (std::uint64_t i = 0; i < 1200; ++i) {
      const Vec3 down = drop_orientation(options_.settings.seed, i).conjugate() * Vec3(0, 0, -1);
      const auto pose =
          static_cast<std::size_t>(face_pose[quasi_static_rest_face(particle, landscape, down)]);
      ++count[pose];
      first[pose] = std::min(first[pose], i);
    }
    for (std::size_t k = 0; k < count.size(); ++k) {
      EXPECT_EQ(studies[p].tally.poses[k].count, count[k]) << particles_[p].source << " pose " << k;
      if (count[k] > 0) {
        EXPECT_EQ(studies[p].tally.poses[k].first_drop, first[k]) << particles_[p].source;
      }
    }
  }
}

TEST_F(Campaign, AStoppedJobResumesFromItsCheckpointToTheSameResult) {
  options_.checkpoint_dir = (dir_ / "checkpoint").string();
  InterruptedRunner killed(7);
  EXPECT_THROW(run_campaign([&] { return particles_; }, options_, killed), std::runtime_error);
  // The checkpoint holds exactly what was absorbed: 7 items, in valid result files.
  std::uint64_t saved = 0;
  for (const CampaignParticle& p : particles_) {
    const std::string path = checkpoint_path(options_.checkpoint_dir, p);
    if (fs::exists(path)) saved += parse_poses_json(read_text_file(path), path).tally.drops();
  }
  EXPECT_EQ(saved, 7 * options_.chunk);

  // Resume with another chunk size and thread count: the result cannot tell.
  options_.chunk = kDrops / 5;
  options_.threads = 1;
  std::uint64_t remaining = 0;
  options_.on_start = [&](std::uint64_t left, const std::vector<PosesStudy>&) { remaining = left; };
  LocalRunner runner;
  const auto studies = run_campaign([&] { return particles_; }, options_, runner);
  EXPECT_EQ(remaining, 2 * kDrops - saved);
  for (std::size_t p = 0; p < 2; ++p)
    EXPECT_EQ(without_timing(studies[p]),
              without_timing(single_run(particles_[p].source, options_.settings, options_.drops)));
  EXPECT_FALSE(fs::exists(options_.checkpoint_dir)) << "checkpoint not removed after the job";
}

TEST_F(Campaign, ACheckpointOfAnotherRunIsRefusedNamingIt) {
  options_.checkpoint_dir = (dir_ / "checkpoint").string();
  InterruptedRunner killed(3);
  EXPECT_THROW(run_campaign([&] { return particles_; }, options_, killed), std::runtime_error);
  options_.settings.seed = 12;
  LocalRunner runner;
  try {
    run_campaign([&] { return particles_; }, options_, runner);
    ADD_FAILURE() << "a checkpoint of seed 11 was resumed with seed 12";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("checkpoint of a different run"));
    EXPECT_THAT(e.what(), HasSubstr("different seeds"));
    EXPECT_THAT(e.what(), HasSubstr(options_.checkpoint_dir));
  }
  // Fewer drops than the checkpoint holds: refused too, not silently over-counted.
  options_.settings.seed = 11;
  options_.drops = {0, options_.chunk};
  EXPECT_THROW(run_campaign([&] { return particles_; }, options_, runner), Error);
}

TEST_F(Campaign, BadInputOnTheRootIsAnErrorBeforeAnyWork) {
  LocalRunner runner;
  bool started = false;
  options_.on_start = [&](std::uint64_t, const std::vector<PosesStudy>&) { started = true; };
  particles_.push_back({"nothing", (dir_ / "missing.stl").string()});
  EXPECT_THROW(run_campaign([&] { return particles_; }, options_, runner), Error);
  EXPECT_FALSE(started);
}

}  // namespace
