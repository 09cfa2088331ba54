// `repose poses` and `repose merge` through the real executable: the JSON contract, determinism across
// threads and splits, the output files, and bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_test_support.hpp"
#include "run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using repose::test::expect_bad_input;
using repose::test::parse_json;
using repose::test::run_cli;
using ::testing::HasSubstr;

class PosesCli : public repose::test::TempDirTest {};

using repose::test::without_timing;
const auto read = repose::test::read_file;

TEST_F(PosesCli, JsonNamesTheIssueFields) {
  const json j = parse_json(run_cli("poses tetrahedron:edge=1 -n 200 --seed 5 --json"));
  EXPECT_EQ(j["n"], 200);
  EXPECT_EQ(j["seed"], 5);
  EXPECT_EQ(j["method"], "dynamic");
  ASSERT_EQ(j["poses"].size(), 4u);
  std::uint64_t total = 0;
  for (const json& p : j["poses"]) {
    for (const char* key : {"probability", "ci95", "count", "down_normal_body", "com_height", "orientation",
                            "quasi_static_probability"})
      EXPECT_TRUE(p.contains(key)) << key;
    EXPECT_LE(p["ci95"][0].get<double>(), p["probability"].get<double>());
    EXPECT_GE(p["ci95"][1].get<double>(), p["probability"].get<double>());
    total += p["count"].get<std::uint64_t>();
  }
  EXPECT_EQ(total + j["status_counts"]["max_time"].get<std::uint64_t>() +
                j["status_counts"]["max_steps"].get<std::uint64_t>(),
            200u);
  EXPECT_TRUE(j.contains("timing"));
  EXPECT_GT(j["timing"]["settles_per_second"].get<double>(), 0);
}

TEST_F(PosesCli, ThreadCountDoesNotChangeTheResult) {
  const std::string cmd = "poses irregular:seed=3 -n 300 --seed 9 --json --threads ";
  const std::string one = without_timing(parse_json(run_cli(cmd + "1"))).dump();
  const std::string two = without_timing(parse_json(run_cli(cmd + "2"))).dump();
  EXPECT_EQ(one, two);
}

TEST_F(PosesCli, SplitRangesMergeIntoTheWholeRun) {
  const std::string base = "poses box:x=1,y=2,z=3 --seed 4 --method dynamic ";
  const json whole = parse_json(run_cli(base + "-n 300 --json"));
  ASSERT_EQ(run_cli(base + "--range 0:150 --out " + (dir_ / "a").string()).exit_code, 0);
  ASSERT_EQ(run_cli(base + "--range 150:300 --threads 1 --out " + (dir_ / "b").string()).exit_code, 0);
  const json merged =
      parse_json(run_cli("merge " + (dir_ / "b/poses.json").string() + " " +
                         (dir_ / "a/poses.json").string() + " --json --out " + (dir_ / "m").string()));
  EXPECT_EQ(without_timing(whole).dump(), without_timing(merged).dump());
  EXPECT_EQ(without_timing(json::parse(read(dir_ / "m/poses.json"))).dump(), without_timing(merged).dump());
}

TEST_F(PosesCli, OutWritesJsonAndCsvAndNothingElse) {
  const fs::path out = dir_ / "out";
  const auto r = run_cli("poses box:x=1,y=1,z=1 -n 50 --method quasi-static --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("quasi-static"));
  EXPECT_EQ(entries(out), (std::vector<std::string>{"poses.csv", "poses.json"}));
  const std::string csv = read(out / "poses.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 7);  // header + 6 faces
  EXPECT_THAT(csv, ::testing::StartsWith("pose,face,count,probability,ci95_lo,ci95_hi"));
}

TEST_F(PosesCli, TableShowsEveryPoseAndTheRate) {
  const auto r = run_cli("poses box:x=1,y=1,z=1 -n 60");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("drops      60 (dynamic, seed 1)"));
  EXPECT_THAT(r.out, HasSubstr("drops/s"));
  EXPECT_EQ(r.err, "") << "no progress bar when stderr is not a terminal";
}

TEST_F(PosesCli, BadInput) {
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1"), {"-n"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 0"), {"--drops", "0"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 --range 5:3"), {"--range", "5:3"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 --range 5"), {"--range"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --range 0:5"), {"--range"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --method static"), {"--method"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --threads -1"), {"--threads"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --damping -1"), {"damping"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --damping-ratio nan"), {"--damping-ratio"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --dt 0 --dt -1"), {"dt"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --persistence -0.1"), {"--persistence"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --density 0"), {"--density"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --density nan"), {"--density"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --dt nan"), {"dt", "nan"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --dt abc"), {"--dt", "abc"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --seed -3"), {"--seed", "-3"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n -5"), {"--drops", "-5"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --contact-threshold 0"), {"contact-threshold"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --line-threshold -1"), {"line-threshold"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --drop-height -1"), {"drop-height"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --max-steps 0"), {"max-steps"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --units imperial"), {"--units", "imperial"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --smooth maybe"), {"--smooth", "maybe"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --bogus"), {"--bogus"});
  expect_bad_input(run_cli("poses -n 5"), {"particle"});
  expect_bad_input(run_cli("poses 'box:x=1,y=-1,z=1' -n 5"), {"box"});
  expect_bad_input(run_cli("poses nosuchshape:x=1 -n 5"), {"nosuchshape"});
  expect_bad_input(run_cli("poses " + (dir_ / "missing.stl").string() + " -n 5"), {"missing.stl"});
  // A directory where a file is read says so (fopen accepts a directory; its read fails as an I/O error).
  fs::create_directory(dir_ / "adir");
  expect_bad_input(run_cli("merge " + (dir_ / "adir").string()), {"adir: cannot read: is a directory"});
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --manifest " + (dir_ / "adir").string()),
                   {"adir: cannot read: is a directory"});
  fs::remove(dir_ / "adir");
  // An output directory that cannot be created: nothing is written anywhere.
  std::ofstream(dir_ / "file") << "x";
  expect_bad_input(run_cli("poses box:x=1,y=1,z=1 -n 5 --out " + (dir_ / "file/sub").string()), {"file/sub"});
  EXPECT_EQ(entries(), (std::vector<std::string>{"file"}));
}

TEST_F(PosesCli, MergeRejectsMismatchedOrOverlappingFiles) {
  const auto run = [&](const std::string& args, const std::string& name) {
    ASSERT_EQ(run_cli("poses " + args + " --out " + (dir_ / name).string()).exit_code, 0);
  };
  run("box:x=1,y=1,z=1 --range 0:20", "a");
  run("box:x=1,y=1,z=1 --range 10:30", "overlap");
  run("box:x=1,y=1,z=1 --range 20:40 --seed 2", "seed");
  run("box:x=1,y=1,z=1 --range 20:40 --damping-ratio 0.1", "damping");
  run("box:x=1,y=1,z=2 --range 20:40", "other");
  const std::string a = (dir_ / "a/poses.json").string();
  expect_bad_input(run_cli("merge " + a + " " + (dir_ / "overlap/poses.json").string()), {"overlapping"});
  expect_bad_input(run_cli("merge " + a + " " + (dir_ / "seed/poses.json").string()), {"seed"});
  expect_bad_input(run_cli("merge " + a + " " + (dir_ / "damping/poses.json").string()), {"settings"});
  expect_bad_input(run_cli("merge " + a + " " + (dir_ / "other/poses.json").string()), {"particles"});
  std::ofstream(dir_ / "junk.json") << "{\"command\": \"poses\"}";
  expect_bad_input(run_cli("merge " + a + " " + (dir_ / "junk.json").string()), {"junk.json", "malformed"});
  expect_bad_input(run_cli("merge " + (dir_ / "none.json").string()), {"none.json"});
  // Found by fuzz_poses_result: a floating-point value where an integer belongs (undefined behaviour in the
  // JSON library's conversion before it was checked).
  const std::string fuzz = std::string(REPOSE_TEST_DATA) + "/fuzz/poses_float_count.json";
  expect_bad_input(run_cli("merge " + fuzz + " " + fuzz), {"poses_float_count.json"});
}

}  // namespace
