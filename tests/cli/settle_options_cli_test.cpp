// `repose settle` options checked by their values, against numbers the tests work out themselves: scenario
// files and the options that override them, --drop-speed, --max-time and exit code 3, --damping, and the
// contact and line thresholds.
//
// Exit code 1 (internal error) has no test: no input reaches it (missing, unreadable, directory, oversized or
// malformed inputs and unwritable outputs are all bad input, code 2), and the tool has no hook to force one.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using repose::test::CliResult;
using repose::test::csv_rows;
using repose::test::numbers;
using repose::test::parse_json;
using repose::test::read_file;
using repose::test::run_cli;
using repose::test::shell_quote;
using ::testing::HasSubstr;

class SettleOptionsCli : public repose::test::TempDirTest {};

// Volume and L of the regular tetrahedron of edge 1: a³ / (6 sqrt 2), and (6V/π)^(1/3).
const double kTetraVolume = 1 / (6 * std::numbers::sqrt2);
const double kTetraLength = std::cbrt(6 * kTetraVolume / std::numbers::pi);

// ---------------------------------------------------------------------------------------------------------
// --scenario FILE

TEST_F(SettleOptionsCli, PaperScenarioEqualsTheCommandWithItsValues) {
  // scenarios/paper/tetrahedron.json: edge 1 cm, 1.2 g/cm³, cgs, this vertex-down orientation.
  const std::string file = std::string(REPOSE_SOURCE_DIR) + "/scenarios/paper/tetrahedron.json";
  const json from_file = parse_json(run_cli("settle --scenario " + shell_quote(file) + " --json"));
  const json direct =
      parse_json(run_cli("settle tetrahedron:edge=1 --density 1.2 --units cgs --orientation "
                         "quat:0.502768,-0.662282,0.507678,0.225546 --json"));
  EXPECT_EQ(from_file.dump(), direct.dump());
  EXPECT_EQ(from_file["parameters"]["gravity"], 981.0);
  EXPECT_NEAR(from_file["particle"]["mass"].get<double>(), 1.2 * kTetraVolume, 1e-15);
  EXPECT_EQ(from_file["status"], "rest");
}

TEST_F(SettleOptionsCli, CommandLineOptionsOverrideTheScenario) {
  // A 1 x 2 x 3 m box of density 2 (m = 12 kg), tilted 0.7 rad about x, damping 3 from the file.
  const fs::path file = dir_ / "box.json";
  std::ofstream(file) << R"({"particle": "box:x=1,y=2,z=3", "density": 2, "units": "si",
                             "orientation": "axis-angle:1,0,0,0.7", "damping": 3})";
  const std::string box = "settle box:x=1,y=2,z=3 --density 2 --json";
  const std::string scenario = "settle --scenario " + shell_quote(file.string()) + " --json";

  const json plain = parse_json(run_cli(scenario));
  EXPECT_EQ(plain.dump(),
            parse_json(run_cli(box + " --orientation axis-angle:1,0,0,0.7 --damping 3")).dump());
  EXPECT_EQ(plain["parameters"]["damping"], 3.0);
  EXPECT_NEAR(plain["particle"]["mass"].get<double>(), 12.0, 1e-12);
  const std::vector<double> q = numbers(plain["parameters"]["initial_orientation"]);
  ASSERT_EQ(q.size(), 4u);
  EXPECT_NEAR(q[0], std::cos(0.35), 1e-15);
  EXPECT_NEAR(q[1], std::sin(0.35), 1e-15);

  // Damping and orientation from the command line; density still from the file.
  const json overridden = parse_json(run_cli(scenario + " --damping 0 --orientation axis-angle:1,0,0,0.8"));
  EXPECT_EQ(overridden.dump(),
            parse_json(run_cli(box + " --orientation axis-angle:1,0,0,0.8 --damping 0")).dump());
  EXPECT_EQ(overridden["parameters"]["damping"], 0.0);
  EXPECT_NEAR(overridden["particle"]["mass"].get<double>(), 12.0, 1e-12);
  EXPECT_NEAR(numbers(overridden["parameters"]["initial_orientation"])[1], std::sin(0.4), 1e-15);
  EXPECT_NE(overridden["time_to_rest"], plain["time_to_rest"]);

  // Density and units too: the same box in cgs is read as centimetres, g = 981.
  const json cgs = parse_json(run_cli(scenario + " --density 5 --units cgs"));
  EXPECT_EQ(cgs["parameters"]["gravity"], 981.0);
  EXPECT_NEAR(cgs["particle"]["mass"].get<double>(), 30.0, 1e-12);
}

TEST_F(SettleOptionsCli, ScenarioMeshPathIsRelativeToTheScenarioFile) {
  fs::create_directories(dir_ / "cases");
  fs::copy_file(std::string(REPOSE_TEST_DATA) + "/cube_ascii.stl", dir_ / "cases/cube.stl");
  std::ofstream(dir_ / "cases/cube.json") << R"({"particle": "cube.stl", "density": 3,
                                                 "orientation": "axis-angle:0,1,0,0.3"})";
  // Run from another directory: the path must not be taken relative to the working directory.
  const json from_file = parse_json(run_cli(
      "settle --scenario " + shell_quote((dir_ / "cases/cube.json").string()) + " --json", "cd / && "));
  const json direct = parse_json(run_cli("settle " + shell_quote((dir_ / "cases/cube.stl").string()) +
                                         " --density 3 --orientation axis-angle:0,1,0,0.3 --json"));
  json a = from_file, b = direct;
  a["particle"].erase("source");
  b["particle"].erase("source");
  EXPECT_EQ(a.dump(), b.dump());
  EXPECT_THAT(from_file["particle"]["source"].get<std::string>(), HasSubstr("cube.stl"));
}

// A scenario carries how its mesh is read (mesh_units or scale, inertia, repair, com): each run equals the
// command with the same options, and each mesh option given on the command line replaces the file's.
TEST_F(SettleOptionsCli, ScenarioCarriesTheMeshOptions) {
  fs::copy_file(std::string(REPOSE_TEST_DATA) + "/cube_ascii.stl", dir_ / "cube.stl");
  const std::string stl = shell_quote((dir_ / "cube.stl").string());
  const auto same_run = [&](const std::string& fields, const std::string& extra, const std::string& direct) {
    std::ofstream(dir_ / "s.json") << R"({"particle": "cube.stl", "density": 1000, )" + fields + "}";
    json a = parse_json(
        run_cli("settle --scenario " + shell_quote((dir_ / "s.json").string()) + " " + extra + " --json"));
    json b = parse_json(run_cli("settle " + stl + " --density 1000 " + direct + " --json"));
    a["particle"].erase("source");
    b["particle"].erase("source");
    EXPECT_EQ(a.dump(), b.dump()) << fields << " | " << extra;
    return a;
  };
  const json plain = parse_json(run_cli("settle " + stl + " --density 1000 --json"));
  const double volume = plain["particle"]["volume"].get<double>();
  const json mm = same_run(R"("mesh_units": "mm")", "", "--mesh-units mm");
  EXPECT_NEAR(mm["particle"]["volume"].get<double>(), 1e-9 * volume, 1e-12 * 1e-9 * volume);
  same_run(R"("mesh_units": "mm", "units": "cgs")", "", "--mesh-units mm --units cgs");  // 0.1 cm per mm
  same_run(R"("scale": 2)", "", "--scale 2");
  same_run(R"("mesh_units": "mm")", "--scale 2", "--scale 2");  // the command line's scale replaces the unit
  same_run(R"("inertia": "shell", "repair": true)", "", "--inertia shell --repair");
  same_run(R"("inertia": "shell")", "--inertia convex", "--inertia convex");
  same_run(R"("com": [0.4, 0.5, 0.5])", "", "--com 0.4,0.5,0.5");
  same_run(R"("com": [0.4, 0.5, 0.5])", "--com 0.5,0.5,0.6", "--com 0.5,0.5,0.6");
}

// ---------------------------------------------------------------------------------------------------------
// --drop-speed

TEST_F(SettleOptionsCli, DropSpeedGivesTheBallisticTouchdownAndInitialEnergy) {
  // A 1 m cube of density 2.5 (m = 2.5 kg) lying flat, its face h = 1 m above the wall, thrown down at
  // v = 2 m/s: it lands at t = (sqrt(v² + 2gh) − v)/g and stops there (a flat landing ends the motion).
  const double m = 2.5, g = 9.81, h = 1, v = 2;
  const fs::path out = dir_ / "run";
  const json j =
      parse_json(run_cli("settle box:x=1,y=1,z=1 --density 2.5 --drop-height 1 --drop-speed 2 "
                         "--json --out " +
                         shell_quote(out.string())));
  ASSERT_EQ(j["status"], "rest");
  const double touchdown = (std::sqrt(v * v + 2 * g * h) - v) / g;
  // Measured: 2e-14 relative (round-off in locating the touchdown). 1e-12 still sees any error in v or g,
  // which move it by > 1e-3; a drop from rest would land at sqrt(2h/g), 55 % later.
  ASSERT_GE(j["phases"].size(), 1u);
  EXPECT_EQ(j["phases"][0]["contact"], "free-fall");
  EXPECT_NEAR(j["phases"][0]["t1"].get<double>(), touchdown, 1e-12 * touchdown);
  EXPECT_NEAR(j["time_to_rest"].get<double>(), touchdown, 1e-12 * touchdown);
  // Energy: ½mv² + m·g·z_com with z_com = h + ½ (measured: exact to the last digit).
  const double start = 0.5 * m * v * v + m * g * (h + 0.5);
  EXPECT_NEAR(j["energy"]["start"].get<double>(), start, 1e-12 * start);
  EXPECT_NEAR(j["energy"]["end"].get<double>(), m * g * 0.5, 1e-12 * m * g);
  // The time series starts with the same split: kinetic ½mv², potential m·g·z_com (12 significant digits).
  const auto rows = csv_rows(read_file(out / "timeseries.csv"));
  ASSERT_FALSE(rows.empty());
  ASSERT_EQ(rows[0].size(), 17u);
  EXPECT_EQ(std::stod(rows[0][0]), 0.0);
  EXPECT_NEAR(std::stod(rows[0][13]), 0.5 * m * v * v, 1e-10);
  EXPECT_NEAR(std::stod(rows[0][14]), m * g * (h + 0.5), 1e-9);
}

// ---------------------------------------------------------------------------------------------------------
// --max-time, exit code 3

TEST_F(SettleOptionsCli, MaxTimeExitsThreeAtThatTime) {
  // The tilted tetrahedron (cgs) needs 0.043 s to rest; stopped at 0.01 s it is still on one vertex.
  const std::string tetra =
      "settle tetrahedron:edge=1 --density 1.2 --units cgs --orientation axis-angle:1,0.3,0,2.5";
  const std::string run = tetra + " --max-time 0.01";
  const fs::path out = dir_ / "run";
  const CliResult r = run_cli(run + " --json --out " + shell_quote(out.string()));
  EXPECT_EQ(r.err, "");
  const json j = parse_json(r, 3);
  EXPECT_EQ(j["status"], "max-time");
  EXPECT_TRUE(j["time_to_rest"].is_null());
  // The last step is cut to end on the limit (measured: exact).
  EXPECT_NEAR(j["time"].get<double>(), 0.01, 1e-15);
  EXPECT_EQ(j["rest"]["contact"], "none");
  EXPECT_EQ(j["rest"]["face"], -1);
  ASSERT_EQ(j["phases"].size(), 1u);
  EXPECT_EQ(j["phases"][0]["contact"], "point");
  // Rows at every 1e-3·sqrt(L/g) (the adaptive integrator's automatic interval) and at the limit.
  const auto rows = csv_rows(read_file(out / "timeseries.csv"));
  const double interval = 1e-3 * std::sqrt(kTetraLength / 981.0);
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(std::ceil(0.01 / interval)) + 1);
  EXPECT_NEAR(std::stod(rows.back()[0]), 0.01, 1e-12);  // 12 significant digits in the file

  const CliResult text = run_cli(run);
  EXPECT_EQ(text.exit_code, 3);
  EXPECT_THAT(text.out, HasSubstr("max-time"));
  // A limit past the rest changes nothing: exit 0.
  EXPECT_EQ(parse_json(run_cli(tetra + " --max-time 0.1 --json"))["status"], "rest");
}

TEST_F(SettleOptionsCli, ZeroStepAndTimeLimitMeanAutomatic) {
  // --dt 0 and --max-time 0 are the documented "automatic" values (--help): the longest step 0.2·sqrt(L/g)
  // of the adaptive integrator (1e-3·sqrt(L/g) for the paper's step) and a limit of 2000·sqrt(L/g) (no fall
  // here): the same run as without them, to the bit.
  const std::string tetra =
      "settle tetrahedron:edge=1 --units cgs --orientation axis-angle:1,0.3,0,2.5 --json";
  const json plain = parse_json(run_cli(tetra));
  const json zero = parse_json(run_cli(tetra + " --dt 0 --max-time 0"));
  const double scale = std::sqrt(kTetraLength / 981.0);
  EXPECT_NEAR(plain["parameters"]["dt"].get<double>(), 0.2 * scale, 1e-15);
  EXPECT_EQ(zero["parameters"]["dt"], plain["parameters"]["dt"]);
  EXPECT_EQ(zero["time"], plain["time"]);
  EXPECT_EQ(zero["steps"], plain["steps"]);
  const json paper = parse_json(run_cli(tetra + " --integrator paper"));
  const json paper_zero = parse_json(run_cli(tetra + " --integrator paper --dt 0 --max-time 0"));
  EXPECT_NEAR(paper["parameters"]["dt"].get<double>(), 1e-3 * scale, 1e-15);
  EXPECT_EQ(paper_zero["time"], paper["time"]);
  EXPECT_EQ(paper_zero["steps"], paper["steps"]);
  EXPECT_THAT(run_cli("settle --help").out,
              HasSubstr("0 or unset: automatic, 1e-3*sqrt(L/g) for paper, 0.2*sqrt(L/g) for adaptive"));
}

// ---------------------------------------------------------------------------------------------------------
// --damping

TEST_F(SettleOptionsCli, DampingSlowsTheFallButNotWhereItRests) {
  // The 1 x 2 x 3 m box of density 2 (m = 12 kg) tilted 0.7 rad about x, past its tipping angle atan(2/3),
  // pivots about an edge onto a 1 x 3 face. A damping moment −C·ω only slows the pivot (at every angle the
  // damped speed is lower), so the time to rest grows with C; the rest and both energies do not change:
  // start m·g·(sin 0.7 + 1.5 cos 0.7), the lowest corner on the wall; end m·g·1.
  const double m = 12, g = 9.81;
  const std::string run = "settle box:x=1,y=2,z=3 --density 2 --orientation axis-angle:1,0,0,0.7 --json";
  double previous = 0;
  for (const double c : {0.0, 3.0, 30.0}) {
    const json j = parse_json(run_cli(run + " --damping " + std::to_string(c)));
    ASSERT_EQ(j["status"], "rest") << c;
    EXPECT_EQ(j["parameters"]["damping"], c);
    const double t = j["time_to_rest"].get<double>();
    EXPECT_GT(t, previous) << "C = " << c;
    previous = t;
    const double start = m * g * (std::sin(0.7) + 1.5 * std::cos(0.7));
    EXPECT_NEAR(j["energy"]["start"].get<double>(), start, 1e-12 * start);
    // Measured: 7e-16 relative (the rest height 1 + 7e-16).
    EXPECT_NEAR(j["energy"]["end"].get<double>(), m * g, 1e-12 * m * g);
    EXPECT_NEAR(numbers(j["rest"]["com"])[2], 1.0, 1e-12);
  }
}

// ---------------------------------------------------------------------------------------------------------
// --contact-threshold and --line-threshold

// The contact sequence of the tilted tetrahedron (cgs) with extra options.
json tetra_run(const std::string& options) {
  return parse_json(
      run_cli("settle tetrahedron:edge=1 --density 1.2 --units cgs --orientation "
              "axis-angle:1,0.3,0,2.5 --json " +
              options));
}

std::vector<std::string> contacts(const json& j) {
  std::vector<std::string> names;
  for (const json& p : j["phases"]) names.push_back(p["contact"].get<std::string>());
  return names;
}

TEST_F(SettleOptionsCli, WiderContactBandEndsThePointPhaseEarlier) {
  // A vertex counts as a contact once it is within ε·L of the wall: the wider the band, the earlier the
  // second vertex joins the first, so the point phase ends earlier; the rest face and height do not change.
  double previous = 1e9;
  for (const double eps : {0.01, 0.05, 0.2}) {
    const json j = tetra_run("--contact-threshold " + std::to_string(eps));
    EXPECT_EQ(j["parameters"]["contact_threshold"], eps);
    ASSERT_EQ(contacts(j), (std::vector<std::string>{"point", "line", "surface"})) << eps;
    const double end = j["phases"][0]["t1"].get<double>();
    EXPECT_LT(end, previous) << "epsilon " << eps;
    previous = end;
    EXPECT_EQ(j["rest"]["contact"], "surface");
    // On a face: the centroid's height, a / sqrt 24 (measured error 2e-16).
    EXPECT_NEAR(numbers(j["rest"]["com"])[2], 1 / std::sqrt(24.0), 1e-12);
  }
}

TEST_F(SettleOptionsCli, LineThresholdSeparatesLineFromSurfaceAtTheFacesSpread) {
  // Three contacts are a line when the residual sum of squares of their best-fit line is below
  // threshold·L². For the landing face, an equilateral triangle of edge a = 1, that RSS is a²/2 (the
  // scatter is isotropic in the plane; the sum of squared distances from the centroid is a²). Just below
  // a²/(2L²) the landing is a surface contact; just above, the particle stays on a "line" until it rests.
  // The switch measured between 0.999 and 1.003 times a²/(2L²) (within the band, the third vertex is not yet
  // flush); 1 % on either side leaves ~3x that.
  const double spread = 0.5 / (kTetraLength * kTetraLength);
  const json below = tetra_run("--line-threshold " + std::to_string(0.99 * spread));
  const json above = tetra_run("--line-threshold " + std::to_string(1.01 * spread));
  EXPECT_NEAR(below["parameters"]["line_threshold"].get<double>(), 0.99 * spread, 1e-6);
  EXPECT_EQ(contacts(below), (std::vector<std::string>{"point", "line", "surface"}));
  ASSERT_EQ(contacts(above), (std::vector<std::string>{"point", "line", "surface"}));
  // Above: the line phase lasts until the rest; the surface phase is only the final instant.
  const double t = above["time_to_rest"].get<double>();
  EXPECT_EQ(above["phases"][1]["t1"].get<double>(), t);
  EXPECT_EQ(above["phases"][2]["t0"].get<double>(), t);
  EXPECT_LT(below["phases"][1]["t1"].get<double>(), below["phases"][2]["t1"].get<double>());
  // Both rest on a face at the centroid's height.
  for (const json* j : {&below, &above}) {
    EXPECT_EQ((*j)["rest"]["contact"], "surface");
    EXPECT_NEAR(numbers((*j)["rest"]["com"])[2], 1 / std::sqrt(24.0), 1e-12);
  }
}

}  // namespace
