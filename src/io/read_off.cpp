// OFF (Object File Format): a keyword ([ST][C][N]OFF), the vertex, face and edge counts, then one vertex per
// line (x y z, then anything: normals, colours) and one face per line ("k i1 ... ik", then anything: a
// colour), indices 0-based. Faces are fan-triangulated; faces of 1 or 2 vertices are no part of the surface.
// '#' starts a comment. Lines after the last face are ignored.
//
// Kept strict where OFF readers disagree: the keyword is required (without it, "4OFF"-style flags and a
// vertex count starting with 4 look alike), the counts end their line, blank and comment lines may come
// only before the first vertex (empty lines anywhere), faces have 1 to 9 vertices, and lines are at most
// 4095 characters.
#include "readers.hpp"
#include "text_scan.hpp"

namespace repose::io {
namespace {

constexpr std::size_t kMaxLine = 4095;
constexpr std::int64_t kMaxFaceVertices = 9;

bool is_off_keyword(std::string_view s) {
  if (s.starts_with("ST")) s.remove_prefix(2);
  if (s.starts_with("C")) s.remove_prefix(1);
  if (s.starts_with("N")) s.remove_prefix(1);
  return s == "OFF";
}

}  // namespace

TriangleMesh read_off(const std::string& path, std::string_view data) {
  check_control_characters(path, data);
  std::vector<std::string_view> tokens;
  // Header: keyword, then the three counts, which must end their line.
  std::uint64_t counts[3] = {0, 0, 0};
  std::size_t n_counts = 0;
  std::size_t data_start = data.size();
  std::int64_t data_line = 0;
  bool keyword = false;
  for_each_line(data, 0, 1, [&](std::int64_t line_no, std::string_view line, std::size_t next) {
    split_tokens(strip_comment(line), tokens);
    for (const std::string_view token : tokens) {
      // Anything more on this line would be read as the first vertex by some readers and not by others.
      if (n_counts == 3) fail(path, at_line(line_no) + "unexpected '" + std::string(token) + "'");
      if (!keyword) {
        if (!is_off_keyword(token)) {
          fail(path, "cannot parse: expected the OFF keyword, found '" + std::string(token) + "'");
        }
        keyword = true;
        continue;
      }
      if (!parse_count(token, counts[n_counts])) {
        fail(path,
             at_line(line_no) + "expected vertex, face and edge counts, found '" + std::string(token) + "'");
      }
      ++n_counts;
    }
    if (n_counts < 3) return true;
    data_start = next;
    data_line = line_no + 1;
    return false;
  });
  if (n_counts < 3) fail(path, "cannot parse: missing OFF vertex, face and edge counts");
  const std::uint64_t n_vertices = counts[0], n_faces = counts[1];

  // A vertex line holds at least 3 numbers and a face line at least one, each with a separator.
  const std::uint64_t room = data.size() - data_start;
  if (n_vertices > room / 6) {
    fail(path, "OFF header claims " + str(n_vertices) + " vertices, more than the " + str(room) +
                   " bytes after it can hold");
  }
  if (n_faces > (room - 6 * n_vertices) / 2) {
    fail(path, "OFF header claims " + str(n_faces) + " faces, more than the " + str(room) +
                   " bytes after it can hold");
  }
  check_vertex_count(path, n_vertices);
  TriangleMesh mesh;
  mesh.vertices.reserve(n_vertices);
  mesh.triangles.reserve(n_faces);

  Polygons polygons(mesh.triangles);
  std::uint64_t faces = 0;
  std::int32_t corners[kMaxFaceVertices];
  bool in_data = false;
  for_each_line(data, data_start, data_line, [&](std::int64_t line_no, std::string_view line, std::size_t) {
    if (mesh.vertices.size() == n_vertices && faces == n_faces) return false;
    if (line.empty()) return true;
    split_tokens(strip_comment(line), tokens);
    if (!in_data && tokens.empty()) return true;
    in_data = true;
    if (line.size() > kMaxLine) fail(path, at_line(line_no) + "longer than " + str(kMaxLine) + " characters");
    if (mesh.vertices.size() < n_vertices) {
      double xyz[3] = {0, 0, 0};
      if (tokens.size() < 3 || !parse_double(tokens[0], xyz[0]) || !parse_double(tokens[1], xyz[1]) ||
          !parse_double(tokens[2], xyz[2])) {
        fail(path, at_line(line_no) + "expected 3 coordinates of vertex " + str(mesh.vertices.size()));
      }
      mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
      return true;
    }
    ++faces;
    std::int64_t k = 0;
    if (tokens.empty() || !parse_int(tokens[0], k)) {
      fail(path, at_line(line_no) + "expected the vertex count of face " + str(faces));
    }
    if (k < 1 || k > kMaxFaceVertices) {
      fail(path, at_line(line_no) + "face " + str(faces) + " has " + std::to_string(k) +
                     " vertices (OFF faces may have 1 to " + std::to_string(kMaxFaceVertices) + ")");
    }
    if (tokens.size() < static_cast<std::size_t>(k) + 1) {
      fail(path, at_line(line_no) + "face " + str(faces) + " lists fewer than " + std::to_string(k) +
                     " vertex indices");
    }
    for (std::int64_t m = 1; m <= k; ++m) {
      const std::string_view token = tokens[static_cast<std::size_t>(m)];
      std::int64_t index = 0;
      if (!parse_int(token, index)) {
        fail(path, at_line(line_no) + "in face " + str(faces) + ", cannot read vertex index '" +
                       std::string(token) + "'");
      }
      if (index < 0 || static_cast<std::uint64_t>(index) >= n_vertices) {
        fail(path, at_line(line_no) + "in face " + str(faces) + ", vertex index " + std::to_string(index) +
                       " does not exist (" + str(n_vertices) + " vertices)");
      }
      corners[m - 1] = static_cast<std::int32_t>(index);
    }
    polygons.add(corners, static_cast<std::size_t>(k));
    return true;
  });
  if (mesh.vertices.size() < n_vertices) {
    fail(path, "truncated OFF: file ends after " + str(mesh.vertices.size()) + " of " + str(n_vertices) +
                   " vertices");
  }
  if (faces < n_faces) {
    fail(path, "truncated OFF: file ends after " + str(faces) + " of " + str(n_faces) + " faces");
  }
  polygons.finish(mesh.vertices);
  return mesh;
}

}  // namespace repose::io
