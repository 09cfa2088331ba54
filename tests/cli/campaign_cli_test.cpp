// `repose poses` over many particles and across MPI ranks, through the real executable (resume after a
// kill: campaign_resume_cli_test.cpp). The MPI tests need a build with REPOSE_MPI and mpirun
// (REPOSE_MPIEXEC).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cli_test_support.hpp"
#include "run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using repose::test::expect_bad_input;
using repose::test::parse_json;
using repose::test::read_file;
using repose::test::run_cli;
using repose::test::without_timing;
using ::testing::HasSubstr;

using repose::test::kCampaignScale;  // fewer drops in the sanitizer build
std::string drops(int n) { return std::to_string(n / kCampaignScale); }

class CampaignCli : public repose::test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    // Open MPI refuses to run as root unless told (CI runs as root); harmless otherwise.
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  }
  // A result file's JSON without timing, or null if the file is missing.
  json result(const fs::path& path) const {
    if (!fs::exists(path)) return nullptr;
    return without_timing(json::parse(read_file(path)));
  }
};

const std::string kCube = std::string(REPOSE_TEST_DATA) + "/cube_ascii.stl";

TEST_F(CampaignCli, ManyParticlesGiveOneResultEachAndASummary) {
  std::ofstream(dir_ / "list.txt") << "# two particles\nbox:x=1,y=2,z=3\ntetrahedron:edge=1\n";
  const fs::path out = dir_ / "out";
  const std::string common =
      " -n " + drops(300) + " --seed 5 --chunk " + drops(70) + " --out " + out.string();
  const json summary = parse_json(
      run_cli("poses " + kCube + " --manifest " + (dir_ / "list.txt").string() + common + " --json"));
  EXPECT_EQ(entries(out),
            (std::vector<std::string>{"box_x=1_y=2_z=3.poses.csv", "box_x=1_y=2_z=3.poses.json",
                                      "cube_ascii.poses.csv", "cube_ascii.poses.json", "summary.csv",
                                      "summary.json", "summary.md", "tetrahedron_edge=1.poses.csv",
                                      "tetrahedron_edge=1.poses.json"}));
  ASSERT_EQ(summary["particles"].size(), 3u);
  EXPECT_EQ(summary["particles"][0]["name"], "cube_ascii");
  EXPECT_EQ(summary["particles"][1]["source"], "box:x=1,y=2,z=3");
  EXPECT_EQ(json::parse(read_file(out / "summary.json"))["particles"], summary["particles"]);
  const std::string csv = read_file(out / "summary.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  EXPECT_THAT(read_file(out / "summary.md"), HasSubstr("| tetrahedron_edge=1 | 4 | " + drops(300) + " |"));
  // Each particle's file is exactly what a run of that particle alone writes.
  for (const std::string& source :
       {kCube, std::string("box:x=1,y=2,z=3"), std::string("tetrahedron:edge=1")}) {
    const json alone = parse_json(run_cli("poses " + source + " -n " + drops(300) + " --seed 5 --json"));
    const std::string name = source == kCube                  ? "cube_ascii"
                             : source == "tetrahedron:edge=1" ? "tetrahedron_edge=1"
                                                              : "box_x=1_y=2_z=3";
    EXPECT_EQ(result(out / (name + ".poses.json")).dump(), without_timing(alone).dump()) << source;
    EXPECT_EQ(summary["particles"][name == "cube_ascii"        ? 0
                                   : name == "box_x=1_y=2_z=3" ? 1
                                                               : 2]["n"],
              300 / kCampaignScale);
  }
}

TEST_F(CampaignCli, DirectoryOfMeshesAndBadInput) {
  fs::create_directories(dir_ / "grains");
  fs::copy_file(kCube, dir_ / "grains/a.stl");
  fs::copy_file(std::string(REPOSE_TEST_DATA) + "/cube.off", dir_ / "grains/b.off");
  const auto r = run_cli("poses " + (dir_ / "grains").string() + " -n 20 --out " + (dir_ / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| a | 6 | 20 |"));
  EXPECT_THAT(r.out, HasSubstr("| b | 6 | 20 |"));

  expect_bad_input(run_cli("poses " + (dir_ / "grains").string() + " -n 20"), {"2 particles", "--out"});
  fs::copy_file(kCube, dir_ / "a.obj");
  expect_bad_input(run_cli("poses " + (dir_ / "grains").string() + " " + (dir_ / "a.obj").string() +
                           " -n 5 --out " + (dir_ / "dup").string()),
                   {"two particles named 'a'"});
  EXPECT_FALSE(fs::exists(dir_ / "dup/.repose-checkpoint"));
  fs::create_directories(dir_ / "empty");
  expect_bad_input(run_cli("poses " + (dir_ / "empty").string() + " -n 5"), {"empty", "no mesh files"});
  expect_bad_input(run_cli("poses --manifest " + (dir_ / "none.txt").string() + " -n 5"), {"none.txt"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --chunk 0"), {"--chunk"});
  // A checkpoint of another study is not silently mixed in.
  fs::create_directories(dir_ / "other/.repose-checkpoint");
  ASSERT_EQ(run_cli("poses box:x=1,y=1,z=1 --range 0:20 --out " + (dir_ / "seed1").string()).exit_code, 0);
  fs::copy_file(dir_ / "seed1/poses.json", dir_ / "other/.repose-checkpoint/poses.json");
  fs::copy_file(dir_ / "seed1/poses.json", dir_ / "other/.repose-checkpoint/box_x=1_y=1_z=1.json");
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 40 --seed 2 --out " + (dir_ / "other").string()),
                   {"box_x=1_y=1_z=1.json", "checkpoint of a different run", "seeds"});
}

#ifdef REPOSE_MPIEXEC

using repose::test::mpirun;

// The acceptance test of the MPI build: 1, 2 and 3 ranks, 1 or 2 threads each, give the same JSON as one
// process (timing excepted), for one particle and for several.
TEST_F(CampaignCli, RanksAndThreadsDoNotChangeTheResult) {
  const std::string args =
      "poses irregular:seed=3 -n " + drops(400) + " --seed 9 --chunk " + drops(37) + " --no-progress --json";
  const std::string alone = without_timing(parse_json(run_cli(args + " --threads 2"))).dump();
  for (int ranks : {1, 2, 3})
    for (int threads : {1, 2}) {
      if (ranks == 3 && threads == 2) continue;  // 6 threads on 2 cores: slow, and adds nothing
      const auto r = run_cli(args + " --threads " + std::to_string(threads), mpirun(ranks));
      EXPECT_EQ(without_timing(parse_json(r)).dump(), alone) << ranks << " ranks, " << threads << " threads";
    }
}

// The mesh options travel to the other ranks with the particle list: a given centre of mass (--com) gives
// the same result on two ranks as in one process, and a different one from the uniform box.
TEST_F(CampaignCli, AGivenCentreOfMassReachesEveryRank) {
  const std::string args = "poses box:x=1,y=2,z=3 -n 120 --chunk 20 --threads 1 --no-progress --json";
  const std::string alone = without_timing(parse_json(run_cli(args + " --com 0.1,0,-0.3"))).dump();
  const auto r = run_cli(args + " --com 0.1,0,-0.3", mpirun(2));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(without_timing(parse_json(r)).dump(), alone);
  EXPECT_NE(without_timing(parse_json(run_cli(args))).dump(), alone);
  EXPECT_NE(alone.find("center_of_mass"), std::string::npos);
}

TEST_F(CampaignCli, ManyParticlesAcrossRanksMatchOneProcess) {
  const std::string particles = kCube + " box:x=1,y=2,z=3 cylinder:r=0.5,h=1,n=24";
  const std::string args =
      "poses " + particles + " -n 250 --seed 3 --chunk 40 --threads 1 --no-progress --out ";
  ASSERT_EQ(run_cli(args + (dir_ / "one").string()).exit_code, 0);
  const auto r = run_cli(args + (dir_ / "three").string(), mpirun(3));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(entries(dir_ / "one"), entries(dir_ / "three"));
  for (const std::string& name : entries(dir_ / "one")) {
    if (name.ends_with(".json"))
      EXPECT_EQ(result(dir_ / "one" / name).dump(), result(dir_ / "three" / name).dump()) << name;
    else
      EXPECT_EQ(read_file(dir_ / "one" / name), read_file(dir_ / "three" / name)) << name;
  }
  EXPECT_EQ(json::parse(read_file(dir_ / "three/summary.json"))["timing"]["ranks"], 3);
}

// Bad input under mpirun: rank 0 prints the one-line error, once, and every rank exits with code 2. Before
// the exit code was agreed collectively (cmd_poses.cpp), rank 1 could exit with 2 first and mpirun then
// killed rank 0 before it printed: 1 run in 12 on a busy machine, 8 in 40 with two busy loops beside it.
TEST_F(CampaignCli, BadInputUnderMpiIsReportedOnce) {
  const fs::path missing = dir_ / "missing.stl";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"poses " + missing.string() + " -n 10", "repose: error: " + missing.string() + ": cannot open"},
      {"poses box:x=1,y=1,z=1 -n 10 --threads -1", "repose: error: option --threads must be >= 0"}};
  for (const auto& [args, line] : cases) {
    const auto r = run_cli(args, mpirun(2));
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_EQ(r.out, "") << args;
    // mpirun adds its own banner about the non-zero exit code; repose's line appears exactly once.
    EXPECT_THAT(r.err, HasSubstr(line)) << args;
    EXPECT_EQ(r.err.find(line), r.err.rfind(line)) << "reported more than once:\n" << r.err;
    EXPECT_EQ(r.err.find("repose: "), r.err.rfind("repose: ")) << "another repose line:\n" << r.err;
  }
}

#else

// A build without MPI started by mpirun cannot share the work: every rank would run the whole job. It says
// so.
TEST_F(CampaignCli, WithoutMpiALaunchedRankWarnsThatItRunsTheWholeJob) {
  const auto r = run_cli("poses box:x=1,y=1,z=1 -n 5 --json", "OMPI_COMM_WORLD_SIZE=2 ");
  EXPECT_EQ(parse_json(r)["n"], 5);
  EXPECT_THAT(r.err, HasSubstr("built without MPI"));
}

#endif

}  // namespace
