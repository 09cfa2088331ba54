// The mesh options at the command line, alike for info, settle and poses: --mesh-units / --scale,
// --inertia convex | shell, --repair, point clouds, and the advice an unloadable file gets.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <repose/geometry/shapes.hpp>
#include <string>

#include "cli_test_support.hpp"

namespace repose::test {
namespace {

class MeshOptionsCli : public TempDirTest {
 protected:
  // A 10 × 20 × 30 box in millimetres, as eight corners and points inside (an .xyz point cloud).
  std::string box_cloud_mm() {
    const std::string path = (dir_ / "box_mm.xyz").string();
    std::ofstream out(path);
    out << "# x y z (mm)\n";
    for (int i = 0; i < 8; ++i)
      out << (i & 1 ? 10 : 0) << " " << (i & 2 ? 20 : 0) << " " << (i & 4 ? 30 : 0) << "\n";
    out << "5 10 15\n2 3 4\n";
    return path;
  }
  // The unit cube as OBJ with its top face (two triangles) missing: one hole.
  std::string open_cube_obj() {
    const std::string path = (dir_ / "open cube.obj").string();
    std::ofstream out(path);
    out << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
           "f 1 3 2\nf 1 4 3\n"                     // bottom (−z)
           "f 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"   // −y, +x
           "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";  // +y, −x
    return path;
  }
  // The same open cube as a scanner or CAD export writes it: every face with corners of its own (5 faces ×
  // 4 records of 8 positions: 12 duplicates) and one triangle with a repeated corner (degenerate).
  std::string unwelded_open_cube_obj() {
    const std::string path = (dir_ / "unwelded.obj").string();
    std::ofstream out(path);
    const int faces[5][4] = {{0, 3, 2, 1}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    int record = 0;
    for (const auto& face : faces) {
      for (int c : face)
        out << "v " << (c == 1 || c == 2 || c == 5 || c == 6) << " " << (c == 2 || c == 3 || c == 6 || c == 7)
            << " " << (c >= 4) << "\n";
      out << "f " << record + 1 << " " << record + 2 << " " << record + 3 << "\n"
          << "f " << record + 1 << " " << record + 3 << " " << record + 4 << "\n";
      record += 4;
    }
    out << "f 1 1 2\n";
    return path;
  }
};

TEST_F(MeshOptionsCli, InfoReadsAPointCloudInMillimetresAsItsConvexHullInMetres) {
  const std::string cloud = box_cloud_mm();
  expect_bad_input(run_cli("info " + shell_quote(cloud)), {"box_mm.xyz", "no faces", "--inertia convex"});
  const nlohmann::json j = parse_json(
      run_cli("info " + shell_quote(cloud) + " --inertia convex --mesh-units mm --density 1000 --json"));
  // 10 × 20 × 30 mm = 6e-6 m³, 6 g at 1000 kg/m³; the bounding box in metres.
  EXPECT_NEAR(j["volume"].get<double>(), 6e-6, 1e-18);
  EXPECT_NEAR(j["mass"].get<double>(), 6e-3, 1e-15);
  EXPECT_EQ(j["inertia_model"], "convex");
  EXPECT_EQ(j["surface_is_hull"], true);
  EXPECT_NEAR(numbers(j["bounding_box"]["max"])[2], 0.03, 1e-15);
  EXPECT_NEAR(j["characteristic_length"].get<double>(), std::cbrt(6 * 6e-6 / M_PI), 1e-15);
  EXPECT_EQ(j["file"]["vertices"], 10);
  EXPECT_EQ(j["length_unit"], "m");
  // --scale is the same factor given as a number; the two cannot be combined.
  const nlohmann::json s =
      parse_json(run_cli("info " + shell_quote(cloud) + " --inertia convex --scale 0.001 --json"));
  EXPECT_EQ(s["volume"], j["volume"]);
  const CliResult both =
      run_cli("info " + shell_quote(cloud) + " --inertia convex --scale 2 --mesh-units mm");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_EQ(both.out, "");
  // In cgs the same file is in centimetres.
  const nlohmann::json cgs = parse_json(
      run_cli("info " + shell_quote(cloud) + " --inertia convex --mesh-units mm --units cgs --json"));
  EXPECT_NEAR(cgs["volume"].get<double>(), 6.0, 1e-12);
  EXPECT_EQ(cgs["length_unit"], "cm");
  // The same corners as an OBJ with vertices only (a scanner's point export) load alike.
  const std::string obj = (dir_ / "box_mm.obj").string();
  std::ofstream(obj) << "v 0 0 0\nv 10 0 0\nv 0 20 0\nv 10 20 0\nv 0 0 30\nv 10 0 30\nv 0 20 30\nv 10 20 30\n"
                        "v 5 10 15\n";
  const nlohmann::json o = parse_json(
      run_cli("info " + shell_quote(obj) + " --inertia convex --mesh-units mm --density 1000 --json"));
  EXPECT_EQ(o["volume"], j["volume"]);
  EXPECT_EQ(o["file"]["vertices"], 9);
}

TEST_F(MeshOptionsCli, AnOpenSurfaceLoadsWithRepairShellOrConvexAndSaysSo) {
  const std::string open = open_cube_obj();
  expect_bad_input(run_cli("info " + shell_quote(open)), {"open cube.obj", "open surface", "--repair"});
  const nlohmann::json repaired = parse_json(run_cli("info " + shell_quote(open) + " --repair --json"));
  EXPECT_NEAR(repaired["volume"].get<double>(), 1.0, 1e-12);  // a flat hole in a flat face: exact
  EXPECT_EQ(repaired["repair"]["holes_filled"], 1);
  EXPECT_NEAR(repaired["repair"]["area_added"].get<double>(), 0.2, 1e-12);  // 1 of the other 5 unit faces
  EXPECT_EQ(repaired["file"]["duplicate_vertices"], 0);  // the file shares its corners: nothing to weld
  const CliResult text = run_cli("info " + shell_quote(open) + " --repair");
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, ::testing::HasSubstr("1 holes filled"));
  const nlohmann::json shell = parse_json(run_cli("info " + shell_quote(open) + " --inertia shell --json"));
  EXPECT_NEAR(shell["area"].get<double>(), 5.0, 1e-12);
  EXPECT_NEAR(numbers(shell["center_of_mass"])[2], 0.4, 1e-12);  // 4 walls at ½, the floor at 0
  const nlohmann::json hull = parse_json(run_cli("info " + shell_quote(open) + " --inertia convex --json"));
  EXPECT_NEAR(hull["volume"].get<double>(), 1.0, 1e-12);
}

// The "file" counts describe the user's file whatever is done to it after: the same with --repair as with
// --inertia shell (which only cleans), counted from the file's 20 records of 8 corners.
TEST_F(MeshOptionsCli, TheFileReportCountsTheFilesOwnDuplicatesAlsoWhenRepaired) {
  const std::string path = unwelded_open_cube_obj();
  for (const char* option : {" --repair", " --inertia shell"}) {
    const nlohmann::json j = parse_json(run_cli("info " + shell_quote(path) + option + " --json"));
    EXPECT_EQ(j["file"]["vertices"], 20) << option;
    EXPECT_EQ(j["file"]["triangles"], 11) << option;
    EXPECT_EQ(j["file"]["duplicate_vertices"], 12) << option;
    EXPECT_EQ(j["file"]["degenerate_triangles"], 1) << option;
  }
  const nlohmann::json repaired = parse_json(run_cli("info " + shell_quote(path) + " --repair --json"));
  EXPECT_NEAR(repaired["volume"].get<double>(), 1.0, 1e-12);  // a flat hole in a flat face: exact
  EXPECT_EQ(repaired["repair"]["holes_filled"], 1);
}

TEST_F(MeshOptionsCli, SettleAndPosesTakeTheSameOptions) {
  const std::string cloud = box_cloud_mm();
  const nlohmann::json r = parse_json(run_cli("settle " + shell_quote(cloud) +
                                              " --inertia convex --mesh-units mm --orientation "
                                              "axis-angle:1,2,0.5,0.3 --json"));
  EXPECT_EQ(r["status"], "rest");
  const std::vector<double> com = numbers(r["rest"]["com"]);
  ASSERT_EQ(com.size(), 3u);
  const double h = com[2];  // rests on a face: half of 10, 20 or 30 mm, in metres
  EXPECT_TRUE(std::abs(h - 0.005) < 1e-9 || std::abs(h - 0.010) < 1e-9 || std::abs(h - 0.015) < 1e-9) << h;
  const nlohmann::json p =
      parse_json(run_cli("poses " + shell_quote(cloud) + " --inertia convex --mesh-units mm -n 64 --json"));
  EXPECT_EQ(p["particle"]["inertia_model"], "convex");
  EXPECT_NEAR(p["particle"]["scale"].get<double>(), 1e-3, 1e-18);
  EXPECT_EQ(p["n"], 64);
  // A manifest line carries its own options.
  std::ofstream(dir_ / "list.txt") << "box_mm.xyz --inertia convex --mesh-units mm\n";
  const CliResult m =
      run_cli("poses --manifest " + shell_quote((dir_ / "list.txt").string()) + " -n 64 --json");
  const nlohmann::json mj = parse_json(m);
  EXPECT_EQ(without_timing(mj)["poses"], without_timing(p)["poses"]);
}

TEST_F(MeshOptionsCli, AMillimetreMeshScaledByAThousandthRestsAsTheSameMeshInMetres) {
  // An irregular 2 cm grain written twice, in metres and in millimetres (%.17g, so the two files differ only
  // by the decimal rounding of ×1000). Rest-pose probabilities do not depend on size (every tolerance is a
  // fraction of L, gravity and damping scale with it), so they agree; that alone would also hold if --scale
  // were ignored, hence L is compared too: the scaled grain must be the metre grain, to round-off.
  const TriangleMesh grain = make_shape("irregular:seed=3,size=0.02");
  const auto write_obj = [&](const std::string& name, double factor) {
    const std::string path = (dir_ / name).string();
    std::FILE* f = std::fopen(path.c_str(), "w");
    for (const Vec3& v : grain.vertices)
      std::fprintf(f, "v %.17g %.17g %.17g\n", factor * v.x(), factor * v.y(), factor * v.z());
    for (const Triangle& t : grain.triangles) std::fprintf(f, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
    std::fclose(f);
    return path;
  };
  const std::string metres = write_obj("grain_m.obj", 1.0), millimetres = write_obj("grain_mm.obj", 1000.0);
  const nlohmann::json m = parse_json(run_cli("poses " + shell_quote(metres) + " -n 1500 --json"));
  for (const std::string& option : {std::string("--scale 0.001"), std::string("--mesh-units mm")}) {
    const nlohmann::json mm =
        parse_json(run_cli("poses " + shell_quote(millimetres) + " " + option + " -n 1500 --json"));
    const double l_m = m["particle"]["characteristic_length"].get<double>();
    EXPECT_NEAR(mm["particle"]["characteristic_length"].get<double>(), l_m, 1e-12 * l_m) << option;
    ASSERT_EQ(mm["poses"].size(), m["poses"].size()) << option;
    // The same drops from the same orientations: equal counts pose by pose (a drop could change pose only by
    // landing within round-off of a basin boundary).
    for (std::size_t i = 0; i < m["poses"].size(); ++i)
      EXPECT_EQ(mm["poses"][i]["count"], m["poses"][i]["count"]) << option;
  }
}

}  // namespace
}  // namespace repose::test
