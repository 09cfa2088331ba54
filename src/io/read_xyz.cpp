// XYZ point clouds: one point per line, "x y z" and then anything (normals, colours, intensities: ignored);
// '#' starts a comment, blank lines are skipped. The result has vertices and no triangles.
#include "readers.hpp"
#include "text_scan.hpp"

namespace repose::io {

TriangleMesh read_xyz(const std::string& path, std::string_view data) {
  check_control_characters(path, data);
  TriangleMesh mesh;
  for_each_line(data, 0, 1, [&](std::int64_t line_no, std::string_view line, std::size_t) {
    line = strip_comment(line);
    std::size_t pos = 0;
    double xyz[3];
    for (int k = 0; k < 3; ++k) {
      const std::string_view token = next_token(line, pos);
      if (k == 0 && token.empty()) return true;  // blank or comment line
      if (!parse_double(token, xyz[k])) {
        fail(path,
             at_line(line_no) + "expected x y z, found " + (token.empty() ? "end of line" : shown(token)));
      }
    }
    check_vertex_count(path, mesh.vertices.size() + 1);
    mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
    return true;
  });
  return mesh;
}

}  // namespace repose::io
