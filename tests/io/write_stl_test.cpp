// write_stl: binary STL written atomically, read back as the same solid.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "repose/error.hpp"
#include "repose/geometry/mesh.hpp"
#include "repose/io/mesh_io.hpp"
#include "test_data.hpp"

namespace repose {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// A scratch directory per test.
class WriteStlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ =
        fs::temp_directory_path() / ("repose_write_stl_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& content) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << content;
    return path;
  }

  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
};

// Triangles as coordinate triples, each rotated to start at its smallest vertex, sorted.
std::vector<std::array<std::array<double, 3>, 3>> canonical(const TriangleMesh& m) {
  std::vector<std::array<std::array<double, 3>, 3>> out;
  for (const Triangle& t : m.triangles) {
    std::array<std::array<double, 3>, 3> tri;
    for (int k = 0; k < 3; ++k) tri[k] = {m.vertices[t[k]].x(), m.vertices[t[k]].y(), m.vertices[t[k]].z()};
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    out.push_back(tri);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST_F(WriteStlTest, WriteThenReadGivesTheSameBox) {
  // A 2 x 3 x 0.5 box whose coordinates are exact in float32.
  TriangleMesh box = read_mesh(test::data_file("cube.off"));
  for (Vec3& v : box.vertices) v = v.cwiseProduct(Vec3(2.0, 3.0, 0.5)) + Vec3(-1.0, 0.25, 4.0);
  validate_mesh(box, "box");
  const std::string path = (dir_ / "box.stl").string();
  write("box.stl", "old content");  // replaced atomically
  write_stl(box, path);
  EXPECT_EQ(fs::file_size(path), 84u + 50u * 12u);
  EXPECT_EQ(listing(), std::vector<std::string>{"box.stl"});  // no temporary left behind

  TriangleMesh back = read_mesh(path);
  const MeshReport r = validate_mesh(back, path);
  EXPECT_FALSE(r.flipped);
  EXPECT_EQ(canonical(back), canonical(box));
  EXPECT_DOUBLE_EQ(signed_volume(back), 3.0);
}

TEST_F(WriteStlTest, WriteStlNormalsFaceOutward) {
  TriangleMesh cube = read_mesh(test::data_file("cube.off"));
  const std::string path = (dir_ / "cube.stl").string();
  write_stl(cube, path);
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 684u);
  for (std::size_t t = 0; t < 12; ++t) {
    float n[3], v[3];
    std::memcpy(n, bytes.data() + 84 + 50 * t, sizeof n);
    std::memcpy(v, bytes.data() + 84 + 50 * t + 12, sizeof v);
    // Stored as float32: each component rounded by ≤ 6e-8 relative, so |n| − 1 ≤ ~1e-7 for any normal; 1e-6
    // is 10× that bound (the cube's axis normals measure 0).
    EXPECT_NEAR(Vec3(n[0], n[1], n[2]).norm(), 1.0, 1e-6);
    // Every face of the unit cube is 0.5 from its centre, so an outward unit normal gives exactly 0.5 (all
    // values here are exact in float); inward gives −0.5, a tilted normal anything else.
    EXPECT_EQ(Vec3(n[0], n[1], n[2]).dot(Vec3(v[0], v[1], v[2]) - Vec3::Constant(0.5)), 0.5) << t;
  }
}

TEST_F(WriteStlTest, WriteFailureLeavesNothingBehind) {
  const TriangleMesh cube = read_mesh(test::data_file("cube.off"));
  const std::string missing = (dir_ / "no_such_dir" / "out.stl").string();
  EXPECT_THROW(
      {
        try {
          write_stl(cube, missing);
        } catch (const Error& e) {
          EXPECT_EQ(std::string(e.what()), missing + ": cannot write: No such file or directory");
          throw;
        }
      },
      Error);
  // Renaming over a directory fails after the temporary was written; it must be removed.
  fs::create_directory(dir_ / "taken.stl");
  const std::string taken = (dir_ / "taken.stl").string();
  EXPECT_THROW(
      {
        try {
          write_stl(cube, taken);
        } catch (const Error& e) {
          EXPECT_THAT(e.what(), HasSubstr(taken + ": cannot write: "));
          throw;
        }
      },
      Error);
  EXPECT_EQ(listing(), std::vector<std::string>{"taken.stl"});
}

TEST(MeshIo, WriteRejectsBadIndices) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0)};
  m.triangles = {{0, 0, 1}};
  EXPECT_THROW(write_stl(m, ::testing::TempDir() + "/never_written.stl"), Error);
  EXPECT_FALSE(fs::exists(::testing::TempDir() + "/never_written.stl"));
}

}  // namespace
}  // namespace repose
