#include "repose/io/mesh_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "repose/error.hpp"
#include "repose/geometry/mesh.hpp"
#include "repose/model/particle.hpp"
#include "test_data.hpp"

namespace repose {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

// The message of the repose::Error that reading (and, with `validate`, validating) throws.
std::string load_error(const std::string& path, bool validate = false) {
  try {
    TriangleMesh m = read_mesh(path);
    if (validate) validate_mesh(m, path);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

std::string data_error(const std::string& name, bool validate = false) {
  return load_error(test::data_file(name), validate);
}

// A scratch directory per test for files too small or too odd to keep under tests/data.
class MeshIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("repose_mesh_io_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& content) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << content;
    return path;
  }

  fs::path dir_;
};

// ---------------------------------------------------------------------------------------------------------
// Every supported format reads the unit cube: its 8 shared vertices as the file holds them (STL: its 36
// corners merged), its quads fan-triangulated, so validate_mesh has nothing to weld.

class ReadCube : public ::testing::TestWithParam<const char*> {};

TEST_P(ReadCube, HasUnitVolume) {
  const std::string path = test::data_file(GetParam());
  TriangleMesh m = read_mesh(path);
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_EQ(m.triangles.size(), 12u);
  const MeshReport r = validate_mesh(m, path);
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(r.welded_vertices, 0);
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  EXPECT_FALSE(r.flipped);
  EXPECT_EQ(r.degenerate_triangles, 0);
  EXPECT_DOUBLE_EQ(signed_volume(m), 1.0);
}

INSTANTIATE_TEST_SUITE_P(MeshIo, ReadCube,
                         ::testing::Values("cube_ascii.stl", "cube_binary.stl",
                                           "cube_binary_solid_header.stl", "cube_binary_trailing.stl",
                                           "cube.obj", "cube_groups.obj", "cube_ascii.ply", "cube_binary.ply",
                                           "cube_binary_be.ply", "cube.off"));

// STL corners with the same coordinates are one vertex (-0 and +0 alike); corners that differ, even by
// less than the weld tolerance, stay apart in the reader and are welded and reported by validate_mesh.
TEST_F(MeshIoTest, StlCornersAreMergedAndNearDuplicatesWelded) {
  const auto facet = [](const std::string& a, const std::string& b, const std::string& c) {
    return "facet normal 0 0 0\nouter loop\nvertex " + a + "\nvertex " + b + "\nvertex " + c +
           "\nendloop\nendfacet\n";
  };
  // The corner tetrahedron; one corner written as -0 and once 1e-30 away from the origin (1e-30 is a
  // normal float, far below the weld tolerance 1e-10 of the diagonal).
  const std::string o = "0 0 0", x = "1 0 0", y = "0 1 0", z = "0 0 1";
  const std::string path = write("tet.stl", "solid t\n" + facet(o, y, x) + facet("-0 0 -0", x, z) +
                                                facet(x, y, z) + facet("1e-30 0 0", z, y) + "endsolid t\n");
  TriangleMesh m = read_mesh(path);
  EXPECT_EQ(m.vertices.size(), 5u);  // the origin twice: once exact (also as -0), once 1e-30 away
  EXPECT_EQ(m.triangles.size(), 4u);
  const MeshReport r = validate_mesh(m, path);
  EXPECT_EQ(r.welded_vertices, 1);
  EXPECT_THAT(r.warnings, ::testing::ElementsAre("welded 1 duplicate vertex"));
  EXPECT_NEAR(signed_volume(m), 1.0 / 6.0, 1e-12);  // exact corner tetrahedron; round-off (measured 0)
}

TEST_F(MeshIoTest, ExtensionIsCaseInsensitive) {
  const fs::path path = dir_ / "CUBE.STL";
  fs::copy_file(test::data_file("cube_binary.stl"), path);
  EXPECT_EQ(read_mesh(path.string()).triangles.size(), 12u);
}

// ---------------------------------------------------------------------------------------------------------
// Files that cannot be read at all.

TEST(MeshIo, NonexistentFile) {
  EXPECT_EQ(data_error("does_not_exist.stl"),
            test::data_file("does_not_exist.stl") + ": cannot open: No such file or directory");
}

TEST(MeshIo, Directory) {
  EXPECT_EQ(load_error(REPOSE_TEST_DATA), std::string(REPOSE_TEST_DATA) + ": cannot open: Is a directory");
}

TEST(MeshIo, EmptyFile) { EXPECT_EQ(data_error("empty.stl"), test::data_file("empty.stl") + ": empty file"); }

TEST_F(MeshIoTest, UnknownExtension) {
  const std::string path = write("cube.3mf", "0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_EQ(load_error(path), path + ": unsupported format '.3mf' (expected .stl, .obj, .ply, .off, .xyz)");
}

TEST_F(MeshIoTest, NoExtension) {
  EXPECT_THAT(load_error(write("cube", "solid x\nendsolid x\n")), HasSubstr("cube: unsupported format"));
}

TEST_F(MeshIoTest, ParseErrorIsOneLine) {
  // Unknown statements are skipped (OBJ has many), which leaves nothing.
  EXPECT_EQ(load_error(write("bad.obj", "garbage\n")), (dir_ / "bad.obj").string() + ": no vertices");
  const std::string path = write("bad.ply", "ply\nformat ascii 1.0\nelement vertex 1\n");
  EXPECT_THAT(load_error(path), AllOf(HasSubstr("bad.ply: cannot parse: "), Not(HasSubstr("\n"))));
}

// ---------------------------------------------------------------------------------------------------------
// Headers that claim more than the file holds fail before anything is allocated.

TEST(MeshIo, TruncatedBinaryStl) {
  EXPECT_EQ(data_error("truncated.stl"),
            test::data_file("truncated.stl") +
                ": truncated binary STL: header claims 12 triangles (needs 684 bytes), file has 664 bytes");
}

TEST(MeshIo, BinaryStlClaimingTwoBillionFacets) {
  // 84 + 50·2^31 wraps to 84 in 32-bit arithmetic, which would make this 84-byte file look consistent.
  EXPECT_EQ(data_error("huge_count.stl"),
            test::data_file("huge_count.stl") +
                ": truncated binary STL: header claims 2147483648 triangles (needs 107374182484 bytes), file "
                "has 84 bytes");
}

TEST_F(MeshIoTest, BinaryStlShorterThanHeader) {
  EXPECT_THAT(load_error(write("short.stl", std::string(40, '\0'))),
              HasSubstr("short.stl: truncated binary STL: file has 40 bytes, less than the 84-byte header"));
}

TEST_F(MeshIoTest, BinaryStlWithoutFacets) {
  EXPECT_THAT(load_error(write("none.stl", std::string(84, '\0'))), HasSubstr("none.stl: no triangles"));
}

TEST(MeshIo, PlyClaimingBillionsOfElements) {
  EXPECT_THAT(data_error("huge_vertices.ply"),
              HasSubstr("huge_vertices.ply: PLY header claims 1000000000 'vertex' elements, more than the 6 "
                        "bytes after it can hold"));
  EXPECT_THAT(data_error("huge_faces_binary.ply"),
              HasSubstr("huge_faces_binary.ply: PLY header claims 1000000000 'face' elements"));
}

TEST(MeshIo, OffClaimingBillionsOfElements) {
  EXPECT_THAT(data_error("huge.off"),
              HasSubstr("huge.off: OFF header claims 1000000000 vertices, more than"));
}

TEST(MeshIo, TruncatedPlyAndOff) {
  EXPECT_THAT(data_error("truncated_ascii.ply"),
              HasSubstr("truncated_ascii.ply: truncated PLY: file ends in 'face' element 7 of 7"));
  EXPECT_THAT(data_error("truncated_binary.ply"),
              HasSubstr("truncated_binary.ply: truncated PLY: file ends in 'face' element 12 of 12"));
  EXPECT_THAT(data_error("truncated.off"),
              HasSubstr("truncated.off: truncated OFF: file ends after 5 of 6 faces"));
}

// ---------------------------------------------------------------------------------------------------------
// Malformed content that a lenient reader (assimp, used before issue 13) would drop, clamp or misread
// silently: rejected, naming the line.

TEST(MeshIo, FaceIndexOutOfRange) {
  EXPECT_EQ(
      data_error("bad_index.off"),
      test::data_file("bad_index.off") + ": line 17: in face 6, vertex index 8 does not exist (8 vertices)");
  EXPECT_EQ(
      data_error("bad_index.obj"),
      test::data_file("bad_index.obj") + ": line 15: in face 6, vertex index 9 does not exist (8 vertices)");
  EXPECT_EQ(
      data_error("bad_index.ply"),
      test::data_file("bad_index.ply") + ": line 24: in face 6, vertex index 8 does not exist (8 vertices)");
}

TEST_F(MeshIoTest, ObjIndexForms) {
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  const std::string faces = "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
  // Negative indices count back from the last vertex so far; texture and normal references are ignored.
  TriangleMesh m = read_mesh(write("relative.obj", vertices + "vt 0 0\nvn 0 0 1\nf -4 -2 -3\nf 1/1 2/1 4/1\n"
                                                              "f 2//1 3//1 4//1\nf 1/1/1 4/1/1 3/1/1\n"));
  validate_mesh(m, "relative.obj");
  EXPECT_NEAR(signed_volume(m), 1.0 / 6.0, 1e-12);  // exact corner tetrahedron; round-off (measured 0)
  EXPECT_THAT(load_error(write("zero.obj", vertices + "f 0 1 2\n")),
              HasSubstr("zero.obj: line 5: in face 1, vertex index 0 does not exist (4 vertices)"));
  EXPECT_THAT(load_error(write("neg.obj", vertices + "f -1 -2 -5\n")),
              HasSubstr("neg.obj: line 5: in face 1, vertex index -5 does not exist (4 vertices)"));
  EXPECT_THAT(load_error(write("word.obj", vertices + "f 1 2 x\n")),
              HasSubstr("word.obj: line 5: in face 1, cannot read vertex index 'x'"));
  // Forward references are legal.
  EXPECT_EQ(read_mesh(write("forward.obj", faces + vertices)).triangles.size(), 4u);
}

TEST_F(MeshIoTest, ObjVertexLinesOtherReadersWouldSkip) {
  const std::string faces = "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
  EXPECT_THAT(load_error(write("dot.obj", "v 0 0 0\nv .5 0 0\nv 0 1 0\nv 0 0 1\n" + faces)),
              HasSubstr("dot.obj: line 2: cannot read vertex coordinate '.5'"));
  EXPECT_THAT(load_error(write("five.obj", "v 0 0 0\nv 1 0 0 1 1\nv 0 1 0\nv 0 0 1\n" + faces)),
              HasSubstr("five.obj: line 2: vertex with 5 numbers"));
  EXPECT_THAT(load_error(write("indent.obj", "v 0 0 0\n  v 1 0 0\nv 0 1 0\nv 0 0 1\n" + faces)),
              HasSubstr("indent.obj: line 2: indented 'v' line"));
  EXPECT_THAT(load_error(write("comment.obj", "v 0 0 0\nv 1 0 0 # 4\nv 0 1 0\nv 0 0 1\n" + faces)),
              HasSubstr("comment.obj: line 2: comment after 'v' data"));
}

// Lines and points are no surface: what remains is a point cloud, which validate_mesh rejects.
TEST(MeshIo, ObjWithoutTriangles) {
  const TriangleMesh m = read_mesh(test::data_file("lines_only.obj"));
  EXPECT_EQ(m.vertices.size(), 3u);
  EXPECT_TRUE(m.triangles.empty());
  EXPECT_EQ(data_error("lines_only.obj", true),
            test::data_file("lines_only.obj") + ": empty mesh (no triangles)");
}

TEST_F(MeshIoTest, OffMalformedLines) {
  const std::string header = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  EXPECT_THAT(load_error(write("neg.off", header + "3 0 2 1\n3 0 1 -1\n3 1 2 3\n3 0 3 2\n")),
              HasSubstr("neg.off: line 8: in face 2, vertex index -1 does not exist (4 vertices)"));
  EXPECT_THAT(load_error(write("big.off", header + "10 0 1 2 3 0 1 2 3 0 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n")),
              HasSubstr("big.off: line 7: face 1 has 10 vertices (OFF faces may have 1 to 9)"));
  const std::string faces = "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
  EXPECT_THAT(load_error(write("comment.off", "OFF\n4 4 0\n0 0 0\n# x\n1 0 0\n0 1 0\n0 0 1\n" + faces)),
              HasSubstr("comment.off: line 4: expected 3 coordinates of vertex 1"));
  EXPECT_THAT(load_error(write("nokeyword.off", "4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n" + faces)),
              HasSubstr("nokeyword.off: cannot parse: expected the OFF keyword, found '4'"));
  EXPECT_THAT(load_error(write("sameline.off", "OFF\n4 4 0 0 0 0\n1 0 0\n0 1 0\n0 0 1\n" + faces)),
              HasSubstr("sameline.off: line 2: unexpected '0'"));
  // Comments (also before the keyword), blank lines and CRLF are fine before the first vertex.
  const std::string ok =
      write("ok.off",
            "# tetrahedron\r\nOFF\r\n4 4 0 # counts\r\n\r\n# first vertex next\r\n0 0 0\r\n1 0 "
            "0\r\n\r\n0 1 0\r\n0 0 1\r\n3 0 2 1\r\n3 0 1 3\r\n3 1 2 3\r\n3 0 3 2\r\n");
  TriangleMesh m = read_mesh(ok);
  validate_mesh(m, ok);
  EXPECT_NEAR(signed_volume(m), 1.0 / 6.0, 1e-12);  // exact corner tetrahedron; round-off (measured 0)
}

TEST_F(MeshIoTest, AsciiStlFacetWithFourVertices) {
  EXPECT_THAT(load_error(write("four.stl",
                               "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                               "vertex 0 1 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid x\n")),
              HasSubstr("four.stl: facet 1 has 4 vertices (expected 3)"));
}

// Found by fuzz_mesh_stl: assimp leaked its partly built mesh when it threw on malformed ASCII STL (here
// binary junk, then a word where a number should be); ASCII STL is now read without assimp, and the
// sanitizer build checks that nothing leaks.
TEST(MeshIo, AsciiStlJunk) {
  EXPECT_THAT(data_error("fuzz/ascii_stl_leak_bad_number.stl"),
              HasSubstr("ascii_stl_leak_bad_number.stl: expected 'facet' or 'endsolid', found '"));
}

TEST_F(MeshIoTest, AsciiStlMalformedFacets) {
  const std::string head = "solid x\nfacet normal 0 0 1\nouter loop\n";
  EXPECT_THAT(load_error(write("word.stl", "solid x\nfacet normal 0 be\n")),
              HasSubstr("word.stl: facet 1: expected a number, found 'be'"));
  EXPECT_THAT(load_error(write("short.stl", head + "vertex 0 0 0\n")),
              HasSubstr("short.stl: facet 1 has 1 vertices (expected 3)"));
  EXPECT_THAT(load_error(write("nonormal.stl", "solid x\nfacet\nouter loop\n")),
              HasSubstr("nonormal.stl: facet 1: expected 'normal', found 'outer'"));
  EXPECT_THAT(load_error(write("noend.stl", head + "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n")),
              HasSubstr("noend.stl: facet 1: expected 'endfacet', found end of file"));
  EXPECT_THAT(load_error(write("stray.stl", "solid x\nvertex 0 0 0\nendsolid x\n")),
              HasSubstr("stray.stl: expected 'facet' or 'endsolid', found 'vertex'"));
  EXPECT_THAT(load_error(write("empty.stl", "solid x\nendsolid x\n")), HasSubstr("empty.stl: no triangles"));
}

// Found by fuzz_mesh_ply: a header with two format lines (ascii, then binary) passed our binary check,
// assimp parsed it as ASCII, threw, and leaked its mesh.
TEST(MeshIo, PlyWithTwoFormatLines) {
  EXPECT_EQ(data_error("fuzz/ply_leak_two_formats.ply"),
            test::data_file("fuzz/ply_leak_two_formats.ply") +
                ": cannot parse: PLY header line 3: second format line");
}

// Found by fuzz_mesh_ply: "end_header" followed by a vertical tab and more words on the same line; our
// header scan and assimp disagreed on where the binary data starts, and assimp read out of bounds.
TEST(MeshIo, PlyHeaderControlCharacters) {
  EXPECT_EQ(data_error("fuzz/ply_segv_end_header_vtab.ply"),
            test::data_file("fuzz/ply_segv_end_header_vtab.ply") +
                ": cannot parse: PLY header line 10: control character");
}

TEST_F(MeshIoTest, PlyEndHeaderMustEndItsLine) {
  EXPECT_THAT(load_error(write("extra.ply", "ply\nformat ascii 1.0\nelement vertex 0\nend_header x\n")),
              HasSubstr("extra.ply: cannot parse: PLY header line 4: unexpected 'x' after end_header"));
}

// Found by fuzz_mesh_ply: a vertex element with 'X' instead of 'x' made ASan's allocator check fire inside
// assimp (memory overwritten there). Positions x, y, z and a face index list are required by name.
TEST(MeshIo, PlyNeedsStandardVertexAndFaceProperties) {
  EXPECT_EQ(data_error("fuzz/ply_vertex_without_x.ply"),
            test::data_file("fuzz/ply_vertex_without_x.ply") +
                ": cannot parse: PLY 'vertex' element has no scalar property 'x'");
}

// Found by fuzz_mesh_ply: a closed, consistently wound surface whose signed volume is only round-off; its
// centre of mass came out 1e7 away and its volume 0 after re-centring. It is no solid.
TEST(MeshIo, DegenerateVolumeIsRejectedWhenBuildingTheParticle) {
  const std::string path = test::data_file("fuzz/ply_degenerate_volume.ply");
  try {
    (void)repose::load_particle(path, 1.0);
    ADD_FAILURE() << "accepted";
  } catch (const repose::Error& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": degenerate solid: its volume is too small to locate its centre of mass");
  }
}

// Found by fuzz_mesh_off: a comment with lone carriage returns ends early for assimp, which then read
// "81460006007" as a count and tried to allocate 66 GB. A CR is accepted only as part of CRLF.
TEST(MeshIo, LoneCarriageReturnIsRejected) {
  EXPECT_EQ(data_error("fuzz/off_lone_carriage_return.off"),
            test::data_file("fuzz/off_lone_carriage_return.off") + ": line 2: control character (byte 13)");
}

TEST_F(MeshIoTest, PlyHeaderChecksElementsAndProperties) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n";
  EXPECT_THAT(load_error(write("noz.ply", head + "element face 0\nproperty list uchar int vertex_indices\n"
                                                 "end_header\n")),
              HasSubstr("noz.ply: cannot parse: PLY 'vertex' element has no scalar property 'z'"));
  EXPECT_THAT(load_error(write("noface.ply", head + "property float z\nelement face 1\nend_header\n")),
              HasSubstr("noface.ply: cannot parse: PLY 'face' element has no 'vertex_indices' list"));
  EXPECT_THAT(load_error(write("twice.ply", head + "property float y\nend_header\n")),
              HasSubstr("twice.ply: cannot parse: PLY header line 6: property 'y' appears twice"));
}

// Found by fuzz_mesh_obj: "v\0 1 1 0" was no vertex line to our scan but one to assimp, which then threw
// and leaked its mesh. Text formats reject control characters other than tab and line ends.
TEST(MeshIo, ObjControlCharacter) {
  EXPECT_EQ(data_error("fuzz/obj_leak_nul_byte.obj"),
            test::data_file("fuzz/obj_leak_nul_byte.obj") + ": line 4: control character (byte 0)");
}

// Found by fuzz_mesh_obj: "vv 0 0 0" is a vertex to assimp but an unknown line to a whitespace tokenizer.
TEST(MeshIo, ObjGluedKeyword) {
  EXPECT_EQ(data_error("fuzz/obj_leak_glued_keyword.obj"),
            test::data_file("fuzz/obj_leak_glued_keyword.obj") + ": line 1: unknown keyword 'vv'");
}

TEST_F(MeshIoTest, TextFormatsRejectControlCharacters) {
  EXPECT_THAT(load_error(write("vt.obj", "v 0 0 0\nv\v1 0 0\n")),
              HasSubstr("vt.obj: line 2: control character (byte 11)"));
  EXPECT_THAT(load_error(write("ff.off", "OFF\n3 1 0\n0 0 0\f\n")),
              HasSubstr("ff.off: line 3: control character (byte 12)"));
  EXPECT_THAT(
      load_error(write(
          "nul.ply",
          "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
          "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n1 2 3" +
              std::string(1, '\0') + "\n")),
      HasSubstr("nul.ply: line 10: control character (byte 0)"));
}

TEST(MeshIo, ReadFromMemoryMatchesReadMesh) {
  for (const char* name : {"cube_ascii.stl", "cube_binary.stl", "cube.obj", "cube_binary.ply", "cube.off"}) {
    std::ifstream in(test::data_file(name), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const TriangleMesh from_memory = read_mesh_from_memory(bytes, name);
    const TriangleMesh from_file = read_mesh(test::data_file(name));
    EXPECT_EQ(from_memory.vertices, from_file.vertices) << name;
    EXPECT_EQ(from_memory.triangles, from_file.triangles) << name;
  }
  EXPECT_THROW(read_mesh_from_memory("solid x\n", "mesh.3mf"), Error);
}

// ---------------------------------------------------------------------------------------------------------
// Files that parse but are not valid solids: validate_mesh names the file and the problem.

TEST(MeshIo, NonFiniteCoordinates) {
  EXPECT_EQ(data_error("nan.stl", true),
            test::data_file("nan.stl") + ": vertex 2 has a non-finite coordinate");
  EXPECT_EQ(data_error("nan.off", true),
            test::data_file("nan.off") + ": vertex 2 has a non-finite coordinate");
  EXPECT_THAT(data_error("inf.obj", true), HasSubstr("inf.obj: vertex 3 has a non-finite coordinate"));
}

TEST(MeshIo, OpenSurface) {
  EXPECT_EQ(data_error("open_cube.off", true),
            test::data_file("open_cube.off") +
                ": open surface: 4 boundary edges (the mesh must be a closed solid)");
}

TEST(MeshIo, NonManifoldSurface) {
  EXPECT_EQ(data_error("nonmanifold.off", true),
            test::data_file("nonmanifold.off") +
                ": non-manifold surface: 1 edges shared by more than two triangles");
}

TEST(MeshIo, InconsistentWinding) {
  EXPECT_EQ(data_error("flipped_face.off", true),
            test::data_file("flipped_face.off") +
                ": inconsistent winding: 3 edges whose two triangles face opposite ways");
}

TEST(MeshIo, ZeroVolume) {
  EXPECT_EQ(data_error("flat.off", true), test::data_file("flat.off") + ": zero volume");
}

TEST(MeshIo, InvertedCubeIsFlipped) {
  TriangleMesh m = read_mesh(test::data_file("inverted_cube.off"));
  EXPECT_DOUBLE_EQ(signed_volume(m), -1.0);
  const MeshReport r = validate_mesh(m, "inverted_cube.off");
  EXPECT_TRUE(r.flipped);
  EXPECT_THAT(r.warnings, ::testing::Contains("inverted winding (negative volume): all triangles flipped"));
  EXPECT_DOUBLE_EQ(signed_volume(m), 1.0);
}

}  // namespace
}  // namespace repose
