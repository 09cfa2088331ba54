// A newcomer's first hour (issue 33), replayed: each of the ten frictions a new user met, as written, with
// the exact text the tool now prints. Expected values come from the issue's deliverables and from closed
// forms (a 1 x 2 x 3 box: V = 6, area 22, L = (36/π)^(1/3)), never from the tool's own output.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sched.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "run_cli.hpp"

namespace {

// The CPUs this process may run on (its affinity mask), counted independently of the library's TBB.
int allowed_cpus() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 1;
  return CPU_COUNT(&set);
}

namespace fs = std::filesystem;
using nlohmann::json;
using repose::test::CliResult;
using repose::test::csv_rows;
using repose::test::parse_json;
using repose::test::read_file;
using repose::test::run_cli;
using repose::test::shell_quote;
using ::testing::HasSubstr;
using ::testing::StartsWith;

class FirstHourCli : public repose::test::TempDirTest {};

const std::string kBox = "box:x=1,y=2,z=3";

// The one line of a bad input: exit 2, nothing on stdout, exactly `line` on stderr.
void expect_refused(const CliResult& r, const std::string& line) {
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "repose: error: " + line + "\n");
}

// The line of `text` that starts with `key`, or "".
std::string line_of(const std::string& text, const std::string& key) {
  std::size_t at = text.rfind("\n" + key);
  at = text.compare(0, key.size(), key) == 0 ? 0 : at == std::string::npos ? at : at + 1;
  if (at == std::string::npos) return "";
  return text.substr(at, text.find('\n', at) - at);
}

// The whole number at the start of `text` after `prefix`, and the rest of `text` (what was expected
// otherwise: {0, "no PREFIX in TEXT"}).
std::pair<std::uint64_t, std::string> number_after(const std::string& text, const std::string& prefix) {
  if (text.compare(0, prefix.size(), prefix) != 0) return {0, "no '" + prefix + "' in '" + text + "'"};
  const std::size_t end = text.find_first_not_of("0123456789", prefix.size());
  if (end == prefix.size()) return {0, "no number after '" + prefix + "' in '" + text + "'"};
  return {std::stoull(text.substr(prefix.size(), end - prefix.size())), text.substr(end)};
}

// 2. Output paths are checked before any work: a billion drops would take hours, so an answer within the
// timeout (`timeout` exits 124) shows nothing ran. /proc takes no new files, even from root.
TEST_F(FirstHourCli, OutputPathsAreCheckedBeforeAnyWork) {
  expect_refused(run_cli("poses " + kBox + " -n 1e9 --html /proc/x.html", "timeout 60 "),
                 "/proc/x.html: cannot be written: /proc: output directory is not writable");
  expect_refused(run_cli("settle " + kBox + " --html /proc/x.html"),
                 "/proc/x.html: cannot be written: /proc: output directory is not writable");
  expect_refused(run_cli("settle " + kBox + " --vtk /proc"), "/proc: output directory is not writable");
  expect_refused(run_cli("info " + kBox + " --write-stl /proc/x.stl"),
                 "/proc/x.stl: cannot be written: /proc: output directory is not writable");
  // A regular file where a directory must be: the same, for any user.
  std::ofstream(dir_ / "file") << "x";
  const std::string under_file = (dir_ / "file" / "x.html").string();
  const CliResult r = run_cli("poses " + kBox + " -n 1e9 --html " + under_file, "timeout 60 ");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, StartsWith("repose: error: " + under_file + ": cannot be written: "));
  EXPECT_EQ(entries(), std::vector<std::string>{"file"});  // no probe left behind
}

// 3. One pose numbering: the catalogue's, lowest centre of mass first (ties by hull face), in the table, the
// JSON and the CSV alike, with the hull face a field of its own.
TEST_F(FirstHourCli, OnePoseNumberingEverywhere) {
  const std::string out = (dir_ / "r").string();
  const CliResult table = run_cli("poses " + kBox + " -n 300 --out " + out);
  ASSERT_EQ(table.exit_code, 0) << table.err;
  const json j = json::parse(read_file(dir_ / "r/poses.json"));
  ASSERT_EQ(j["poses"].size(), 6u);
  // The box's rest heights are its half extents: 0.5 (faces ±x), 1 (±y), 1.5 (±z); pose k sits k-th lowest.
  std::vector<std::pair<double, int>> by_height;
  for (const json& p : j["poses"])
    by_height.emplace_back(p["com_height"].get<double>(), p["face"].get<int>());
  std::sort(by_height.begin(), by_height.end());
  std::map<int, int> pose_of_face;
  for (const json& p : j["poses"]) {
    const int pose = p["pose"].get<int>(), face = p["face"].get<int>();
    pose_of_face[face] = pose;
    EXPECT_EQ(by_height[static_cast<std::size_t>(pose)].second, face) << "pose " << pose;
    const double half_extents[] = {0.5, 0.5, 1.0, 1.0, 1.5, 1.5};
    EXPECT_NEAR(p["com_height"].get<double>(), half_extents[pose], 1e-12);
  }
  for (const auto& row : csv_rows(read_file(dir_ / "r/poses.csv")))
    EXPECT_EQ(pose_of_face.at(std::stoi(row[1])), std::stoi(row[0])) << "CSV row of face " << row[1];
  // The table: "  pose   face ..." then one row per pose, the same pairs.
  std::istringstream rows(table.out);
  std::string line;
  int seen = 0;
  while (std::getline(rows, line)) {
    int pose = -1, face = -1;
    if (std::sscanf(line.c_str(), " %d %d", &pose, &face) == 2 && line.find('[') != std::string::npos) {
      EXPECT_EQ(pose_of_face.at(face), pose) << line;
      ++seen;
    }
  }
  EXPECT_EQ(seen, 6);
  EXPECT_THAT(table.out, HasSubstr("(pose: its number in the catalogue, lowest centre of mass first"));
}

// 4. Units on every printed quantity: info, settle and the poses table, in si and cgs, and a units object in
// every JSON.
TEST_F(FirstHourCli, UnitsOnEveryPrintedQuantity) {
  const CliResult info = run_cli("info " + kBox);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_EQ(line_of(info.out, "density"),
            "density             1 kg/m³ (the default; --density sets it: it scales mass, inertia and "
            "energies, not rest poses)");
  EXPECT_EQ(line_of(info.out, "surface area"), "surface area        22 m²");
  EXPECT_EQ(line_of(info.out, "volume"), "volume              6 m³");
  EXPECT_EQ(line_of(info.out, "mass"), "mass                6 kg");
  EXPECT_EQ(line_of(info.out, "centre of mass"), "centre of mass      [0, 0, 0] m");
  // I = m(b² + c²)/12 about x: 6·13/12 = 6.5.
  EXPECT_EQ(line_of(info.out, "inertia about COM"), "inertia about COM   [6.5, -0, -0] kg·m²");
  const CliResult cgs = run_cli("info " + kBox + " --units cgs --density 2");
  EXPECT_EQ(line_of(cgs.out, "density"), "density             2 g/cm³");
  EXPECT_EQ(line_of(cgs.out, "mass"), "mass                12 g");
  EXPECT_EQ(line_of(cgs.out, "bounding box"), "bounding box        [-0.5, -1, -1.5] .. [0.5, 1, 1.5] cm");

  const CliResult settle = run_cli("settle " + kBox + " --orientation axis-angle:1,0.5,0.2,1.2");
  ASSERT_EQ(settle.exit_code, 0) << settle.err;
  EXPECT_THAT(line_of(settle.out, "particle"), ::testing::EndsWith(" m)"));
  EXPECT_THAT(line_of(settle.out, "at rest"),
              ::testing::MatchesRegex("at rest         at t = [0-9.]+ s \\(the time to rest: the "
                                      "supporting face flush on the wall, nothing moving\\)"));
  EXPECT_THAT(line_of(settle.out, "centre of mass"), ::testing::EndsWith("] m"));
  EXPECT_THAT(line_of(settle.out, "energy"), ::testing::EndsWith(" J (kinetic + potential, from the wall)"));
  EXPECT_THAT(line_of(settle.out, "phases (s)"), StartsWith("phases (s)      "));
  const CliResult settle_cgs =
      run_cli("settle " + kBox + " --units cgs --orientation axis-angle:1,0.5,0.2,1.2");
  EXPECT_THAT(line_of(settle_cgs.out, "energy"), HasSubstr(" erg "));

  const CliResult poses = run_cli("poses " + kBox + " -n 20");
  EXPECT_THAT(poses.out, HasSubstr("quasi-static  COM height (m)  down normal (body)"));
  EXPECT_THAT(poses.out, HasSubstr("(L = 2.2545 m, 6 hull faces)"));

  const json si = {{"system", "si"},
                   {"length", "m"},
                   {"mass", "kg"},
                   {"time", "s"},
                   {"energy", "J"},
                   {"speed", "m/s"},
                   {"angular_speed", "rad/s"},
                   {"inertia", "kg·m²"},
                   {"damping", "kg·m²/s"}};
  EXPECT_EQ(parse_json(run_cli("settle " + kBox + " --json"))["units"], si);
  EXPECT_EQ(parse_json(run_cli("poses " + kBox + " -n 20 --json"))["units"], si);
  const json poses_cgs = parse_json(run_cli("poses " + kBox + " -n 20 --json --units cgs"))["units"];
  EXPECT_EQ(poses_cgs["length"], "cm");
  EXPECT_EQ(poses_cgs["energy"], "erg");
  const json info_units = parse_json(run_cli("info " + kBox + " --json"))["units"];
  EXPECT_EQ(info_units["density"], "kg/m³");
  EXPECT_EQ(info_units["area"], "m²");
}

// 5. An implausible size names --mesh-units; a plausible one, or the right unit, says nothing.
TEST_F(FirstHourCli, ImplausibleSizeNamesMeshUnits) {
  // A cube of edge 1 in mm read as m, scaled to the 433 mm of the issue's part: L = (6/π)^(1/3)·433 = 537 m.
  const std::string cube = std::string(REPOSE_TEST_DATA) + "/cube.obj";
  const CliResult big = run_cli("info " + cube + " --scale 433");
  EXPECT_EQ(big.exit_code, 0);
  EXPECT_THAT(big.err,
              ::testing::MatchesRegex(
                  "repose: warning: .*cube.obj: L = 537\\.[0-9]+ m is larger than 10 m; if the file is "
                  "not in metres, give --mesh-units mm\\|cm\\|m\\|in \\(or --scale\\)\n"));
  EXPECT_EQ(run_cli("info " + cube + " --scale 433 --mesh-units mm").exit_code, 2);  // one or the other
  EXPECT_EQ(run_cli("info " + cube + " --mesh-units mm").err, "");                   // 1.24 mm: plausible
  const CliResult small = run_cli("settle " + kBox + " --scale 1e-7");
  EXPECT_THAT(small.err, HasSubstr("is smaller than 1 µm; if the file is not in metres, give --mesh-units"));
  const CliResult poses = run_cli("poses " + cube + " --scale 433 -n 10");
  EXPECT_EQ(poses.exit_code, 0);
  EXPECT_THAT(poses.err, HasSubstr("m is larger than 10 m; if the file is not in metres, give --mesh-units"));
  // 433 cm in a cgs run is 4.33 m: plausible.
  EXPECT_EQ(run_cli("info " + cube + " --scale 433 --units cgs").err, "");
}

// 6. Typos answered with the closest valid names and that subcommand's help.
TEST_F(FirstHourCli, TyposAreAnsweredWithTheClosestNames) {
  expect_refused(run_cli("pose " + kBox),
                 "unknown subcommand 'pose' (did you mean poses?); the subcommands are info, settle, paper, "
                 "poses, merge or design (see repose --help)");
  expect_refused(run_cli("poses " + kBox + " --drop 2000"),
                 "poses: unknown option --drop (did you mean --drops/-n?) (see repose poses --help)");
  expect_refused(
      run_cli("settle " + kBox + " --orientaton identity"),
      "settle: unknown option --orientaton (did you mean --orientation?) (see repose settle --help)");
  expect_refused(run_cli("info " + kBox + " --josn"),
                 "info: unknown option --josn (did you mean --json?) (see repose info --help)");
  expect_refused(
      run_cli("xyzzy"),
      "unknown subcommand 'xyzzy'; the subcommands are info, settle, paper, poses, merge or design (see "
      "repose --help)");
  expect_refused(run_cli(""),
                 "a subcommand is required: info, settle, paper, poses, merge or design (see repose --help)");
  // Other parse errors point at the subcommand's help too.
  const CliResult missing = run_cli("info");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, ::testing::EndsWith(" (see repose info --help)\n"));
}

// 7. Ctrl-C: one line with the drops kept, where and how to resume, exit 130; the rerun says it resumed.
TEST_F(FirstHourCli, InterruptSaysWhatIsKeptAndTheRerunResumes) {
  const fs::path out = dir_ / "run";
  const std::string command = shell_quote(REPOSE_CLI) + " poses " + kBox + " -n 10000000 --chunk 200 --out " +
                              shell_quote(out.string());
  const fs::path checkpoint = out / ".repose-checkpoint" / "box_x=1_y=2_z=3.json";
  // Waits (at most 120 s) for `ready`, then sends SIGINT; stderr to ERR, the exit code to CODE.
  const auto interrupt = [&](const std::string& ready, const std::string& name) {
    const fs::path err = dir_ / (name + ".err"), code = dir_ / (name + ".code");
    const std::string script =
        command + " 2>" + shell_quote(err.string()) + " & pid=$!; i=0; until " + ready +
        " || [ $i -ge 2400 ]; do sleep 0.05; i=$((i+1)); done; kill -INT $pid; wait $pid; " + "echo $? >" +
        shell_quote(code.string());
    std::system(("sh -c " + shell_quote(script)).c_str());
    return std::make_pair(std::stoi(read_file(code)), read_file(err));
  };
  const auto [code, err] = interrupt("[ -f " + shell_quote(checkpoint.string()) + " ]", "first");
  EXPECT_EQ(code, 130);
  const std::string kept_dir = (out / ".repose-checkpoint").string();
  const auto [kept, after_kept] = number_after(err, "repose: interrupted: ");
  EXPECT_EQ(after_kept, " of 10000000 drops kept in " + kept_dir + "; rerun the same command to resume\n")
      << err;
  // The count is what the checkpoint holds (it may have grown by an item since the message: never shrunk).
  const json saved = json::parse(read_file(checkpoint));
  EXPECT_GE(kept, 200u);
  EXPECT_EQ(kept % 200, 0u);
  EXPECT_GE(saved["n"].get<std::uint64_t>(), kept);

  const auto [code2, err2] =
      interrupt("grep -q resuming " + shell_quote((dir_ / "second.err").string()), "second");
  EXPECT_EQ(code2, 130);
  const std::string first_line = err2.substr(0, err2.find('\n') + 1);
  const auto [found, after_found] = number_after(first_line, "repose: resuming from " + kept_dir + ": ");
  const auto [left, after_left] = number_after(after_found, " of 10000000 drops found there, ");
  EXPECT_EQ(after_left, " to run\n") << err2;
  EXPECT_EQ(found + left, 10000000u);
  EXPECT_GE(found, saved["n"].get<std::uint64_t>());
  // Then the interruption's own line.
  EXPECT_EQ(number_after(err2.substr(first_line.size()), "repose: interrupted: ").second,
            " of 10000000 drops kept in " + kept_dir + "; rerun the same command to resume\n");
}

// Without --out nothing is kept, and the message says how to keep it. SIGTERM (a batch system's kill) is
// reported alike, with 128 + 15.
TEST_F(FirstHourCli, InterruptWithoutOutSaysNothingIsKept) {
  for (const auto& [signal, expected] : {std::pair{"INT", 130}, std::pair{"TERM", 143}}) {
    const fs::path err = dir_ / signal, code = dir_ / (std::string(signal) + ".code");
    const std::string script = shell_quote(REPOSE_CLI) + " poses " + kBox + " -n 10000000 2>" +
                               shell_quote(err.string()) + " & pid=$!; sleep 3; kill -" + signal +
                               " $pid; wait $pid; echo $? >" + shell_quote(code.string());
    std::system(("sh -c " + shell_quote(script)).c_str());
    EXPECT_EQ(std::stoi(read_file(code)), expected) << signal;
    EXPECT_EQ(number_after(read_file(err), "repose: interrupted: ").second,
              " of 10000000 drops done and not kept (give --out DIR to keep a checkpoint that a rerun "
              "resumes)\n")
        << signal;
  }
}

// 8. settle's text says which time answers what, what dt is, and which start orientation it used.
TEST_F(FirstHourCli, SettleTextSaysWhatEachTimeIs) {
  const CliResult r = run_cli("settle " + kBox + " --orientation axis-angle:1,0.5,0.2,1.2");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(line_of(r.out, "start"), "start           axis-angle:1,0.5,0.2,1.2");
  EXPECT_THAT(
      line_of(r.out, "stable"),
      ::testing::MatchesRegex("stable          at t = [0-9.]+ s \\(the paper's stability test, §2.4, passed: "
                              "its run would stop here, the face up to contact-threshold above the "
                              "wall\\)"));
  EXPECT_THAT(line_of(r.out, "steps"),
              ::testing::MatchesRegex("steps           [0-9]+ adaptive steps, none longer than [0-9.]+ s"));
  const json j = parse_json(run_cli("settle " + kBox + " --orientation axis-angle:1,0.5,0.2,1.2 --json"));
  EXPECT_LT(j["stable_time"].get<double>(), j["time_to_rest"].get<double>());
  EXPECT_EQ(line_of(run_cli("settle " + kBox).out, "start"),
            "start           identity (the default: the mesh's axes; --orientation sets it)");
  EXPECT_THAT(line_of(run_cli("settle " + kBox + " --integrator paper --max-steps 3").out, "steps"),
              ::testing::MatchesRegex("steps           [0-9]+ steps of [0-9.e-]+ s"));
  const CliResult stopped =
      run_cli("settle " + kBox + " --orientation axis-angle:1,0.5,0.2,1.2 --max-steps 3");
  EXPECT_EQ(stopped.exit_code, 3);
  EXPECT_THAT(line_of(stopped.out, "not at rest"),
              ::testing::MatchesRegex(
                  "not at rest     stopped by --max-steps at t = [0-9.]+ s \\(raise it; exit code 3\\)"));
}

// 9. Numbers in the forms the help shows; more threads than cores warned about and capped.
TEST_F(FirstHourCli, NumbersInTheFormsTheHelpShows) {
  EXPECT_EQ(run_cli("settle " + kBox + " --max-steps 2e7").exit_code, 0);  // the help's own default
  EXPECT_EQ(parse_json(run_cli("poses " + kBox + " -n 5 --max-steps 3e4 --json"))["settings"]["max_steps"],
            30000);
  EXPECT_EQ(parse_json(run_cli("poses " + kBox + " -n 1e3 --json"))["n"], 1000);
  EXPECT_EQ(parse_json(run_cli("poses " + kBox + " --range 1e2:2.5e2 --json"))["drop_ranges"],
            json::parse("[[100, 250]]"));
  expect_refused(run_cli("poses " + kBox + " -n 1.5"),
                 "poses: --drops: must be a whole number >= 1, got '1.5' (see repose poses --help)");
  expect_refused(run_cli("poses " + kBox + " -n -3"),
                 "poses: --drops: must be a whole number >= 1, got '-3' (see repose poses --help)");
  const int cores = allowed_cpus();
  const CliResult many = run_cli("poses " + kBox + " -n 20 --threads 1000 --json");
  EXPECT_EQ(many.exit_code, 0);
  EXPECT_EQ(many.err, "repose: warning: --threads 1000 is more than the " + std::to_string(cores) +
                          " cores this process may use; using " + std::to_string(cores) + "\n");
  EXPECT_EQ(parse_json(many)["timing"]["threads"], cores);
}

// On a share of the machine (a container, taskset, a batch job's CPUs) "all cores" are the ones the process
// may run on: an arena sized by the machine's cores made TBB print a warning of its own on every run, and
// every one-line error became three lines. The CLI inherits this test's affinity, narrowed to one CPU here.
TEST_F(FirstHourCli, OnOneAllowedCoreARunPrintsNoWarning) {
  cpu_set_t all, one;
  ASSERT_EQ(sched_getaffinity(0, sizeof all, &all), 0);
  CPU_ZERO(&one);
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &all)) {
      CPU_SET(c, &one);
      break;
    }
  ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);
  const CliResult run = run_cli("poses " + kBox + " -n 20 --json");
  const CliResult bad = run_cli("poses " + kBox + " -n 20 --chunk 0");
  ASSERT_EQ(sched_setaffinity(0, sizeof all, &all), 0);
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_EQ(run.err, "");
  EXPECT_EQ(parse_json(run)["timing"]["threads"], 1);
  expect_bad_input(bad, {"--chunk"});
}

// 10. Contradictory or ignored combinations refused; a CSV given to merge named as such; a solid's area; and
// drops left unsettled exit 3 with their results written.
TEST_F(FirstHourCli, IgnoredCombinationsAndUnsettledDrops) {
  expect_refused(
      run_cli("poses " + kBox + " -n 20 --method quasi-static --full-settle"),
      "poses: --full-settle has no effect with --method quasi-static (it sets the dynamic engine's "
      "drops); remove it or use --method dynamic");
  expect_refused(run_cli("poses " + kBox + " -n 20 --method quasi-static --max-steps 5"),
                 "poses: --max-steps has no effect with --method quasi-static (it sets the dynamic engine's "
                 "drops); remove it or use --method dynamic");
  const std::string vtk = (dir_ / "vtk").string();
  expect_refused(
      run_cli("settle " + kBox + " --vtk " + vtk + " --frames 10 --frame-dt 0.1"),
      "settle: give --frames N (N frames spread over the run) or --frame-dt T (a frame every T), not "
      "both");
  expect_refused(run_cli("settle " + kBox + " --frames 10"),
                 "settle: --frames sets the ParaView frames of --vtk DIR, which is not given");
  expect_refused(
      run_cli("settle " + kBox + " --sample-dt 0.1"),
      "settle: --sample-dt spaces the samples written by --out, --vtk or --html, and none is given");

  const std::string out = (dir_ / "r").string();
  ASSERT_EQ(run_cli("poses " + kBox + " -n 20 --out " + out).exit_code, 0);
  const std::string csv = (dir_ / "r/poses.csv").string();
  expect_refused(
      run_cli("merge " + csv),
      csv +
          ": not a repose poses result file: not JSON (give the poses.json that repose poses --out "
          "writes; the CSV cannot be read back)");

  const json info = parse_json(run_cli("info " + kBox + " --json"));
  EXPECT_DOUBLE_EQ(info["area"].get<double>(), 22.0);  // 2(1·2 + 2·3 + 3·1)

  const std::string limited = (dir_ / "limited").string();
  const CliResult stopped = run_cli("poses " + kBox + " -n 200 --max-steps 5 --out " + limited);
  EXPECT_EQ(stopped.exit_code, 3);
  const json j = json::parse(read_file(dir_ / "limited/poses.json"));
  const auto unrested =
      j["status_counts"]["max_steps"].get<int>() + j["status_counts"]["max_time"].get<int>();
  EXPECT_GT(unrested, 0);
  EXPECT_EQ(stopped.err, "repose: warning: " + std::to_string(unrested) +
                             " of 200 drops did not come to rest within the limits: they are in no pose, so "
                             "the probabilities add up to less than 1 (status_counts; raise --max-time or "
                             "--max-steps); exit code 3\n");
  EXPECT_THAT(stopped.out,
              HasSubstr("max_steps " + std::to_string(j["status_counts"]["max_steps"].get<int>())));
  EXPECT_THAT(run_cli("--help").out,
              HasSubstr("3 not at rest (settle: the run; poses: some drops, results still written)"));
}

}  // namespace
