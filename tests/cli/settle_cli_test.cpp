// `repose settle` through the real executable: the JSON summary of a known run, the human-readable output,
// the --out files, orientation specs, option validation, exit code 3, unit systems and drop height.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using repose::test::CliResult;
using repose::test::expect_bad_input;
using repose::test::numbers;
using repose::test::parse_json;
using repose::test::run_cli;
using ::testing::HasSubstr;
using ::testing::StartsWith;

/// The reference run: a regular tetrahedron (edge 1 cm) dropped on an edge-ish orientation in cgs units.
const std::string kTetra =
    "settle tetrahedron:edge=1 --density 1.2 --units cgs --orientation axis-angle:1,0.3,0,2.5";
const std::string kTiltedTetra = "settle tetrahedron:edge=1 --orientation axis-angle:1,0.3,0,2.5";

/// Single-quotes `s` for /bin/sh.
std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// "%.17g": a double that reads back exactly.
std::string exact(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

double norm(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

/// Rotates body-frame vector v by the unit quaternion q = [w, x, y, z].
std::vector<double> rotate(const std::vector<double>& q, const std::vector<double>& v) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  std::vector<double> out(3, 0.0);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) out[i] += r[i][k] * v[k];
  return out;
}

class SettleCli : public repose::test::TempDirTest {};

// ---------------------------------------------------------------------------------------------------------
// The reference run.

TEST_F(SettleCli, TetrahedronJsonSummary) {
  const CliResult r = run_cli(kTetra + " --json");
  EXPECT_EQ(r.err, "");
  const json j = parse_json(r);
  EXPECT_EQ(j["status"], "rest");
  const double t = j["time_to_rest"].get<double>();
  EXPECT_GT(t, 0.0);
  // Where the paper's run ends (its stability test): before the flush rest, which finishes the rotation.
  ASSERT_TRUE(j["stable_time"].is_number()) << j["stable_time"];
  EXPECT_GT(j["stable_time"].get<double>(), 0.0);
  EXPECT_LT(j["stable_time"].get<double>(), t);
  ASSERT_TRUE(j["steps"].is_number_integer());
  EXPECT_GT(j["steps"].get<long>(), 0);

  // L = volume-equivalent sphere diameter; regular tetrahedron of edge a has volume a³ / (6 sqrt 2).
  const double L = std::cbrt(6 * (1 / (6 * std::numbers::sqrt2)) / std::numbers::pi);
  EXPECT_NEAR(j["particle"]["characteristic_length"].get<double>(), L, 1e-12);
  EXPECT_GE(j["max_penetration"].get<double>(), 0.0);
  EXPECT_LE(j["max_penetration"].get<double>(), 1e-9 * L);

  const json& rest = j["rest"];
  const std::vector<double> q = numbers(rest["orientation"]);
  ASSERT_EQ(q.size(), 4u);
  EXPECT_NEAR(norm(q), 1.0, 1e-12);
  const std::vector<double> com = numbers(rest["com"]);
  ASSERT_EQ(com.size(), 3u);
  EXPECT_NEAR(com[2], std::sqrt(2.0 / 3.0) / 4, 1e-6);  // resting on a face: height of the centroid
  EXPECT_EQ(rest["contact"], "surface");
  ASSERT_TRUE(rest["contact_points"].is_array());
  ASSERT_EQ(rest["contact_points"].size(), 3u);
  for (const json& p : rest["contact_points"]) {
    ASSERT_EQ(p.size(), 3u);
    EXPECT_NEAR(p[2].get<double>(), 0.0, 1e-9 * L);
  }
  const std::vector<double> down = numbers(rest["down_normal_body"]);
  ASSERT_EQ(down.size(), 3u);
  EXPECT_NEAR(norm(down), 1.0, 1e-12);
  // The body-frame down normal, rotated by the rest orientation, points at the wall (world −z).
  const std::vector<double> down_world = rotate(q, down);
  EXPECT_NEAR(down_world[0], 0.0, 1e-9);
  EXPECT_NEAR(down_world[1], 0.0, 1e-9);
  EXPECT_NEAR(down_world[2], -1.0, 1e-9);

  ASSERT_TRUE(j["phases"].is_array());
  std::vector<std::string> contacts;
  double previous_end = 0.0;
  for (const json& p : j["phases"]) {
    contacts.push_back(p["contact"].get<std::string>());
    const double t0 = p["t0"].get<double>(), t1 = p["t1"].get<double>();
    EXPECT_LE(t0, t1);
    EXPECT_EQ(t0, previous_end) << "phases must be contiguous";
    previous_end = t1;
  }
  EXPECT_EQ(contacts, (std::vector<std::string>{"point", "line", "surface"}));
  EXPECT_DOUBLE_EQ(previous_end, t);
  EXPECT_GT(j["energy"]["start"].get<double>(), j["energy"]["end"].get<double>());
}

/// True if some "[a, b, c]" in `text` holds three numbers equal to `v` within a relative 1e-8 (the text
/// output prints 10 significant digits).
bool contains_vector(const std::string& text, const std::vector<double>& v) {
  for (size_t open = text.find('['); open != std::string::npos; open = text.find('[', open + 1)) {
    const size_t close = text.find(']', open);
    if (close == std::string::npos) break;
    std::stringstream in(text.substr(open + 1, close - open - 1));
    std::vector<double> got;
    std::string item;
    while (std::getline(in, item, ',')) {
      try {
        got.push_back(std::stod(item));
      } catch (...) {
        break;
      }
    }
    if (got.size() != v.size()) continue;
    bool same = true;
    for (size_t i = 0; i < v.size(); ++i)
      same = same && std::abs(got[i] - v[i]) <= 1e-8 * std::abs(v[i]) + 1e-12;
    if (same) return true;
  }
  return false;
}

TEST_F(SettleCli, TetrahedronTextOutputShowsRestAndCom) {
  const json j = parse_json(run_cli(kTetra + " --json"));
  const CliResult r = run_cli(kTetra);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_THAT(r.out, HasSubstr("rest"));
  EXPECT_TRUE(contains_vector(r.out, numbers(j["rest"]["com"])))
      << "centre of mass " << j["rest"]["com"] << " not in:\n"
      << r.out;
}

// ---------------------------------------------------------------------------------------------------------
// --out DIR.

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string f;
  while (std::getline(in, f, sep)) fields.push_back(f);
  if (!line.empty() && line.back() == sep) fields.push_back("");
  return fields;
}

TEST_F(SettleCli, OutWritesTimeSeriesAndSummary) {
  const fs::path out = dir_ / "run" / "nested";  // created by repose
  const CliResult r = run_cli(kTetra + " --json --out " + quote(out.string()));
  const json j = parse_json(r);
  ASSERT_TRUE(fs::is_directory(out));
  EXPECT_EQ(entries(out), (std::vector<std::string>{"summary.json", "timeseries.csv"}))
      << "only the two result files, no temporary files left";

  EXPECT_EQ(slurp(out / "summary.json"), r.out);

  std::ifstream csv(out / "timeseries.csv");
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line,
            "t,qw,qx,qy,qz,omega_x,omega_y,omega_z,com_x,com_y,com_z,contact,contact_count,kinetic_energy,"
            "potential_energy,sticking,sliding");
  const std::set<std::string> contact_names = {"free-fall", "point", "line", "surface"};
  std::vector<std::vector<double>> rows;
  while (std::getline(csv, line)) {
    const std::vector<std::string> f = split(line, ',');
    ASSERT_EQ(f.size(), 17u) << line;
    std::vector<double> row;
    for (size_t i = 0; i < f.size(); ++i) {
      if (i == 11) {
        EXPECT_TRUE(contact_names.count(f[i])) << line;
        row.push_back(0);
        continue;
      }
      size_t used = 0;
      double x = 0;
      ASSERT_NO_THROW(x = std::stod(f[i], &used)) << line;
      EXPECT_EQ(used, f[i].size()) << line;
      EXPECT_TRUE(std::isfinite(x)) << line;
      row.push_back(x);
    }
    rows.push_back(row);
  }
  // With the default (adaptive) integrator the series holds the initial state, every multiple of the
  // automatic interval 1e-3·sqrt(L/g) before the rest, and the rest: 1 + ceil(T/Δ) rows.
  const double length = std::cbrt(6 / (6 * std::numbers::sqrt2) / std::numbers::pi);  // L, edge 1
  const double interval = 1e-3 * std::sqrt(length / 981.0);
  const double rest_time = j["time"].get<double>();
  ASSERT_EQ(rows.size(), static_cast<size_t>(std::ceil(rest_time / interval)) + 1);
  for (size_t i = 1; i + 1 < rows.size(); ++i)  // the file has 9 significant digits
    ASSERT_NEAR(rows[i][0], i * interval, 1e-8 * i * interval) << "row " << i;
  for (size_t i = 1; i < rows.size(); ++i) ASSERT_LE(rows[i - 1][0], rows[i][0]) << "row " << i;
  EXPECT_EQ(rows.front()[0], 0.0);
  const double t = j["time_to_rest"].get<double>();
  EXPECT_NEAR(rows.back()[0], t, 1e-9 * t);
  const std::vector<double> com = numbers(j["rest"]["com"]);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(rows.back()[8 + k], com[k], 1e-10) << "com " << k;
  EXPECT_EQ(rows.back()[12], 3.0);  // three contact points at rest
}

TEST_F(SettleCli, SampleIntervalAndThePaperIntegratorSetTheRows) {
  // --sample-dt S: rows at 0, S, 2S, ... and the rest; --integrator paper: one row per step (its default),
  // the same rest as the adaptive run within the trapezoidal rule's error (measured 2e-8 of the time; 1e-6).
  const fs::path a = dir_ / "a", b = dir_ / "b";
  const json ja = parse_json(run_cli(kTetra + " --json --sample-dt 0.002 --out " + quote(a.string())));
  const json jb = parse_json(run_cli(kTetra + " --json --integrator paper --out " + quote(b.string())));
  auto times = [&](const fs::path& dir) {
    std::ifstream csv(dir / "timeseries.csv");
    std::string line;
    std::getline(csv, line);
    std::vector<double> t;
    while (std::getline(csv, line)) t.push_back(std::stod(line.substr(0, line.find(','))));
    return t;
  };
  const std::vector<double> ta = times(a), tb = times(b);
  const double rest = ja["time"].get<double>();
  ASSERT_EQ(ta.size(), static_cast<size_t>(std::ceil(rest / 0.002)) + 1);
  for (size_t i = 0; i + 1 < ta.size(); ++i) EXPECT_NEAR(ta[i], 0.002 * i, 1e-8 * 0.002 * i);  // 9 digits
  EXPECT_NEAR(ta.back(), rest, 1e-8 * rest);
  EXPECT_EQ(jb["parameters"]["integrator"], "paper");
  EXPECT_EQ(ja["parameters"]["integrator"], "adaptive");
  EXPECT_EQ(ja["parameters"]["tolerance"].get<double>(), 1e-9);  // the default, reported
  EXPECT_EQ(tb.size(), jb["steps"].get<size_t>() + 1);
  EXPECT_EQ(jb["rest"]["face"], ja["rest"]["face"]);
  EXPECT_NEAR(jb["time"].get<double>(), rest, 1e-6 * rest);
  // The series does not change the run: the same summary as without --out.
  const json plain = parse_json(run_cli(kTetra + " --json"));
  EXPECT_EQ(plain["time"], ja["time"]);
  EXPECT_EQ(plain["rest"], ja["rest"]);
}

TEST_F(SettleCli, OutIntoExistingDirectoryKeepsOtherFiles) {
  std::ofstream(dir_ / "notes.txt") << "mine\n";
  const CliResult r = run_cli(kTiltedTetra + " --out " + quote(dir_.string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(entries(dir_), (std::vector<std::string>{"notes.txt", "summary.json", "timeseries.csv"}));
  EXPECT_EQ(slurp(dir_ / "notes.txt"), "mine\n");
}

TEST_F(SettleCli, OutBelowRegularFileExitsTwoAndCreatesNothing) {
  expect_bad_input(run_cli(kTiltedTetra + " --out /dev/null/x"), {"/dev/null/x"});

  const fs::path file = dir_ / "plain";
  std::ofstream(file) << "data\n";
  const std::string below = (file / "sub").string();
  expect_bad_input(run_cli(kTiltedTetra + " --out " + quote(below)), {below});
  expect_bad_input(run_cli(kTiltedTetra + " --out " + quote(file.string())),
                   {file.string(), "not a directory"});
  EXPECT_EQ(entries(dir_), std::vector<std::string>{"plain"});
  EXPECT_EQ(slurp(file), "data\n");
}

// ---------------------------------------------------------------------------------------------------------
// Orientation specs.

/// The parts of a summary that depend on the initial orientation, compared within `tol`.
void expect_same_run(const json& a, const json& b, double tol) {
  EXPECT_EQ(a["status"], b["status"]);
  EXPECT_EQ(a["rest"]["face"], b["rest"]["face"]);
  EXPECT_EQ(a["rest"]["contact"], b["rest"]["contact"]);
  EXPECT_NEAR(a["time_to_rest"].get<double>(), b["time_to_rest"].get<double>(), tol);
  for (const char* key : {"orientation", "com", "down_normal_body"}) {
    const std::vector<double> x = numbers(a["rest"][key]), y = numbers(b["rest"][key]);
    ASSERT_EQ(x.size(), y.size()) << key;
    for (size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(x[i], y[i], tol) << key << i;
  }
  const std::vector<double> q0 = numbers(a["parameters"]["initial_orientation"]);
  const std::vector<double> q1 = numbers(b["parameters"]["initial_orientation"]);
  ASSERT_EQ(q0.size(), 4u);
  ASSERT_EQ(q1.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(q0[i], q1[i], 1e-15) << "initial orientation " << i;
}

TEST_F(SettleCli, UnitQuaternionIdentityEqualsIdentity) {
  const std::string base = "settle tetrahedron:edge=1 --json --orientation ";
  const json identity = parse_json(run_cli(base + "identity"));
  const json quat = parse_json(run_cli(base + "quat:1,0,0,0"));
  const json scaled = parse_json(run_cli(base + "quat:2.5,0,0,0"));
  expect_same_run(identity, quat, 1e-12);
  expect_same_run(identity, scaled, 1e-12);
  EXPECT_EQ(numbers(identity["parameters"]["initial_orientation"]), (std::vector<double>{1, 0, 0, 0}));
}

TEST_F(SettleCli, NonUnitAxisAndQuaternionEqualUnitForms) {
  // Axis (1, 0.3, 0) and angle 2.5 rad; the unit axis and the unit quaternion of the same rotation.
  const double n = std::hypot(1.0, 0.3);
  const double ux = 1.0 / n, uy = 0.3 / n, half = 2.5 / 2;
  const std::string base = "settle tetrahedron:edge=1 --json --orientation ";
  const json unit_axis = parse_json(run_cli(base + "axis-angle:" + exact(ux) + "," + exact(uy) + ",0,2.5"));
  const json scaled_axis = parse_json(run_cli(base + "axis-angle:10,3,0,2.5"));
  const std::vector<double> q = {std::cos(half), ux * std::sin(half), uy * std::sin(half), 0.0};
  const json unit_quat =
      parse_json(run_cli(base + "quat:" + exact(q[0]) + "," + exact(q[1]) + "," + exact(q[2]) + ",0"));
  const json scaled_quat = parse_json(
      run_cli(base + "quat:" + exact(3 * q[0]) + "," + exact(3 * q[1]) + "," + exact(3 * q[2]) + ",0"));
  ASSERT_EQ(unit_axis["status"], "rest");
  expect_same_run(unit_axis, scaled_axis, 1e-9);
  expect_same_run(unit_axis, unit_quat, 1e-9);
  expect_same_run(unit_axis, scaled_quat, 1e-9);
}

struct BadCase {
  const char* name;  ///< test name suffix
  std::string args;  ///< arguments after "settle"
  std::vector<std::string> expected;
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << "settle " << c.args; }

class SettleBadInput : public SettleCli, public ::testing::WithParamInterface<BadCase> {};

TEST_P(SettleBadInput, ExitsTwoWithOneLineNamingInputAndProblem) {
  expect_bad_input(run_cli("settle " + GetParam().args), GetParam().expected);
  EXPECT_TRUE(entries(dir_).empty());
}

BadCase orientation(const char* name, const std::string& spec, const std::string& problem) {
  return {name, "tetrahedron:edge=1 --orientation " + quote(spec), {"orientation '" + spec + "'", problem}};
}

std::string case_name(const ::testing::TestParamInfo<BadCase>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(
    Orientations, SettleBadInput,
    ::testing::Values(orientation("ZeroQuaternion", "quat:0,0,0,0", "zero quaternion"),
                      orientation("ZeroAxis", "axis-angle:0,0,0,1", "zero axis"),
                      orientation("ThreeQuaternionValues", "quat:1,2,3", "expected 4 numbers, got 3"),
                      orientation("FiveQuaternionValues", "quat:1,0,0,0,0", "expected 4 numbers, got 5"),
                      orientation("NonNumericQuaternion", "quat:a,b,c,d", "'a' is not a finite number"),
                      orientation("UnknownKind", "euler:1,2,3", "unknown kind 'euler'"),
                      orientation("NanQuaternion", "quat:nan,0,0,0", "'nan' is not a finite number"),
                      orientation("InfQuaternion", "quat:1,0,0,inf", "'inf' is not a finite number"),
                      orientation("NanAngle", "axis-angle:1,0,0,nan", "'nan' is not a finite number"),
                      orientation("NanAxis", "axis-angle:nan,0,0,1", "'nan' is not a finite number"),
                      orientation("Empty", "", "unknown kind")),
    case_name);

INSTANTIATE_TEST_SUITE_P(
    Options, SettleBadInput,
    ::testing::Values(
        // --dt 0 means automatic, so only negative and non-finite steps are bad.
        BadCase{"NegativeDt", "tetrahedron:edge=1 --dt -1", {"dt", "positive", "-1"}},
        BadCase{"NanDt", "tetrahedron:edge=1 --dt nan", {"dt", "nan"}},
        BadCase{"NonNumericDt", "tetrahedron:edge=1 --dt abc", {"--dt", "abc"}},
        BadCase{"NegativeDamping", "tetrahedron:edge=1 --damping -1", {"damping", ">= 0", "-1"}},
        BadCase{"ZeroContactThreshold",
                "tetrahedron:edge=1 --contact-threshold 0",
                {"contact-threshold", "(0, 1)"}},
        BadCase{"LargeContactThreshold",
                "tetrahedron:edge=1 --contact-threshold 1.5",
                {"contact-threshold", "(0, 1)", "1.5"}},
        BadCase{"NegativeDropHeight", "tetrahedron:edge=1 --drop-height -1", {"drop-height", ">= 0", "-1"}},
        BadCase{"NegativeDropSpeed", "tetrahedron:edge=1 --drop-speed -1", {"drop-speed", ">= 0", "-1"}},
        BadCase{"ImperialUnits", "tetrahedron:edge=1 --units imperial", {"--units", "imperial"}},
        BadCase{"SmoothMaybe", "tetrahedron:edge=1 --smooth maybe", {"--smooth", "maybe"}},
        BadCase{"NegativeMaxTime", "tetrahedron:edge=1 --max-time -1", {"max-time", "-1"}},
        BadCase{"ZeroMaxSteps", "tetrahedron:edge=1 --max-steps 0", {"max-steps", "positive"}},
        BadCase{"ZeroDensity", "tetrahedron:edge=1 --density 0", {"--density", "positive", "0"}},
        BadCase{"UnknownOption", "tetrahedron:edge=1 --bogus", {"--bogus"}},
        BadCase{"MissingParticle", "--json", {"particle"}},
        BadCase{"UnknownShape", "blob:x=1", {"blob", "unknown shape"}},
        BadCase{"BadMeshFile",
                quote(std::string(REPOSE_TEST_DATA) + "/open_cube.off"),
                {"open_cube.off:", "open surface"}}),
    case_name);

TEST_F(SettleCli, BadOrientationIsCheckedBeforeOutputDirectoryIsCreated) {
  const fs::path out = dir_ / "run";
  expect_bad_input(
      run_cli("settle tetrahedron:edge=1 --orientation quat:0,0,0,0 --out " + quote(out.string())),
      {"orientation 'quat:0,0,0,0'"});
  EXPECT_FALSE(fs::exists(out));
}

// ---------------------------------------------------------------------------------------------------------
// Runs that end without rest, units, drop height.

TEST_F(SettleCli, MaxStepsExitsThreeWithStatus) {
  const CliResult r = run_cli(kTiltedTetra + " --max-steps 5 --json");
  EXPECT_EQ(r.err, "");
  const json j = parse_json(r, 3);
  EXPECT_EQ(j["status"], "max-steps");
  EXPECT_EQ(j["steps"].get<long>(), 5);

  const CliResult text = run_cli(kTiltedTetra + " --max-steps 5");
  EXPECT_EQ(text.exit_code, 3);
  EXPECT_THAT(text.out, HasSubstr("max-steps"));
}

TEST_F(SettleCli, SiAndCgsGiveSameRestForSameBox) {
  // The same 1 m x 2 m x 3 m box, in metres (g = 9.81) and in centimetres (g = 981), tilted 0.7 rad on an
  // edge: past its tipping angle atan(2/3), so it falls onto a side face. Time scales as sqrt(L/g): equal.
  const std::string tilt = " --orientation axis-angle:1,0,0,0.7 --json";
  const json si = parse_json(run_cli("settle box:x=1,y=2,z=3 --units si" + tilt));
  const json cgs = parse_json(run_cli("settle box:x=100,y=200,z=300 --units cgs" + tilt));
  ASSERT_EQ(si["status"], "rest");
  ASSERT_EQ(cgs["status"], "rest");
  EXPECT_EQ(si["rest"]["face"], cgs["rest"]["face"]);
  EXPECT_EQ(si["rest"]["contact"], "surface");
  EXPECT_EQ(cgs["rest"]["contact"], "surface");
  const std::vector<double> n_si = numbers(si["rest"]["down_normal_body"]);
  const std::vector<double> n_cgs = numbers(cgs["rest"]["down_normal_body"]);
  ASSERT_EQ(n_si.size(), 3u);
  ASSERT_EQ(n_cgs.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(n_si[i], n_cgs[i], 1e-9);
  // It tipped over onto a y face (|down normal| along body y), where the COM is 1 m = 100 cm high.
  EXPECT_NEAR(std::abs(n_si[1]), 1.0, 1e-9);
  EXPECT_NEAR(numbers(si["rest"]["com"])[2], 1.0, 1e-9);
  EXPECT_NEAR(numbers(cgs["rest"]["com"])[2], 100.0, 1e-7);
  const double t = si["time_to_rest"].get<double>();
  EXPECT_NEAR(cgs["time_to_rest"].get<double>(), t, 1e-9 * t);
}

TEST_F(SettleCli, DropHeightFreeFallTime) {
  // A unit cube lying flat, its lowest face 1 m above the wall: it lands after sqrt(2 h / g) and stops there
  // (a flat landing is perfectly inelastic in the kinematic model).
  const json j = parse_json(run_cli("settle box:x=1,y=1,z=1 --drop-height 1 --json"));
  EXPECT_EQ(j["status"], "rest");
  const double fall = std::sqrt(2 * 1.0 / 9.81);
  EXPECT_NEAR(j["time_to_rest"].get<double>(), fall, 1e-6 * fall);
  ASSERT_TRUE(j["phases"].is_array());
  ASSERT_GE(j["phases"].size(), 2u);
  EXPECT_EQ(j["phases"][0]["contact"], "free-fall");
  EXPECT_EQ(j["phases"][0]["t0"].get<double>(), 0.0);
  EXPECT_NEAR(j["phases"][0]["t1"].get<double>(), fall, 1e-6 * fall);
  EXPECT_EQ(j["phases"].back()["contact"], "surface");
  EXPECT_NEAR(numbers(j["rest"]["com"])[2], 0.5, 1e-9);
  // Energy: m g (h + 1/2) at the start, m g / 2 at rest (m = 1).
  EXPECT_NEAR(j["energy"]["start"].get<double>(), 9.81 * 1.5, 1e-9);
  EXPECT_NEAR(j["energy"]["end"].get<double>(), 9.81 * 0.5, 1e-9);
}

}  // namespace
