// `repose info` through the real executable: every class of bad input exits 2 with a one-line message that
// names the input and the problem (and prints nothing on stdout); good input gives stable JSON fields; the
// validated surface survives a --write-stl round trip.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

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
using repose::test::expect_bad_input;
using repose::test::parse_json;
using repose::test::run_cli;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kData = REPOSE_TEST_DATA;

/// Single-quotes `s` for /bin/sh.
std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string data(const std::string& name) { return quote(kData + "/" + name); }

class InfoCli : public repose::test::TempDirTest {};

// ---------------------------------------------------------------------------------------------------------
// Bad input: files.

struct BadCase {
  const char* name;  ///< test name suffix
  std::string args;  ///< arguments after "info"
  std::vector<std::string> expected;
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << "info " << c.args; }

class InfoBadInput : public InfoCli, public ::testing::WithParamInterface<BadCase> {};

TEST_P(InfoBadInput, ExitsTwoWithOneLineNamingInputAndProblem) {
  expect_bad_input(run_cli("info " + GetParam().args), GetParam().expected);
  EXPECT_TRUE(entries().empty()) << "info must not create files";
}

std::vector<BadCase> bad_file_cases() {
  const auto file = [](const char* name, const char* file_name, std::vector<std::string> problem) {
    problem.insert(problem.begin(), std::string(file_name) + ":");
    return BadCase{name, data(file_name), problem};
  };
  return {
      file("EmptyFile", "empty.stl", {"empty file"}),
      file("TruncatedBinaryStl", "truncated.stl", {"truncated binary STL", "12 triangles"}),
      file("StlHeaderClaimsBillionsOfFaces", "huge_count.stl", {"truncated binary STL", "2147483648"}),
      file("PlyHeaderClaimsBillionsOfFaces", "huge_faces_binary.ply", {"1000000000 'face' elements"}),
      file("PlyHeaderClaimsBillionsOfVertices", "huge_vertices.ply", {"1000000000 'vertex' elements"}),
      file("OffHeaderClaimsBillions", "huge.off", {"OFF header claims 1000000000"}),
      file("TruncatedOff", "truncated.off", {"truncated OFF"}),
      file("TruncatedAsciiPly", "truncated_ascii.ply", {"truncated PLY"}),
      file("TruncatedBinaryPly", "truncated_binary.ply", {"truncated PLY"}),
      file("FaceIndexOutOfRangeOff", "bad_index.off", {"vertex index 8 does not exist"}),
      file("FaceIndexOutOfRangeObj", "bad_index.obj", {"does not exist"}),
      file("FaceIndexOutOfRangePly", "bad_index.ply", {"vertex index 8 does not exist"}),
      file("NanCoordinateOff", "nan.off", {"non-finite coordinate"}),
      file("NanCoordinateStl", "nan.stl", {"non-finite coordinate"}),
      file("InfCoordinateObj", "inf.obj", {"non-finite coordinate"}),
      file("OpenSurface", "open_cube.off",
           {"open surface", "boundary edges", "--repair", "--inertia convex"}),
      file("InconsistentWinding", "flipped_face.off", {"inconsistent winding"}),
      file("ZeroVolume", "flat.off", {"zero volume"}),
      file("NonManifold", "nonmanifold.off", {"non-manifold"}),
      file("NoTriangles", "lines_only.obj", {"no faces", "--inertia convex"}),
      file("UnsupportedFormat", "unknown.abc", {"unsupported format"}),
  };
}

std::vector<BadCase> bad_option_cases() {
  const std::string cube = data("cube.off");
  return {
      {"UnknownShape", "blob:x=1", {"blob", "unknown shape"}},
      {"ShapeMissingParameter", "box:x=1,y=2", {"box:x=1,y=2", "missing parameter 'z'"}},
      {"ShapeNegativeParameter", "box:x=1,y=2,z=-1", {"box:x=1,y=2,z=-1", "'z'", "positive"}},
      {"ShapeNonNumericParameter", "box:x=1,y=2,z=abc", {"box:x=1,y=2,z=abc", "'z'", "abc"}},
      {"ShapeNanParameter", "box:x=1,y=2,z=nan", {"box:x=1,y=2,z=nan", "'z'", "finite"}},
      {"ShapeUnknownParameter", "box:x=1,y=2,z=3,w=4", {"box:x=1,y=2,z=3,w=4", "unknown parameter 'w'"}},
      {"ZeroDensity", cube + " --density 0", {"--density", "positive", "0"}},
      {"NegativeDensity", cube + " --density -1", {"--density", "positive", "-1"}},
      {"NanDensity", cube + " --density nan", {"--density", "finite", "nan"}},
      {"NonNumericDensity", cube + " --density heavy", {"--density", "heavy"}},
      {"UnknownOption", cube + " --bogus", {"--bogus"}},
      {"MissingPositional", "--json", {"particle", "required"}},
      {"ExtraPositional", cube + " extra", {"extra"}},
  };
}

std::string case_name(const ::testing::TestParamInfo<BadCase>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Files, InfoBadInput, ::testing::ValuesIn(bad_file_cases()), case_name);
INSTANTIATE_TEST_SUITE_P(SpecsAndOptions, InfoBadInput, ::testing::ValuesIn(bad_option_cases()), case_name);

TEST_F(InfoCli, NonexistentFileIsNamed) {
  const std::string path = (dir_ / "missing.stl").string();
  expect_bad_input(run_cli("info " + quote(path)), {path + ":", "cannot open"});
  EXPECT_TRUE(entries().empty());
}

TEST_F(InfoCli, DirectoryIsRejected) {
  const fs::path sub = dir_ / "meshes.stl";
  fs::create_directory(sub);
  expect_bad_input(run_cli("info " + quote(sub.string())), {sub.string() + ":", "directory"});
}

TEST_F(InfoCli, EmptyFileInTempDirectoryIsNamed) {
  const std::string path = (dir_ / "nothing.obj").string();
  std::ofstream(path).close();
  expect_bad_input(run_cli("info " + quote(path)), {path + ":", "empty"});
}

// ---------------------------------------------------------------------------------------------------------
// Repairs with a warning.

TEST_F(InfoCli, InvertedWindingIsFixedWithWarning) {
  const CliResult text = run_cli("info " + data("inverted_cube.off"));
  EXPECT_EQ(text.exit_code, 0) << text.err;
  // The warning may go to either stream; it must be shown to the user.
  EXPECT_THAT(text.out + text.err, AllOf(HasSubstr("warning"), HasSubstr("inverted winding")));

  const json j = parse_json(run_cli("info " + data("inverted_cube.off") + " --json"));
  ASSERT_TRUE(j.contains("warnings"));
  ASSERT_TRUE(j["warnings"].is_array());
  ASSERT_EQ(j["warnings"].size(), 1u) << j["warnings"];
  EXPECT_THAT(j["warnings"][0].get<std::string>(), HasSubstr("inverted winding"));
  EXPECT_NEAR(j["volume"].get<double>(), 1.0, 1e-12);  // repaired: positive volume
}

TEST_F(InfoCli, CleanMeshHasNoWarnings) {
  const json j = parse_json(run_cli("info " + data("cube.off") + " --json"));
  ASSERT_TRUE(j["warnings"].is_array());
  EXPECT_TRUE(j["warnings"].empty()) << j["warnings"];
  EXPECT_NEAR(j["volume"].get<double>(), 1.0, 1e-12);
}

// ---------------------------------------------------------------------------------------------------------
// Good input: JSON fields and values.

void expect_vec(const json& v, const std::vector<double>& expected, double tol, const std::string& what) {
  ASSERT_TRUE(v.is_array()) << what;
  ASSERT_EQ(v.size(), expected.size()) << what;
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(v[i].get<double>(), expected[i], tol) << what << i;
}

TEST_F(InfoCli, BoxJsonHasStableFieldsWithRightValues) {
  const CliResult r = run_cli("info box:x=1,y=2,z=3 --json");
  EXPECT_EQ(r.err, "");
  const json j = parse_json(r);
  for (const char* key : {"volume", "mass", "center_of_mass", "inertia", "principal_moments",
                          "principal_axes", "bounding_box", "characteristic_length", "hull", "warnings"})
    EXPECT_TRUE(j.contains(key)) << key;

  const double tol = 1e-12;
  EXPECT_NEAR(j["volume"].get<double>(), 6.0, tol);
  EXPECT_NEAR(j["mass"].get<double>(), 6.0, tol);  // default density 1
  expect_vec(j["center_of_mass"], {0, 0, 0}, tol, "center_of_mass");
  // Solid box about its centre: Ixx = m (y² + z²) / 12 etc., no products of inertia.
  const double m = 6.0;
  const std::vector<double> diag = {m * (4 + 9) / 12, m * (1 + 9) / 12, m * (1 + 4) / 12};
  ASSERT_TRUE(j["inertia"].is_array());
  ASSERT_EQ(j["inertia"].size(), 3u);
  for (int i = 0; i < 3; ++i) {
    std::vector<double> row(3, 0.0);
    row[i] = diag[i];
    expect_vec(j["inertia"][i], row, tol, "inertia row ");
  }
  expect_vec(j["principal_moments"], {2.5, 5.0, 6.5}, tol, "principal_moments");  // ascending
  // One row per principal axis, in the order of the moments: ±z, ±y, ±x.
  ASSERT_TRUE(j["principal_axes"].is_array());
  ASSERT_EQ(j["principal_axes"].size(), 3u);
  const int axis_of_moment[3] = {2, 1, 0};
  for (int i = 0; i < 3; ++i) {
    const json& row = j["principal_axes"][i];
    ASSERT_EQ(row.size(), 3u);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(std::abs(row[k].get<double>()), k == axis_of_moment[i] ? 1.0 : 0.0, tol)
          << "principal axis " << i;
  }
  expect_vec(j["bounding_box"]["min"], {-0.5, -1.0, -1.5}, tol, "bounding_box.min");
  expect_vec(j["bounding_box"]["max"], {0.5, 1.0, 1.5}, tol, "bounding_box.max");
  EXPECT_NEAR(j["characteristic_length"].get<double>(), std::cbrt(6 * 6.0 / std::numbers::pi), tol);
  EXPECT_EQ(j["hull"]["vertices"].get<int>(), 8);
  EXPECT_EQ(j["hull"]["faces"].get<int>(), 6);
  ASSERT_TRUE(j["warnings"].is_array());
  EXPECT_TRUE(j["warnings"].empty());
}

TEST_F(InfoCli, DensityScalesMassAndInertiaNotVolume) {
  const json j = parse_json(run_cli("info box:x=1,y=2,z=3 --density 2.5 --json"));
  EXPECT_NEAR(j["volume"].get<double>(), 6.0, 1e-12);
  EXPECT_NEAR(j["mass"].get<double>(), 15.0, 1e-12);
  expect_vec(j["principal_moments"], {6.25, 12.5, 16.25}, 1e-12, "principal_moments");
}

TEST_F(InfoCli, MeshFileCentreOfMassIsInInputFrame) {
  // The unit cube [0,1]^3 from a file: reported in the file's own frame.
  const json j = parse_json(run_cli("info " + data("cube_binary.stl") + " --json"));
  expect_vec(j["center_of_mass"], {0.5, 0.5, 0.5}, 1e-7, "center_of_mass");
  expect_vec(j["bounding_box"]["min"], {0, 0, 0}, 1e-7, "bounding_box.min");
  expect_vec(j["bounding_box"]["max"], {1, 1, 1}, 1e-7, "bounding_box.max");
}

TEST_F(InfoCli, TextOutputNamesParticleAndVolume) {
  const CliResult r = run_cli("info box:x=1,y=2,z=3");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_THAT(r.out, AllOf(HasSubstr("box:x=1,y=2,z=3"), HasSubstr("volume"), HasSubstr("6")));
}

// ---------------------------------------------------------------------------------------------------------
// --write-stl round trip.

class InfoRoundTrip : public InfoCli, public ::testing::WithParamInterface<const char*> {};

TEST_P(InfoRoundTrip, WrittenStlHasSameMassPropertiesAndHull) {
  const std::string shape = GetParam();
  const std::string stl = (dir_ / "shape.stl").string();
  const CliResult write = run_cli("info " + quote(shape) + " --density 2.5 --write-stl " + quote(stl));
  ASSERT_EQ(write.exit_code, 0) << write.err;
  ASSERT_TRUE(fs::is_regular_file(stl));
  EXPECT_EQ(entries(), std::vector<std::string>{"shape.stl"}) << "no temporary files left behind";

  const json built = parse_json(run_cli("info " + quote(shape) + " --density 2.5 --json"));
  const json read = parse_json(run_cli("info " + quote(stl) + " --density 2.5 --json"));

  // Binary STL stores float32 coordinates: each is rounded with relative error <= 2^-24 ~ 6e-8 of the
  // particle's size (the shapes are centred on their centre of mass). Volume is a sum of cubic and the
  // moments of inertia a sum of quintic terms in the coordinates, so their relative error is bounded by a few
  // times 6e-8 (measured: <= 6e-8). 1e-6 leaves a safe margin yet is far below what a lost or flipped
  // triangle would change (>= 1e-4 for these meshes).
  const double rel = 1e-6;
  const auto near = [&](const json& a, const json& b, const std::string& what) {
    const double x = a.get<double>(), y = b.get<double>();
    EXPECT_NEAR(y, x, rel * std::abs(x)) << shape << ": " << what;
  };
  near(built["volume"], read["volume"], "volume");
  near(built["mass"], read["mass"], "mass");
  for (int i = 0; i < 3; ++i)
    near(built["principal_moments"][i], read["principal_moments"][i],
         "principal moment " + std::to_string(i));
  EXPECT_EQ(read["hull"]["vertices"], built["hull"]["vertices"]) << shape;
  EXPECT_EQ(read["hull"]["faces"], built["hull"]["faces"]) << shape;
  // The surface is written in the input frame; built-in shapes are centred on their centre of mass.
  const double size = built["characteristic_length"].get<double>();
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(read["center_of_mass"][i].get<double>(), built["center_of_mass"][i].get<double>(), rel * size)
        << shape;
}

INSTANTIATE_TEST_SUITE_P(Shapes, InfoRoundTrip,
                         ::testing::Values("box:x=1,y=2,z=3", "cylinder:r=0.67,h=0.67", "tetrahedron:edge=1",
                                           "ellipsoid:a=1,b=0.7,c=0.5", "irregular:seed=3"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           return name.substr(0, name.find(':'));
                         });

TEST_F(InfoCli, WriteStlIntoMissingDirectoryFailsAndLeavesNoFile) {
  const fs::path target = dir_ / "no_such_dir" / "out.stl";
  expect_bad_input(run_cli("info box:x=1,y=1,z=1 --write-stl " + quote(target.string())),
                   {target.string(), "cannot write"});
  EXPECT_FALSE(fs::exists(target));
  EXPECT_FALSE(fs::exists(target.parent_path()));
  EXPECT_TRUE(entries().empty());
}

TEST_F(InfoCli, WriteStlBelowRegularFileFailsAndLeavesNoFile) {
  const fs::path file = dir_ / "plain";
  std::ofstream(file) << "not a directory\n";
  const fs::path target = file / "out.stl";
  expect_bad_input(run_cli("info box:x=1,y=1,z=1 --write-stl " + quote(target.string())), {target.string()});
  EXPECT_EQ(entries(), std::vector<std::string>{"plain"});
  EXPECT_EQ(fs::file_size(file), std::string("not a directory\n").size());
}

}  // namespace
