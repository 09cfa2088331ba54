// Cutting a job into work items and finding its particles.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "repose/campaign/campaign.hpp"
#include "repose/error.hpp"

namespace {

using namespace repose;
namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(RemainingRanges, IsTheComplementInsideTheWantedRange) {
  const auto left = remaining_ranges({10, 100}, {{40, 50}, {10, 20}, {90, 100}});
  ASSERT_EQ(left.size(), 2u);
  EXPECT_EQ(left[0].begin, 20u);
  EXPECT_EQ(left[0].end, 40u);
  EXPECT_EQ(left[1].begin, 50u);
  EXPECT_EQ(left[1].end, 90u);
  EXPECT_TRUE(remaining_ranges({0, 5}, {{0, 5}}).empty());
  const auto all = remaining_ranges({3, 7}, {});
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].size(), 4u);
}

TEST(RemainingRanges, RejectsDropsOutsideOrOverlapping) {
  EXPECT_THROW(remaining_ranges({0, 100}, {{50, 150}}), Error);
  EXPECT_THROW(remaining_ranges({10, 100}, {{0, 5}}), Error);
  EXPECT_THROW(remaining_ranges({0, 100}, {{0, 50}, {40, 60}}), Error);
}

TEST(PlanWork, CoversEveryRemainingDropExactlyOnceCostliestFirst) {
  const std::vector<std::vector<DropRange>> remaining = {{{0, 1000}}, {{5, 17}, {30, 1030}}, {}};
  const std::vector<double> cost = {1.0, 50.0, 7.0};
  const auto items = plan_work(remaining, cost, 64);
  std::map<std::uint32_t, std::vector<std::uint64_t>> seen;
  for (const WorkItem& w : items) {
    EXPECT_GT(w.drops.size(), 0u);
    EXPECT_LE(w.drops.size(), 64u);
    for (std::uint64_t i = w.drops.begin; i < w.drops.end; ++i) seen[w.particle].push_back(i);
  }
  for (std::size_t p = 0; p < remaining.size(); ++p) {
    std::vector<std::uint64_t> expected;
    for (const DropRange& r : remaining[p])
      for (std::uint64_t i = r.begin; i < r.end; ++i) expected.push_back(i);
    std::sort(seen[static_cast<std::uint32_t>(p)].begin(), seen[static_cast<std::uint32_t>(p)].end());
    EXPECT_EQ(seen[static_cast<std::uint32_t>(p)], expected) << "particle " << p;
  }
  for (std::size_t k = 1; k < items.size(); ++k)
    EXPECT_GE(static_cast<double>(items[k - 1].drops.size()) * cost[items[k - 1].particle],
              static_cast<double>(items[k].drops.size()) * cost[items[k].particle]);
  EXPECT_EQ(items.front().particle, 1u);
  EXPECT_THROW(plan_work(remaining, cost, 0), Error);
}

TEST(AutoChunk, StaysWithinItsBounds) {
  EXPECT_EQ(auto_chunk(100, 2), 100u);             // never more than the drops
  EXPECT_EQ(auto_chunk(10'000, 2), 256u);          // at least 128 drops per thread
  EXPECT_EQ(auto_chunk(1'000'000, 2), 15'625u);    // about 64 items
  EXPECT_EQ(auto_chunk(100'000'000, 2), 65'536u);  // at most 65,536
  EXPECT_EQ(auto_chunk(1, 8), 1u);
}

class ParticleList : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "repose_plan_test_XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { fs::remove_all(dir_); }
  void touch(const fs::path& p) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << "x";
  }
  fs::path dir_;
};

TEST_F(ParticleList, DirectoriesGiveTheirMeshFilesSortedAndSpecsStay) {
  touch(dir_ / "grains/b.stl");
  touch(dir_ / "grains/a.OBJ");
  touch(dir_ / "grains/notes.txt");
  touch(dir_ / "grains/sub/c.ply");  // not recursive
  const auto particles = resolve_particles({(dir_ / "grains").string(), "box:x=1,y=2,z=3"});
  ASSERT_EQ(particles.size(), 3u);
  EXPECT_EQ(particles[0].name, "a");
  EXPECT_EQ(particles[0].source, (dir_ / "grains/a.OBJ").string());
  EXPECT_EQ(particles[1].name, "b");
  EXPECT_EQ(particles[2].name, "box_x=1_y=2_z=3");
  EXPECT_EQ(particles[2].source, "box:x=1,y=2,z=3");
}

TEST_F(ParticleList, ManifestPathsAreRelativeToTheManifest) {
  touch(dir_ / "lib/one.stl");
  touch(dir_ / "lib/more/two.off");
  std::ofstream(dir_ / "lib/list.txt") << "# my grains\n\none.stl\n  more/two.off  \r\ntetrahedron:edge=2\n";
  const auto particles = resolve_particles({}, (dir_ / "lib/list.txt").string());
  ASSERT_EQ(particles.size(), 3u);
  EXPECT_EQ(particles[0].source, (dir_ / "lib/one.stl").string());
  EXPECT_EQ(particles[1].source, (dir_ / "lib/more/two.off").string());
  EXPECT_EQ(particles[1].name, "two");
  EXPECT_EQ(particles[2].source, "tetrahedron:edge=2");
}

TEST_F(ParticleList, BadInputThrowsNamingIt) {
  touch(dir_ / "a/grain.stl");
  touch(dir_ / "b/grain.obj");
  fs::create_directories(dir_ / "empty");
  try {
    resolve_particles({(dir_ / "a").string(), (dir_ / "b").string()});
    ADD_FAILURE() << "duplicate names accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("two particles named 'grain'"));
  }
  try {
    resolve_particles({(dir_ / "empty").string()});
    ADD_FAILURE() << "empty directory accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("no mesh files"));
  }
  EXPECT_THROW(resolve_particles({}), Error);
  EXPECT_THROW(resolve_particles({}, (dir_ / "missing.txt").string()), Error);
}

}  // namespace
