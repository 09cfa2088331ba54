// Wavefront OBJ: 'v x y z [w]' or 'v x y z r g b' vertices in file order, 'f' faces of 1-based or negative
// (relative) indices in the forms i, i/t, i//n, i/t/n, fan-triangulated. 'l' and 'p' (lines, points) are
// checked but are no part of the surface, nor are faces of fewer than 3 vertices; every other statement
// (vt, vn, g, o, s, usemtl, mtllib, ...) is ignored.
//
// The reader is strict where OBJ readers disagree, so that a file it accepts means the same to other
// programs: a statement word starting with v, f, l or p must be one of the above ("vv", "f6" are
// rejected, not skipped), and v/f/l/p lines may not be indented, carry a trailing comment or continue on
// the next line ('\'); coordinates start with a digit or sign (".5" is rejected) or are nan/inf.
#include <algorithm>
#include <limits>
#include <optional>

#include "readers.hpp"
#include "text_scan.hpp"

namespace repose::io {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

bool starts_with_word(std::string_view s, std::string_view word) {
  if (s.size() < word.size()) return false;
  for (std::size_t k = 0; k < word.size(); ++k)
    if (lower(s[k]) != word[k]) return false;
  return true;
}

bool obj_number(std::string_view s, double& out) {
  if (s.empty()) return false;
  const char c = s.front();
  const bool numeric_start = is_digit(c) || c == '-' || c == '+';
  return (numeric_start || starts_with_word(s, "nan") || starts_with_word(s, "inf")) && parse_double(s, out);
}

bool is_statement(std::string_view key) {
  return key == "v" || key == "vt" || key == "vn" || key == "vp" || key == "f" || key == "l" || key == "p";
}

// Where in the file an index error is: indices are checked in file order, token by token.
struct Position {
  std::int64_t line = 0;
  std::size_t token = 0;
  bool operator<(const Position& o) const { return line < o.line || (line == o.line && token < o.token); }
};

// A positive index beyond the vertices read so far: legal if the file defines that many in the end.
struct ForwardIndex {
  Position at;
  std::int64_t face = 0;  // its number, 0 on an 'l' or 'p' line
  std::int64_t index = 0;
};

std::string where(std::int64_t line, std::int64_t face) {
  return at_line(line) + (face > 0 ? "in face " + str(face) + ", " : std::string());
}

}  // namespace

TriangleMesh read_obj(const std::string& path, std::string_view data) {
  check_control_characters(path, data);
  TriangleMesh mesh;
  std::vector<std::string_view> tokens;
  std::vector<std::int32_t> corners;
  Polygons polygons(mesh.triangles);
  // Errors in v lines and keywords come before index errors anywhere in the file, and index errors in file
  // order; forward indices are only known to be bad at the end. So the first index error waits, and of the
  // forward indices only those above every earlier one are kept: only they can be the first to exceed.
  std::optional<std::pair<Position, std::string>> index_error;
  std::vector<ForwardIndex> forward;
  std::int64_t faces = 0;
  for_each_line(data, 0, 1, [&](std::int64_t line_no, std::string_view line, std::size_t) {
    split_tokens(line, tokens);
    if (tokens.empty()) return true;
    const std::string_view key = tokens.front();
    if (std::string_view("vflp").find(key.front()) != std::string_view::npos && !is_statement(key)) {
      fail(path, at_line(line_no) + "unknown keyword '" + std::string(key.substr(0, 40)) + "'");
    }
    if (key != "v" && key != "f" && key != "l" && key != "p") return true;
    if (is_space(line.front())) fail(path, at_line(line_no) + "indented '" + std::string(key) + "' line");
    if (line.find('#') != std::string_view::npos)
      fail(path, at_line(line_no) + "comment after '" + std::string(key) + "' data");
    if (line.back() == '\\') fail(path, at_line(line_no) + "line continuation ('\\')");

    if (key == "v") {
      const std::size_t n = tokens.size() - 1;
      if (n != 3 && n != 4 && n != 6) {
        fail(path, at_line(line_no) + "vertex with " + str(n) +
                       " numbers (expected x y z, x y z w or x y z r g b)");
      }
      double xyz[3] = {0, 0, 0};
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        double value = 0;
        if (!obj_number(tokens[k], value)) {
          fail(path, at_line(line_no) + "cannot read vertex coordinate '" + std::string(tokens[k]) + "'");
        }
        if (k <= 3) xyz[k - 1] = value;
      }
      check_vertex_count(path, mesh.vertices.size() + 1);
      mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
      return true;
    }

    const bool face = key == "f";
    if (face) ++faces;
    if (index_error) return true;
    const std::int64_t face_no = face ? faces : 0;
    const auto so_far = static_cast<std::int64_t>(mesh.vertices.size());
    corners.clear();
    for (std::size_t k = 1; k < tokens.size(); ++k) {
      const std::string_view ref = tokens[k].substr(0, tokens[k].find('/'));
      std::int64_t index = 0;
      if (!parse_int(ref, index)) {
        index_error.emplace(Position{line_no, k}, where(line_no, face_no) + "cannot read vertex index '" +
                                                      std::string(tokens[k]) + "'");
        return true;
      }
      // Positive indices are 1-based; negative ones count back from the vertices defined so far.
      if (index > 0) {
        if (index > so_far && (forward.empty() || index > forward.back().index)) {
          forward.push_back({Position{line_no, k}, face_no, index});
        }
        // An index past the int32 range fails at the end: no file holds that many vertices.
        corners.push_back(static_cast<std::int32_t>(
            std::min<std::int64_t>(index - 1, std::numeric_limits<std::int32_t>::max())));
      } else if (index < 0 && index >= -so_far) {
        corners.push_back(static_cast<std::int32_t>(so_far + index));
      } else {
        index_error.emplace(Position{line_no, k}, where(line_no, face_no) + "vertex index " +
                                                      std::to_string(index) + " does not exist (" +
                                                      str(so_far) + " vertices)");
        return true;
      }
    }
    if (face) polygons.add(corners.data(), corners.size());
    return true;
  });

  const auto total = static_cast<std::int64_t>(mesh.vertices.size());
  for (const ForwardIndex& f : forward) {
    if (f.index <= total) continue;
    if (index_error && index_error->first < f.at) break;
    fail(path, where(f.at.line, f.face) + "vertex index " + std::to_string(f.index) + " does not exist (" +
                   str(total) + " vertices)");
  }
  if (index_error) fail(path, index_error->second);
  polygons.finish(mesh.vertices);
  return mesh;
}

}  // namespace repose::io
