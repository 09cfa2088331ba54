// The per-format mesh readers behind read_mesh(). Each reads the file's bytes in one pass and returns the
// vertices exactly as the file lists them (STL: its corners merged, see read_stl) and the polygons
// fan-triangulated; a file with vertices but no faces gives a point cloud (no triangles). Errors are
// repose::Error("PATH: problem"), naming the line or element where it helps.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "repose/geometry/types.hpp"

namespace repose::io {

TriangleMesh read_stl(const std::string& path, std::string_view data);
TriangleMesh read_obj(const std::string& path, std::string_view data);
TriangleMesh read_off(const std::string& path, std::string_view data);
TriangleMesh read_ply(const std::string& path, std::string_view data);
TriangleMesh read_xyz(const std::string& path, std::string_view data);

/// Fails unless `count` vertices can be numbered by a Triangle's int32 indices.
void check_vertex_count(const std::string& path, std::uint64_t count);

/// Polygons as they are read, triangulated with their winding: a fan from the first corner (c0, c1, c2),
/// (c0, c2, c3), ..., which covers a convex polygon exactly, except that a quad with a concave corner is
/// fanned from that corner, so that its diagonal lies inside (as assimp did before issue 13, so quad meshes
/// keep their triangles). Vertices may follow the faces that use them (OBJ forward references, PLY elements
/// in any order), so quads are settled in finish(), once every vertex is known. Fewer than 3 corners add
/// nothing.
class Polygons {
 public:
  explicit Polygons(std::vector<Triangle>& out) : out_(out) {}
  void add(const std::int32_t* c, std::size_t n) {
    if (n == 4) quads_.push_back(out_.size());
    for (std::size_t k = 1; k + 1 < n; ++k) out_.push_back({c[0], c[k], c[k + 1]});
  }
  void finish(const std::vector<Vec3>& vertices);

 private:
  std::vector<Triangle>& out_;
  std::vector<std::size_t> quads_;  // where each quad's two triangles start in out_
};

}  // namespace repose::io
