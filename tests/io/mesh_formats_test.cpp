// The one-pass readers, format by format: vertices exactly as the file lists them, polygons fan-triangulated
// with their winding, files without faces as point clouds, and one-line errors naming the file and line.
// Files are written here as strings; read_mesh_from_memory parses them exactly as read_mesh parses a file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "repose/error.hpp"
#include "repose/geometry/mesh.hpp"
#include "repose/io/mesh_io.hpp"

namespace repose {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::string error_of(const std::string& bytes, const std::string& name) {
  try {
    (void)read_mesh_from_memory(bytes, name);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

// The value's bytes, little or big endian.
template <typename T>
std::string bytes_of(T value, bool big_endian = false) {
  const auto raw = std::bit_cast<std::array<char, sizeof(T)>>(value);
  std::string out(raw.begin(), raw.end());
  if (big_endian) std::reverse(out.begin(), out.end());
  return out;
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// ---------------------------------------------------------------------------------------------------------
// Polygons.

TEST(MeshFormats, ObjQuadIsFanTriangulatedWithItsWinding) {
  // A unit square pyramid of height 1 (volume 1/3): the base quad, counter-clockwise seen from below.
  const TriangleMesh m = read_mesh_from_memory(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\n"
      "f 1 4 3 2\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n",
      "pyramid.obj");
  EXPECT_EQ(m.vertices.size(), 5u);
  ASSERT_EQ(m.triangles.size(), 6u);
  EXPECT_EQ(m.triangles[0], (Triangle{0, 3, 2}));  // the fan from the quad's first vertex
  EXPECT_EQ(m.triangles[1], (Triangle{0, 2, 1}));
  EXPECT_NEAR(signed_volume(m), 1.0 / 3.0, 1e-15);  // exact in binary but for the 1/3 (measured 0)
}

// A quad with a concave corner is fanned from that corner: the fan from the first corner would put its
// diagonal outside the quad, giving one triangle facing the wrong way.
TEST(MeshFormats, ConcaveQuadIsFannedFromItsConcaveCorner) {
  // The dart (0,0), (2,1), (0,2), (1,1), counter-clockwise in z = 0 (area 1), concave at (1,1); the face
  // comes first, as OBJ allows.
  const TriangleMesh m = read_mesh_from_memory("f 1 2 3 4\nv 0 0 0\nv 2 1 0\nv 0 2 0\nv 1 1 0\n", "dart.obj");
  EXPECT_THAT(m.triangles, ElementsAre(Triangle{3, 0, 1}, Triangle{3, 1, 2}));
  for (const Triangle& t : m.triangles) {
    const Vec3 n = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    EXPECT_EQ(n, Vec3(0, 0, 1));  // twice the area 0.5, facing +z
  }
}

TEST(MeshFormats, OffPentagonsAreFanTriangulatedWithTheirWinding) {
  // A prism over the regular pentagon of circumradius 1, height 1: volume (5/2)·sin 72°.
  std::string off = "OFF\n10 7 0\n";
  for (int z = 0; z < 2; ++z)
    for (int k = 0; k < 5; ++k)
      off += number(std::cos(2 * std::numbers::pi * k / 5)) + " " +
             number(std::sin(2 * std::numbers::pi * k / 5)) + " " + std::to_string(z) + "\n";
  off += "5 4 3 2 1 0\n5 5 6 7 8 9\n";  // bottom seen from below, top from above
  for (int k = 0; k < 5; ++k) {
    const int n = (k + 1) % 5;
    off += "4 " + std::to_string(k) + " " + std::to_string(n) + " " + std::to_string(5 + n) + " " +
           std::to_string(5 + k) + "\n";
  }
  TriangleMesh m = read_mesh_from_memory(off, "prism.off");
  EXPECT_EQ(m.vertices.size(), 10u);
  ASSERT_EQ(m.triangles.size(), 3u + 3u + 5u * 2u);
  EXPECT_EQ(m.triangles[0], (Triangle{4, 3, 2}));
  const MeshReport r = validate_mesh(m, "prism.off");
  EXPECT_FALSE(r.flipped);
  EXPECT_EQ(r.welded_vertices, 0);
  // Coordinates are rounded to 17 digits; the volume is a sum of 16 terms of size ~1 (round-off ~1e-15).
  EXPECT_NEAR(signed_volume(m), 2.5 * std::sin(2 * std::numbers::pi / 5), 1e-13);
}

TEST(MeshFormats, FacesOfOneOrTwoVerticesAreNoSurface) {
  const std::string tet_obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
  EXPECT_EQ(read_mesh_from_memory(tet_obj + "f 1 2\nf 3\nf\nl 1 2 3\np 4\n", "t.obj").triangles.size(), 4u);
  const std::string tet_off = "OFF\n4 6 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
  EXPECT_EQ(read_mesh_from_memory(tet_off + "2 0 1\n1 3\n", "t.off").triangles.size(), 4u);
}

// ---------------------------------------------------------------------------------------------------------
// Point clouds: vertices and no faces read fine; validate_mesh then says there is no surface.

const char* const kPlyXyz = "property float x\nproperty float y\nproperty float z\n";

TEST(MeshFormats, FilesWithoutFacesArePointClouds) {
  const std::vector<std::pair<std::string, std::string>> files = {
      {"v.obj", "# points\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n"},
      {"v.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"},
      {"v.ply", std::string("ply\nformat ascii 1.0\nelement vertex 3\n") + kPlyXyz +
                    "end_header\n0 0 0\n1 0 0\n0 1 0\n"},
      {"empty_face.ply",
       std::string("ply\nformat ascii 1.0\nelement vertex 3\n") + kPlyXyz +
           "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"},
      {"v.xyz", "0 0 0\n1 0 0\n0 1 0\n"},
  };
  for (const auto& [name, bytes] : files) {
    TriangleMesh m = read_mesh_from_memory(bytes, name);
    EXPECT_EQ(m.vertices, (std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)})) << name;
    EXPECT_TRUE(m.triangles.empty()) << name;
    EXPECT_THROW(validate_mesh(m, name), Error) << name;
  }
}

TEST(MeshFormats, BinaryPlyPointCloud) {
  for (const bool big : {false, true}) {
    // Positions as double, with a colour between them that must be read past.
    std::string ply = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex 2\nproperty double x\nproperty uchar red\nproperty double y\n"
                      "property double z\nend_header\n";
    ply += bytes_of(1.5, big) + "\xff" + bytes_of(-2.0, big) + bytes_of(0.25, big);
    ply += bytes_of(3.0, big) + "\x01" + bytes_of(1e300, big) + bytes_of(-0.5, big);
    const TriangleMesh m = read_mesh_from_memory(ply, "cloud.ply");
    EXPECT_EQ(m.vertices, (std::vector<Vec3>{Vec3(1.5, -2, 0.25), Vec3(3, 1e300, -0.5)})) << big;
    EXPECT_TRUE(m.triangles.empty());
  }
}

TEST(MeshFormats, XyzIgnoresExtraColumnsCommentsAndBlankLines) {
  const TriangleMesh m = read_mesh_from_memory(
      "# x y z nx ny nz r g b\r\n\r\n1 2 3 0 0 1 255 0 0\r\n  -4.5e1\t+5 6 # a comment\r\n\n7 8 9\n"
      "nan inf 1e999\n",
      "scan.xyz");
  ASSERT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.vertices[0], Vec3(1, 2, 3));
  EXPECT_EQ(m.vertices[1], Vec3(-45, 5, 6));
  EXPECT_EQ(m.vertices[2], Vec3(7, 8, 9));
  // Read, to be rejected by validate_mesh (non-finite), like every format's nan and inf.
  EXPECT_TRUE(std::isnan(m.vertices[3].x()));
  EXPECT_TRUE(std::isinf(m.vertices[3].y()) && std::isinf(m.vertices[3].z()));
  EXPECT_TRUE(m.triangles.empty());
}

TEST(MeshFormats, XyzErrorsNameTheLine) {
  EXPECT_EQ(error_of("0 0 0\n1 2\n", "a.xyz"), "a.xyz: line 2: expected x y z, found end of line");
  EXPECT_EQ(error_of("0 0 0\n\n1 2 x 4\n", "b.xyz"), "b.xyz: line 3: expected x y z, found 'x'");
  EXPECT_EQ(error_of("0,0,0\n", "c.xyz"), "c.xyz: line 1: expected x y z, found '0,0,0'");
  EXPECT_EQ(error_of("0 0 0\n1 1\v1\n", "d.xyz"), "d.xyz: line 2: control character (byte 11)");
  EXPECT_EQ(error_of("# nothing\n\n", "e.xyz"), "e.xyz: no vertices");
}

TEST(MeshFormats, FilesWithNothingAreErrors) {
  EXPECT_EQ(error_of("OFF\n0 0 0\n", "a.off"), "a.off: no vertices");
  EXPECT_EQ(error_of("# nothing\ng group\n", "b.obj"), "b.obj: no vertices");
  EXPECT_EQ(
      error_of(std::string("ply\nformat ascii 1.0\nelement vertex 0\n") + kPlyXyz + "end_header\n", "c.ply"),
      "c.ply: no vertices");
}

// ---------------------------------------------------------------------------------------------------------
// OBJ indices: errors in file order, forward references checked against the final count.

TEST(MeshFormats, ObjIndexErrorsInFileOrder) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  EXPECT_EQ(error_of("f 1 2 9\n" + v, "a.obj"),
            "a.obj: line 1: in face 1, vertex index 9 does not exist (4 vertices)");
  EXPECT_EQ(error_of("f 1 2 9\n" + v + "f 1 2 x\n", "b.obj"),
            "b.obj: line 1: in face 1, vertex index 9 does not exist (4 vertices)");
  EXPECT_EQ(error_of("f 1 2 x\nf 1 2 9\n" + v, "c.obj"),
            "c.obj: line 1: in face 1, cannot read vertex index 'x'");
  EXPECT_EQ(error_of(v + "l 1 7\n", "d.obj"), "d.obj: line 5: vertex index 7 does not exist (4 vertices)");
  // A bad vertex line anywhere comes before index errors.
  EXPECT_EQ(error_of(v + "f 1 2 0\nv 1 2\n", "e.obj"),
            "e.obj: line 6: vertex with 2 numbers (expected x y z, x y z w or x y z r g b)");
  EXPECT_EQ(error_of(v + "f -9223372036854775808 1 2\n", "f.obj"),
            "f.obj: line 5: in face 1, vertex index -9223372036854775808 does not exist (4 vertices)");
  EXPECT_EQ(error_of(v + "f 99999999999 1 2\n", "g.obj"),
            "g.obj: line 5: in face 1, vertex index 99999999999 does not exist (4 vertices)");
  // Forward references to vertices that come later are fine.
  const TriangleMesh m = read_mesh_from_memory("f 1 3 2\nf 1 2 4\n" + v + "f 2 3 4\nf -4 -1 -2\n", "h.obj");
  EXPECT_THAT(m.triangles,
              ElementsAre(Triangle{0, 2, 1}, Triangle{0, 1, 3}, Triangle{1, 2, 3}, Triangle{0, 3, 2}));
}

// ---------------------------------------------------------------------------------------------------------
// PLY: any numeric type, either byte order, other elements and properties read past.

std::string tetra_ply_binary(bool big) {
  std::string ply = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\ncomment faces first, an unknown element, lists everywhere\n"
                    "element face 4\nproperty uchar flags\nproperty list uchar int vertex_indices\n"
                    "property list uchar float texcoord\n"
                    "element material 1\nproperty list ushort char name\n"
                    "element vertex 4\nproperty list uchar float uv\nproperty short x\nproperty uint8 y\n"
                    "property float z\nend_header\n";
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  for (const auto& f : faces) {
    ply += std::string("\x07\x03") + bytes_of<std::int32_t>(f[0], big) + bytes_of<std::int32_t>(f[1], big) +
           bytes_of<std::int32_t>(f[2], big) + "\x01" + bytes_of(0.5f, big);
  }
  ply += bytes_of<std::uint16_t>(3, big) + "abc";
  const int xyz[4][3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
  for (const auto& p : xyz) {
    ply += std::string("\x02") + bytes_of(0.f, big) + bytes_of(1.f, big) + bytes_of<std::int16_t>(p[0], big) +
           static_cast<char>(p[1]) + bytes_of(static_cast<float>(p[2]), big);
  }
  return ply;
}

TEST(MeshFormats, BinaryPlyWithOtherElementsAndProperties) {
  for (const bool big : {false, true}) {
    TriangleMesh m = read_mesh_from_memory(tetra_ply_binary(big), "tet.ply");
    EXPECT_EQ(m.vertices, (std::vector<Vec3>{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 2)}));
    EXPECT_THAT(m.triangles,
                ElementsAre(Triangle{0, 2, 1}, Triangle{0, 1, 3}, Triangle{1, 2, 3}, Triangle{0, 3, 2}));
    validate_mesh(m, "tet.ply");
    EXPECT_DOUBLE_EQ(signed_volume(m), 8.0 / 6.0);
    // Every byte counts: one missing and the last vertex is cut short.
    const std::string cut = tetra_ply_binary(big).substr(0, tetra_ply_binary(big).size() - 1);
    EXPECT_EQ(error_of(cut, "cut.ply"), "cut.ply: truncated PLY: file ends in 'vertex' element 4 of 4");
  }
}

std::string ply_head(const std::string& format, const std::string& list) {
  return "ply\nformat " + format + " 1.0\nelement vertex 4\n" + kPlyXyz + "element face 1\n" + list +
         "end_header\n";
}

TEST(MeshFormats, PlyFaceErrorsNameTheFace) {
  const std::string v = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  const std::string ints = "property list uchar int vertex_indices\n";
  EXPECT_EQ(error_of(ply_head("ascii", ints) + v + "0\n", "a.ply"), "a.ply: line 14: face 1 has no vertices");
  EXPECT_EQ(error_of(ply_head("ascii", ints) + v + "3 0 1 -1\n", "b.ply"),
            "b.ply: line 14: in face 1, vertex index -1 does not exist (4 vertices)");
  EXPECT_EQ(error_of(ply_head("ascii", ints) + v + "3 0 1 x\n", "c.ply"),
            "c.ply: line 14: 'face' element 1 of 1: 'x' is not a number");
  // A malformed line is reported as such, even when it also holds a bad index.
  EXPECT_EQ(error_of(ply_head("ascii", ints) + v + "3 0 1 9 7\n", "j.ply"),
            "j.ply: line 14: 'face' element 1 of 1: too many values");
  // Float lists hold indices too, if they are whole numbers; 'vertex_index' is the other usual name.
  const std::string floats = "property list uchar float vertex_index\n";
  EXPECT_EQ(read_mesh_from_memory(ply_head("ascii", floats) + v + "3 0 2.0 1e0\n", "d.ply").triangles,
            (std::vector<Triangle>{{0, 2, 1}}));
  EXPECT_EQ(error_of(ply_head("ascii", floats) + v + "3 0 1 2.5\n", "e.ply"),
            "e.ply: line 14: in face 1, vertex index 2.5 is not an integer");
  std::string binary = ply_head("binary_little_endian", ints);
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f}) binary += bytes_of(c);
  EXPECT_EQ(error_of(binary + "\x03" + bytes_of(0) + bytes_of(1) + bytes_of(-1), "f.ply"),
            "f.ply: in face 1, vertex index -1 does not exist (4 vertices)");
  EXPECT_EQ(error_of(binary + "\x03" + bytes_of(0) + bytes_of(1) + bytes_of(4), "g.ply"),
            "g.ply: in face 1, vertex index 4 does not exist (4 vertices)");
  EXPECT_EQ(error_of(binary + std::string(1, '\0'), "h.ply"), "h.ply: face 1 has no vertices");
  EXPECT_EQ(error_of("ply\nformat ascii 1.0\nelement vertex 0\n" + std::string(kPlyXyz) +
                         "element vertex 0\nend_header\n",
                     "i.ply"),
            "i.ply: cannot parse: PLY header line 7: second 'vertex' element");
}

}  // namespace
}  // namespace repose
