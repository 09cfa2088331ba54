// `repose poses` over many particles, across MPI ranks, and resumed after a kill, through the real
// executable. The MPI tests need a build with REPOSE_MPI and mpirun (REPOSE_MPIEXEC).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "cli_test_support.hpp"
#include "run_cli.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using repose::test::expect_bad_input;
using repose::test::parse_json;
using repose::test::read_file;
using repose::test::run_cli;
using repose::test::without_timing;
using ::testing::HasSubstr;

// The sanitizer build runs the engine ~200x slower: the same checks on fewer drops and smaller items.
#ifdef NDEBUG
constexpr int kScale = 1;
#else
constexpr int kScale = 20;
#endif
std::string drops(int n) { return std::to_string(n / kScale); }

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

// Starts `command` (run by /bin/sh) in its own process group and returns its pid.
pid_t spawn(const std::string& command) {
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attr, 0);
  std::string shell = "/bin/sh", flag = "-c", line = "exec " + command;
  char* argv[] = {shell.data(), flag.data(), line.data(), nullptr};
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, "/bin/sh", nullptr, &attr, argv, environ);
  posix_spawnattr_destroy(&attr);
  return rc == 0 ? pid : -1;
}

// Waits until `path` exists (true) or `pid` has exited or 120 s have passed (false).
bool wait_for_file(const fs::path& path, pid_t pid) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    if (fs::exists(path)) return true;
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

// Every file under `dir` that has a final name (not a temporary .tmp-PID) is a complete JSON or CSV file.
void expect_no_partial_files(const fs::path& dir) {
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp-") != std::string::npos) continue;
    const std::string text = read_file(entry.path());
    if (entry.path().extension() == ".json")
      EXPECT_FALSE(json::parse(text, nullptr, false).is_discarded()) << "partial file " << entry.path();
    else
      EXPECT_TRUE(!text.empty() && text.back() == '\n') << "partial file " << entry.path();
  }
}

// The shell command line of `repose ARGS`.
std::string repose_command(const std::string& args) {
  std::string line = "'";
  line += REPOSE_CLI;
  line += "' ";
  line += args;
  return line;
}

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
              300 / kScale);
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

// The acceptance test of resume: kill -9 midway, rerun the same command, get the uninterrupted result.
TEST_F(CampaignCli, KilledRunResumesToTheUninterruptedResult) {
  const std::string common = "poses box:x=1,y=1,z=1 -n " + drops(6000) + " --seed 8 --no-progress";
  const std::string args = common + " --chunk " + drops(100) + " --threads 1";
  const json whole = parse_json(run_cli(common + " --json --threads 2"));
  const fs::path out = dir_ / "out";
  const fs::path checkpoint = out / ".repose-checkpoint/box_x=1_y=1_z=1.json";
  const pid_t pid = spawn(repose_command(args + " --out " + out.string() + " >/dev/null 2>&1"));
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(wait_for_file(checkpoint, pid)) << "no checkpoint appeared";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_EQ(::kill(pid, SIGKILL), 0) << "the run ended before it could be killed";
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run ended before it was killed";

  // Midway: the checkpoint is a complete result file holding some but not all drops; no result yet.
  const json saved = json::parse(read_file(checkpoint));
  EXPECT_GT(saved["n"].get<int>(), 0);
  EXPECT_LT(saved["n"].get<int>(), 6000 / kScale);
  EXPECT_FALSE(fs::exists(out / "poses.json"));
  expect_no_partial_files(out);

  const auto resumed = run_cli(args + " --json --out " + out.string());
  EXPECT_EQ(without_timing(parse_json(resumed)).dump(), without_timing(whole).dump());
  EXPECT_EQ(result(out / "poses.json").dump(), without_timing(whole).dump());
  EXPECT_EQ(entries(out), (std::vector<std::string>{"poses.csv", "poses.json"})) << "checkpoint left behind";
}

#ifdef REPOSE_MPIEXEC

std::string mpirun(int ranks) { return std::string(REPOSE_MPIEXEC) + " -np " + std::to_string(ranks) + " "; }

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

TEST_F(CampaignCli, MpiJobKilledMidwayResumesOnAnotherRankCount) {
  const std::string common = "poses box:x=1,y=1,z=1 -n " + drops(8000) + " --seed 4 --no-progress";
  const std::string args = common + " --chunk " + drops(100) + " --threads 1";
  const json whole = parse_json(run_cli(common + " --json --threads 2"));
  const fs::path out = dir_ / "out";
  const pid_t pid = spawn(mpirun(2) + repose_command(args + " --out " + out.string() + " >/dev/null 2>&1"));
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(wait_for_file(out / ".repose-checkpoint/box_x=1_y=1_z=1.json", pid))
      << "no checkpoint appeared";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  // mpirun passes SIGTERM on to every rank and waits for them (as SLURM's scancel does).
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the job ended before it was stopped";
  EXPECT_FALSE(fs::exists(out / "poses.json"));
  expect_no_partial_files(out);

  const auto resumed = run_cli(args + " --json --out " + out.string(), mpirun(3));
  EXPECT_EQ(without_timing(parse_json(resumed)).dump(), without_timing(whole).dump());
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
