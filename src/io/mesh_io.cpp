// Mesh reading goes through assimp, but only after our own scan of the file: assimp trusts element counts
// in headers (allocating whatever they claim), silently clamps or drops bad indices and short vertex lines
// in OFF, OBJ and PLY, and aborts the process on some inconsistent OFF files. The scans below reject
// those inputs with a message naming the line; what they accept is plain, well-formed data that assimp
// parses correctly.
#include "repose/io/mesh_io.hpp"

#include <assimp/MemoryIOWrapper.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "repose/error.hpp"

namespace repose {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw Error(path + ": " + what); }

std::string errno_message(int error) { return std::error_code(error, std::generic_category()).message(); }

std::string str(std::uint64_t n) { return std::to_string(n); }

// ---------------------------------------------------------------------------------------------------------
// Text scanning helpers.

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// The whitespace-separated token starting at or after `pos` (empty at the end); advances `pos` past it.
std::string_view next_token(std::string_view s, std::size_t& pos) {
  while (pos < s.size() && (is_space(s[pos]) || s[pos] == '\n')) ++pos;
  const std::size_t start = pos;
  while (pos < s.size() && !is_space(s[pos]) && s[pos] != '\n') ++pos;
  return s.substr(start, pos - start);
}

std::vector<std::string_view> split_tokens(std::string_view s) {
  std::vector<std::string_view> tokens;
  std::size_t pos = 0;
  for (std::string_view t = next_token(s, pos); !t.empty(); t = next_token(s, pos)) tokens.push_back(t);
  return tokens;
}

std::string_view strip_comment(std::string_view line) { return line.substr(0, line.find('#')); }

// Calls f(number, line, next) for the lines from offset `start` on, numbering them from `first_number`
// ('\r' of CRLF removed; `next` is the offset of the following line). f returns false to stop.
template <typename F>
void for_each_line(std::string_view text, std::size_t start, std::int64_t first_number, F&& f) {
  std::int64_t number = first_number;
  for (std::size_t pos = start; pos < text.size(); ++number) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view line = text.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = std::min(end + 1, text.size());
    if (!f(number, line, pos)) return;
  }
}

std::string at_line(std::int64_t number) { return "line " + std::to_string(number) + ": "; }

// assimp splits text formats at spaces, tabs and line ends only, and stops at a NUL byte, so a file with
// other control characters reads differently in our scan and in assimp; assimp then throws on the
// mismatch and leaks what it has built (found by fuzz_mesh_obj: "v\0 1 1 0"). Mesh files never need them.
void check_control_characters(const std::string& path, std::string_view text, std::int64_t first_line = 1) {
  const auto control = [](char c) {
    return (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r' && c != '\n') || c == 0x7f;
  };
  // A carriage return only as part of CRLF: assimp ends a line at a lone CR where this scan does not, so a
  // "comment" could hide a count line from us (found by fuzz_mesh_off: a 66 GB allocation in assimp).
  const auto at = std::adjacent_find(
      text.begin(), text.end(), [&](char c, char next) { return control(c) || (c == '\r' && next != '\n'); });
  if (at == text.end()) {
    // adjacent_find never tests the last character alone.
    if (text.empty() || (!control(text.back()) && text.back() != '\r')) return;
    const auto line = first_line + std::count(text.begin(), text.end(), '\n');
    fail(path,
         at_line(line) + "control character (byte " + str(static_cast<unsigned char>(text.back())) + ")");
  }
  const auto line = first_line + std::count(text.begin(), at, '\n');
  fail(path, at_line(line) + "control character (byte " + str(static_cast<unsigned char>(*at)) + ")");
}

bool parse_int(std::string_view s, std::int64_t& out) {
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && ptr == s.data() + s.size() && !s.empty();
}

bool parse_count(std::string_view s, std::uint64_t& out) {
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  if (ptr != s.data() + s.size() || s.empty()) return false;
  if (ec == std::errc::result_out_of_range) out = std::numeric_limits<std::uint64_t>::max();
  return ec == std::errc() || ec == std::errc::result_out_of_range;
}

// A real number, including nan, inf and values that overflow (validate_mesh rejects non-finite ones later).
bool is_number(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  return !s.empty() && ptr == s.data() + s.size() &&
         (ec == std::errc() || ec == std::errc::result_out_of_range);
}

// ---------------------------------------------------------------------------------------------------------
// STL.

std::uint32_t read_le32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 |
         std::uint32_t{b[3]} << 24;
}

// ASCII STL starts with "solid" and, unlike binary STL, never contains a NUL byte. Binary files often start
// with "solid" too, so the keyword alone decides nothing.
bool looks_like_ascii_stl(std::string_view data) {
  const std::size_t start = data.find_first_not_of(" \t\r\n");
  return start != std::string_view::npos && data.substr(start).starts_with("solid") &&
         data.find('\0') == std::string_view::npos;
}

// A binary file's size is 84 + 50 × the facet count in its header.
bool is_binary_stl_size(std::string_view data) {
  return data.size() >= 84 && 84 + 50 * std::uint64_t{read_le32(data.data() + 80)} == data.size();
}

bool is_ascii_stl(std::string_view data) { return !is_binary_stl_size(data) && looks_like_ascii_stl(data); }

std::string shown(std::string_view token) {
  if (token.empty()) return "end of file";
  std::string out = "'";
  out.append(token.substr(0, 40));
  if (token.size() > 40) out += "...";
  out += '\'';
  return out;
}

// ASCII STL is read here, not by assimp: assimp leaks the meshes it has built whenever it throws on a
// malformed ASCII file (a word where a number should be, a facet cut short; found by fuzz_mesh_stl), and
// its lenient tokenizer would have to be mirrored exactly to rule that out. The grammar: "solid [name]",
// facets "facet normal nx ny nz / outer loop / vertex x y z (three times) / endloop / endfacet", then
// "endsolid [name]"; several solids may follow each other, and the last endsolid may be missing, as assimp
// allows. Coordinates are rounded to float, as binary STL and assimp store them.
TriangleMesh read_ascii_stl(const std::string& path, std::string_view data) {
  TriangleMesh mesh;
  std::size_t pos = 0;
  const auto skip_line = [&] { pos = std::min(data.find('\n', pos), data.size()); };
  const auto expect = [&](std::string_view word, const std::string& where) {
    const std::string_view token = next_token(data, pos);
    if (token != word) fail(path, where + "expected '" + std::string(word) + "', found " + shown(token));
  };
  const auto number = [&](const std::string& where) {
    const std::string_view token = next_token(data, pos);
    if (!is_number(token)) fail(path, where + "expected a number, found " + shown(token));
    return static_cast<double>(std::strtof(std::string(token).c_str(), nullptr));
  };
  std::int64_t facet = 0;
  std::string_view token = next_token(data, pos);
  while (token.starts_with("solid")) {  // the name may follow without a space, as assimp reads it
    skip_line();
    for (token = next_token(data, pos); token == "facet"; token = next_token(data, pos)) {
      ++facet;
      const std::string where = "facet " + str(facet) + ": ";
      expect("normal", where);
      for (int k = 0; k < 3; ++k) number(where);
      expect("outer", where);
      expect("loop", where);
      std::int64_t vertices = 0;
      for (token = next_token(data, pos); token == "vertex"; token = next_token(data, pos)) {
        const double x = number(where);
        const double y = number(where);
        const double z = number(where);
        if (++vertices <= 3) mesh.vertices.emplace_back(x, y, z);
      }
      if (vertices != 3) {
        fail(path, "facet " + str(facet) + " has " + str(vertices) + " vertices (expected 3)");
      }
      if (token != "endloop") fail(path, where + "expected 'endloop', found " + shown(token));
      expect("endfacet", where);
      if (mesh.vertices.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
        fail(path, "too many vertices (more than " + str(std::numeric_limits<std::int32_t>::max()) + ")");
      }
      const auto first = static_cast<std::int32_t>(mesh.vertices.size() - 3);
      mesh.triangles.push_back({first, first + 1, first + 2});
    }
    if (token.empty()) break;
    if (token != "endsolid") fail(path, "expected 'facet' or 'endsolid', found " + shown(token));
    skip_line();
    token = next_token(data, pos);
  }
  if (!token.empty()) fail(path, "expected 'solid', found " + shown(token));
  if (mesh.triangles.empty()) fail(path, "no triangles");
  return mesh;
}

// Binary STL: returns how many leading bytes assimp should parse (the file may carry trailing bytes).
std::size_t check_binary_stl(const std::string& path, std::string_view data) {
  const std::uint64_t size = data.size();
  const std::uint64_t count = size >= 84 ? read_le32(data.data() + 80) : 0;
  const std::uint64_t needed = 84 + 50 * count;  // 64-bit: 50 * 2^31 must not wrap to 0
  if (size < 84) {
    fail(path, "truncated binary STL: file has " + str(size) + " bytes, less than the 84-byte header");
  }
  if (needed > size) {
    fail(path, "truncated binary STL: header claims " + str(count) + " triangles (needs " + str(needed) +
                   " bytes), file has " + str(size) + " bytes");
  }
  if (count == 0) fail(path, "no triangles");
  return needed;
}

// ---------------------------------------------------------------------------------------------------------
// OBJ: assimp drops 'v' lines it cannot count as 3, 4 or 6 numbers (shifting every later index), ignores
// indented lines, and reports a bad face index without saying where.

// assimp counts a coordinate only if it starts with a digit or sign, or is nan/inf.
bool is_obj_number(std::string_view s) {
  if (s.empty()) return false;
  const char c = s.front();
  const bool numeric_start = std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+';
  std::string lower(s.substr(0, 3));
  for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return (numeric_start || lower == "nan" || lower == "inf") && is_number(s);
}

void check_obj(const std::string& path, std::string_view data) {
  check_control_characters(path, data);
  // Pass 1: vertex lines. Indices may point forward, so faces are checked against the final count.
  std::int64_t total_vertices = 0;
  for_each_line(data, 0, 1, [&](std::int64_t line_no, std::string_view line, std::size_t) {
    const auto tokens = split_tokens(line);
    if (tokens.empty()) return true;
    const std::string key(tokens.front());
    // assimp keys on the first character, so it reads "vv 0 0 0" as a vertex and "f6 8 7" as a face where
    // we would skip both; it then threw on the shifted indices and leaked (found by fuzz_mesh_obj).
    if (std::string_view("vflp").find(key.front()) != std::string_view::npos && key != "v" && key != "vt" &&
        key != "vn" && key != "vp" && key != "f" && key != "l" && key != "p") {
      fail(path, at_line(line_no) + "unknown keyword '" + std::string(tokens.front().substr(0, 40)) + "'");
    }
    if (key != "v" && key != "f" && key != "l" && key != "p") return true;
    // Forms assimp would skip or misread without an error.
    if (is_space(line.front())) fail(path, at_line(line_no) + "indented '" + key + "' line");
    if (line.find('#') != std::string_view::npos) {
      fail(path, at_line(line_no) + "comment after '" + key + "' data");
    }
    if (line.back() == '\\') fail(path, at_line(line_no) + "line continuation ('\\')");
    if (key != "v") return true;
    const std::size_t n = tokens.size() - 1;
    if (n != 3 && n != 4 && n != 6) {
      fail(path,
           at_line(line_no) + "vertex with " + str(n) + " numbers (expected x y z, x y z w or x y z r g b)");
    }
    for (std::size_t k = 1; k < tokens.size(); ++k) {
      if (!is_obj_number(tokens[k])) {
        fail(path, at_line(line_no) + "cannot read vertex coordinate '" + std::string(tokens[k]) + "'");
      }
    }
    ++total_vertices;
    return true;
  });

  // Pass 2: indices of faces, lines and points.
  std::int64_t vertices = 0, faces = 0;
  for_each_line(data, 0, 1, [&](std::int64_t line_no, std::string_view line, std::size_t) {
    const auto tokens = split_tokens(line);
    if (tokens.empty()) return true;
    const std::string_view key = tokens.front();
    if (key == "v") ++vertices;
    if (key != "f" && key != "l" && key != "p") return true;
    if (key == "f") ++faces;
    auto where = [&] {
      return at_line(line_no) + (key == "f" ? "in face " + str(faces) + ", " : std::string());
    };
    for (std::size_t k = 1; k < tokens.size(); ++k) {
      const std::string_view ref = tokens[k].substr(0, tokens[k].find('/'));
      std::int64_t index = 0;
      if (!parse_int(ref, index)) {
        fail(path, where() + "cannot read vertex index '" + std::string(tokens[k]) + "'");
      }
      // Positive indices are 1-based; negative ones count back from the vertices defined so far.
      const bool exists = index > 0 ? index <= total_vertices : index < 0 && -index <= vertices;
      if (!exists) {
        fail(path, where() + "vertex index " + std::to_string(index) + " does not exist (" +
                       str(index > 0 ? total_vertices : vertices) + " vertices)");
      }
    }
    return true;
  });
}

// ---------------------------------------------------------------------------------------------------------
// OFF: assimp allocates the header's counts up front, clamps out-of-range indices to the last vertex, drops
// faces with more than 9 vertices, and aborts on a file with fewer faces than the header claims.

// assimp copies each data line into a 4096-byte buffer.
constexpr std::size_t kOffMaxLine = 4095;

bool is_off_keyword(std::string_view s) {
  if (s.starts_with("ST")) s.remove_prefix(2);
  if (s.starts_with("C")) s.remove_prefix(1);
  if (s.starts_with("N")) s.remove_prefix(1);
  return s == "OFF";
}

void check_off(const std::string& path, std::string_view data) {
  check_control_characters(path, data);
  // Header: keyword, then the vertex, face and edge counts, which must end their line. The keyword is
  // optional in the format, but without it assimp takes a leading '4' of the vertex count for a flag.
  std::vector<std::uint64_t> counts;
  std::size_t data_start = data.size();
  std::int64_t data_line = 0;
  bool keyword = false;
  for_each_line(data, 0, 1, [&](std::int64_t line_no, std::string_view line, std::size_t next) {
    for (const std::string_view token : split_tokens(strip_comment(line))) {
      // assimp would read the rest of this line as the first vertex.
      if (counts.size() == 3) fail(path, at_line(line_no) + "unexpected '" + std::string(token) + "'");
      if (!keyword) {
        if (!is_off_keyword(token)) {
          fail(path, "cannot parse: expected the OFF keyword, found '" + std::string(token) + "'");
        }
        keyword = true;
        continue;
      }
      std::uint64_t n = 0;
      if (!parse_count(token, n)) {
        fail(path,
             at_line(line_no) + "expected vertex, face and edge counts, found '" + std::string(token) + "'");
      }
      counts.push_back(n);
    }
    if (counts.size() < 3) return true;
    data_start = next;
    data_line = line_no + 1;
    return false;
  });
  if (counts.size() < 3) fail(path, "cannot parse: missing OFF vertex, face and edge counts");
  const std::uint64_t n_vertices = counts[0], n_faces = counts[1];
  if (n_faces == 0) fail(path, "no triangles");

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

  std::uint64_t vertices = 0, faces = 0;
  bool in_data = false;  // assimp skips blank and comment lines only before the first vertex
  for_each_line(data, data_start, data_line, [&](std::int64_t line_no, std::string_view line, std::size_t) {
    if (vertices == n_vertices && faces == n_faces) return false;
    if (line.empty()) return true;
    const auto tokens = split_tokens(strip_comment(line));
    if (!in_data && tokens.empty()) return true;
    in_data = true;
    if (line.size() > kOffMaxLine) {
      fail(path, at_line(line_no) + "longer than " + str(kOffMaxLine) + " characters");
    }
    if (vertices < n_vertices) {
      if (tokens.size() < 3 || !is_number(tokens[0]) || !is_number(tokens[1]) || !is_number(tokens[2])) {
        fail(path, at_line(line_no) + "expected 3 coordinates of vertex " + str(vertices));
      }
      ++vertices;
      return true;
    }
    ++faces;
    std::int64_t k = 0;
    if (tokens.empty() || !parse_int(tokens[0], k)) {
      fail(path, at_line(line_no) + "expected the vertex count of face " + str(faces));
    }
    if (k < 1 || k > 9) {
      fail(path, at_line(line_no) + "face " + str(faces) + " has " + std::to_string(k) +
                     " vertices (OFF faces may have 1 to 9)");
    }
    if (tokens.size() < static_cast<std::size_t>(k) + 1) {
      fail(path, at_line(line_no) + "face " + str(faces) + " lists fewer than " + std::to_string(k) +
                     " vertex indices");
    }
    for (std::int64_t m = 1; m <= k; ++m) {
      std::int64_t index = 0;
      if (!parse_int(tokens[m], index)) {
        fail(path, at_line(line_no) + "in face " + str(faces) + ", cannot read vertex index '" +
                       std::string(tokens[m]) + "'");
      }
      if (index < 0 || static_cast<std::uint64_t>(index) >= n_vertices) {
        fail(path, at_line(line_no) + "in face " + str(faces) + ", vertex index " + std::to_string(index) +
                       " does not exist (" + str(n_vertices) + " vertices)");
      }
    }
    return true;
  });
  if (vertices < n_vertices) {
    fail(path, "truncated OFF: file ends after " + str(vertices) + " of " + str(n_vertices) + " vertices");
  }
  if (faces < n_faces) {
    fail(path, "truncated OFF: file ends after " + str(faces) + " of " + str(n_faces) + " faces");
  }
}

// ---------------------------------------------------------------------------------------------------------
// PLY: assimp allocates the header's element counts up front, repeats the last face of a short ASCII file,
// reads past the end of a short binary file, and keeps out-of-range face indices.

struct PlyType {
  int size = 0;  // bytes in binary files
  bool is_signed = false;
  bool is_integer = false;
};

bool ply_type(std::string_view name, PlyType& type) {
  static constexpr std::array<std::pair<std::string_view, PlyType>, 16> kTypes{{
      {"char", {1, true, true}},
      {"int8", {1, true, true}},
      {"uchar", {1, false, true}},
      {"uint8", {1, false, true}},
      {"short", {2, true, true}},
      {"int16", {2, true, true}},
      {"ushort", {2, false, true}},
      {"uint16", {2, false, true}},
      {"int", {4, true, true}},
      {"int32", {4, true, true}},
      {"uint", {4, false, true}},
      {"uint32", {4, false, true}},
      {"float", {4, true, false}},
      {"float32", {4, true, false}},
      {"double", {8, true, false}},
      {"float64", {8, true, false}},
  }};
  for (const auto& [n, t] : kTypes) {
    if (n == name) {
      type = t;
      return true;
    }
  }
  return false;
}

struct PlyProperty {
  std::string name;
  bool is_list = false;
  PlyType count;  // list length type
  PlyType value;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { kAscii, kBinaryLittle, kBinaryBig };

std::string ply_position(const PlyElement& e, std::uint64_t i) {
  return "'" + e.name + "' element " + str(i + 1) + " of " + str(e.count);
}

// An integer list length stored in binary; negative lengths are errors.
bool read_ply_length(const unsigned char* p, const PlyType& type, bool big_endian, std::int64_t& length) {
  std::uint64_t raw = 0;
  for (int b = 0; b < type.size; ++b) {
    const int shift = 8 * (big_endian ? type.size - 1 - b : b);
    raw |= std::uint64_t{p[b]} << shift;
  }
  if (type.is_signed && type.size < 8 && (raw >> (8 * type.size - 1)) != 0) return false;
  length = static_cast<std::int64_t>(raw);
  return true;
}

void walk_binary_ply(const std::string& path, std::string_view data, std::size_t pos,
                     const std::vector<PlyElement>& elements, bool big_endian) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  for (const PlyElement& e : elements) {
    const bool has_list =
        std::any_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.is_list; });
    if (!has_list) {
      std::uint64_t fixed = 0;
      for (const PlyProperty& p : e.properties) fixed += p.value.size;
      if (fixed == 0) continue;
      // Counts were checked against the file size, so this product cannot overflow.
      if (fixed * e.count > data.size() - pos) {
        fail(path, "truncated PLY: file ends in " + ply_position(e, (data.size() - pos) / fixed));
      }
      pos += fixed * e.count;
      continue;
    }
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const PlyProperty& p : e.properties) {
        const std::uint64_t head = p.is_list ? p.count.size : p.value.size;
        if (head > data.size() - pos) fail(path, "truncated PLY: file ends in " + ply_position(e, i));
        if (!p.is_list) {
          pos += head;
          continue;
        }
        std::int64_t length = 0;
        if (!read_ply_length(bytes + pos, p.count, big_endian, length)) {
          fail(path, "negative list length in " + ply_position(e, i));
        }
        pos += head;
        if (static_cast<std::uint64_t>(length) * p.value.size > data.size() - pos) {
          fail(path, "truncated PLY: file ends in " + ply_position(e, i));
        }
        pos += static_cast<std::uint64_t>(length) * p.value.size;
      }
    }
  }
}

// One element per line, with exactly the values its properties call for.
void walk_ascii_ply(const std::string& path, std::string_view data, std::size_t pos, std::int64_t first_line,
                    const std::vector<PlyElement>& elements) {
  std::size_t e = 0;
  std::uint64_t i = 0;
  auto skip_empty = [&] {
    while (e < elements.size() && i == elements[e].count) {
      ++e;
      i = 0;
    }
  };
  skip_empty();
  for_each_line(data, pos, first_line, [&](std::int64_t line_no, std::string_view line, std::size_t) {
    if (e == elements.size()) return false;
    const auto tokens = split_tokens(line);
    if (tokens.empty()) return true;
    const PlyElement& el = elements[e];
    const auto where = [&] { return at_line(line_no) + ply_position(el, i) + ": "; };
    std::size_t t = 0;
    for (const PlyProperty& p : el.properties) {
      if (t == tokens.size()) fail(path, where() + "too few values");
      if (p.is_list) {
        std::int64_t length = 0;
        if (!parse_int(tokens[t], length) || length < 0) {
          fail(path, where() + "bad list length '" + std::string(tokens[t]) + "'");
        }
        if (static_cast<std::uint64_t>(length) > tokens.size() - t - 1) {
          fail(path, where() + "too few values");
        }
        for (std::int64_t k = 1; k <= length; ++k) {
          if (!is_number(tokens[t + k])) {
            fail(path, where() + "'" + std::string(tokens[t + k]) + "' is not a number");
          }
        }
        t += static_cast<std::size_t>(length) + 1;
      } else {
        if (!is_number(tokens[t])) fail(path, where() + "'" + std::string(tokens[t]) + "' is not a number");
        ++t;
      }
    }
    if (t != tokens.size()) fail(path, where() + "too many values");
    ++i;
    skip_empty();
    return true;
  });
  if (e < elements.size()) fail(path, "truncated PLY: file ends in " + ply_position(elements[e], i));
}

void check_ply(const std::string& path, std::string_view data) {
  std::vector<PlyElement> elements;
  PlyFormat format = PlyFormat::kAscii;
  bool have_format = false, ended = false;
  std::size_t pos = 0;
  std::int64_t line_no = 0;
  while (!ended && pos < data.size()) {
    ++line_no;
    std::size_t end = data.find('\n', pos);
    if (end == std::string_view::npos) end = data.size();
    const std::string_view text = data.substr(pos, end - pos);
    const auto tokens = split_tokens(text);
    pos = std::min(end + 1, data.size());
    const std::string where = "cannot parse: PLY header line " + str(line_no) + ": ";
    // assimp splits header words only at spaces, tabs and line ends: a vertical tab or form feed after
    // "end_header" moved its start of the data away from ours, and it read out of bounds (found by
    // fuzz_mesh_ply).
    const auto control = [](char c) {
      return (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r') || c == 0x7f;
    };
    if (std::any_of(text.begin(), text.end(), control)) fail(path, where + "control character");
    if (line_no == 1) {
      if (tokens.size() != 1 || (tokens[0] != "ply" && tokens[0] != "PLY")) {
        fail(path, "cannot parse: not a PLY file (no 'ply' line)");
      }
      continue;
    }
    if (tokens.empty()) continue;
    const std::string_view key = tokens[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "end_header") {
      if (tokens.size() != 1) {
        fail(path, where + "unexpected '" + std::string(tokens[1]) + "' after end_header");
      }
      ended = true;
    } else if (key == "format" && tokens.size() >= 2) {
      // assimp reads the first format line and we would check the last; it then throws on the mismatch
      // and leaks the mesh it has built (found by fuzz_mesh_ply).
      if (have_format) fail(path, where + "second format line");
      if (tokens[1] == "ascii") {
        format = PlyFormat::kAscii;
      } else if (tokens[1] == "binary_little_endian") {
        format = PlyFormat::kBinaryLittle;
      } else if (tokens[1] == "binary_big_endian") {
        format = PlyFormat::kBinaryBig;
      } else {
        fail(path, where + "unknown format '" + std::string(tokens[1]) + "'");
      }
      have_format = true;
    } else if (key == "element" && tokens.size() == 3) {
      PlyElement e;
      e.name = tokens[1];
      if (!parse_count(tokens[2], e.count)) {
        fail(path, where + "bad element count '" + std::string(tokens[2]) + "'");
      }
      elements.push_back(std::move(e));
    } else if (key == "property" && !elements.empty() && tokens.size() >= 3) {
      PlyProperty p;
      p.is_list = tokens[1] == "list";
      const bool ok = p.is_list ? tokens.size() == 5 && ply_type(tokens[2], p.count) && p.count.is_integer &&
                                      ply_type(tokens[3], p.value)
                                : tokens.size() == 3 && ply_type(tokens[1], p.value);
      if (!ok) fail(path, where + "unsupported property");
      p.name = std::string(tokens.back());
      for (const PlyProperty& q : elements.back().properties)
        if (q.name == p.name) fail(path, where + "property '" + p.name + "' appears twice");
      elements.back().properties.push_back(p);
    } else {
      fail(path, where + "unexpected '" + std::string(key) + "'");
    }
  }
  if (!ended) fail(path, "cannot parse: PLY header has no end_header line");
  if (!have_format) fail(path, "cannot parse: PLY header has no format line");
  // A surface needs vertex positions x, y, z and faces with a vertex_indices (or vertex_index) list. assimp
  // copes badly without them (an ASan allocator check fired inside it for a vertex element with 'X' instead
  // of 'x', found by fuzz_mesh_ply), so they are required here, by their standard lower-case names.
  const auto find_element = [&](const char* name) -> const PlyElement* {
    for (const PlyElement& e : elements)
      if (e.name == name) return &e;
    return nullptr;
  };
  const auto has_property = [](const PlyElement& e, std::string_view name, bool list) {
    return std::any_of(e.properties.begin(), e.properties.end(),
                       [&](const PlyProperty& p) { return p.name == name && p.is_list == list; });
  };
  const PlyElement* vertex = find_element("vertex");
  if (!vertex) fail(path, "cannot parse: PLY header has no 'vertex' element");
  for (const char* axis : {"x", "y", "z"})
    if (!has_property(*vertex, axis, false))
      fail(path, std::string("cannot parse: PLY 'vertex' element has no scalar property '") + axis + "'");
  const PlyElement* face = find_element("face");
  if (!face) fail(path, "cannot parse: PLY header has no 'face' element");
  if (!has_property(*face, "vertex_indices", true) && !has_property(*face, "vertex_index", true))
    fail(path, "cannot parse: PLY 'face' element has no 'vertex_indices' list");

  // Fail fast on impossible counts: every ASCII value takes at least 2 bytes (digit and separator), every
  // binary element at least its fixed-size part.
  const std::uint64_t room = data.size() - pos;
  std::uint64_t claimed = 0;
  for (const PlyElement& e : elements) {
    std::uint64_t min_size = 0;
    for (const PlyProperty& p : e.properties) {
      min_size += format == PlyFormat::kAscii ? 2 : (p.is_list ? p.count.size : p.value.size);
    }
    min_size = std::max<std::uint64_t>(min_size, 1);
    if (e.count > (room - claimed) / min_size) {
      fail(path, "PLY header claims " + str(e.count) + " '" + e.name + "' elements, more than the " +
                     str(room) + " bytes after it can hold");
    }
    claimed += e.count * min_size;
  }

  if (format == PlyFormat::kAscii) {
    check_control_characters(path, data.substr(pos), line_no + 1);
    walk_ascii_ply(path, data, pos, line_no + 1, elements);
  } else {
    walk_binary_ply(path, data, pos, elements, format == PlyFormat::kBinaryBig);
  }
}

// ---------------------------------------------------------------------------------------------------------
// Files.

enum class Format { kStl, kObj, kPly, kOff };

class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_;
};

Format format_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".stl") return Format::kStl;
  if (ext == ".obj") return Format::kObj;
  if (ext == ".ply") return Format::kPly;
  if (ext == ".off") return Format::kOff;
  if (ext.empty()) fail(path, "unsupported format (no file extension; expected .stl, .obj, .ply, .off)");
  fail(path, "unsupported format '" + ext + "' (expected .stl, .obj, .ply, .off)");
}

const char* hint_of(Format format) {
  switch (format) {
    case Format::kStl:
      return "stl";
    case Format::kObj:
      return "obj";
    case Format::kPly:
      return "ply";
    case Format::kOff:
      return "off";
  }
  return "";
}

// assimp's STL reader keeps sizes in 32 bits; real particle meshes are far smaller.
constexpr std::uint64_t kMaxFileSize = std::numeric_limits<std::uint32_t>::max();

// Opens `path`, checks that it is not a directory and that its extension names a supported `format`, and
// returns its bytes.
std::string read_file(const std::string& path, Format& format) {
  const FileDescriptor file(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (file.get() < 0) fail(path, "cannot open: " + errno_message(errno));
  struct stat st {};
  if (::fstat(file.get(), &st) != 0) fail(path, "cannot open: " + errno_message(errno));
  if (S_ISDIR(st.st_mode)) fail(path, "cannot open: " + errno_message(EISDIR));
  format = format_of(path);
  if (static_cast<std::uint64_t>(st.st_size) > kMaxFileSize) {
    fail(path, "file too large (" + str(st.st_size) + " bytes; at most " + str(kMaxFileSize) + ")");
  }
  std::string data;
  data.reserve(static_cast<std::size_t>(st.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(file.get(), buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(path, "cannot read: " + errno_message(errno));
    if (n == 0) break;
    data.append(buffer, static_cast<std::size_t>(n));
    if (data.size() > kMaxFileSize) fail(path, "file too large (more than " + str(kMaxFileSize) + " bytes)");
  }
  return data;
}

// assimp messages may span lines and name its in-memory file; make them one line naming the user's file.
std::string one_line(std::string message, const std::string& path, const char* hint) {
  const std::string magic = std::string(AI_MEMORYIO_MAGIC_FILENAME) + "." + hint;
  for (std::size_t at = message.find(magic); at != std::string::npos;
       at = message.find(magic, at + path.size())) {
    message.replace(at, magic.size(), path);
  }
  std::replace(message.begin(), message.end(), '\n', ' ');
  std::replace(message.begin(), message.end(), '\r', ' ');
  while (!message.empty() && message.back() == ' ') message.pop_back();
  return message.empty() ? "unknown error" : message;
}

// Faces as assimp built them, before triangulation (so face numbers follow the file for PLY).
void check_faces(const std::string& path, const aiScene& scene) {
  std::uint64_t face_no = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      ++face_no;
      if (face.mNumIndices == 0 || face.mIndices == nullptr) {
        fail(path, "cannot parse: face " + str(face_no) + " has no vertices");
      }
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices) {
          fail(path, "in face " + str(face_no) + ", vertex index " + str(face.mIndices[k]) +
                         " does not exist (" + str(mesh.mNumVertices) + " vertices)");
        }
      }
    }
  }
}

TriangleMesh merge_triangles(const std::string& path, const aiScene& scene) {
  TriangleMesh out;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    const std::size_t offset = out.vertices.size();
    if (offset + mesh.mNumVertices > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
      fail(path, "too many vertices (more than " + str(std::numeric_limits<std::int32_t>::max()) + ")");
    }
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      out.vertices.emplace_back(p.x, p.y, p.z);
    }
    // Points and lines (OBJ 'p'/'l', short OFF faces) are not part of the surface.
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      out.triangles.push_back({static_cast<std::int32_t>(offset + face.mIndices[0]),
                               static_cast<std::int32_t>(offset + face.mIndices[1]),
                               static_cast<std::int32_t>(offset + face.mIndices[2])});
    }
  }
  if (out.triangles.empty()) fail(path, "no triangles");
  return out;
}

void append_le32(std::string& out, std::uint32_t v) {
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<char>((v >> (8 * b)) & 0xFF));
}

void append_float(std::string& out, double v) {
  const auto f = static_cast<float>(v);
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  append_le32(out, bits);
}

// Checks and parses the bytes of a mesh file; `path` names it in errors.
TriangleMesh parse_mesh(const std::string& path, const std::string& data, Format format) {
  if (data.empty()) fail(path, "empty file");

  std::size_t length = data.size();
  switch (format) {
    case Format::kStl:
      if (is_ascii_stl(data)) return read_ascii_stl(path, data);
      length = check_binary_stl(path, data);
      break;
    case Format::kObj:
      check_obj(path, data);
      break;
    case Format::kPly:
      check_ply(path, data);
      break;
    case Format::kOff:
      check_off(path, data);
      break;
  }

  // No logger is created, so assimp's default null logger stays silent. Read without post-processing
  // first: check_faces() must see the faces before the triangulator trusts their indices.
  const char* hint = hint_of(format);
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFileFromMemory(data.data(), length, 0, hint);
    if (scene != nullptr) {
      check_faces(path, *scene);
      scene = importer.ApplyPostProcessing(aiProcess_Triangulate);
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail(path, "cannot parse: " + one_line(e.what(), path, hint));
  } catch (...) {
    fail(path, "cannot parse: unknown error");
  }
  if (scene == nullptr) fail(path, "cannot parse: " + one_line(importer.GetErrorString(), path, hint));
  return merge_triangles(path, *scene);
}

}  // namespace

TriangleMesh read_mesh(const std::string& path) {
  Format format = Format::kStl;
  const std::string data = read_file(path, format);
  return parse_mesh(path, data, format);
}

TriangleMesh read_mesh_from_memory(const std::string& bytes, const std::string& name) {
  const Format format = format_of(name);
  if (bytes.size() > kMaxFileSize) {
    fail(name, "file too large (" + str(bytes.size()) + " bytes; at most " + str(kMaxFileSize) + ")");
  }
  return parse_mesh(name, bytes, format);
}

void write_stl(const TriangleMesh& mesh, const std::string& path) {
  const auto n_vertices = mesh.vertices.size();
  if (mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max()) {
    fail(path, "cannot write: too many triangles for STL");
  }
  std::string out = "binary STL written by repose";
  out.resize(80, ' ');
  append_le32(out, static_cast<std::uint32_t>(mesh.triangles.size()));
  out.reserve(84 + 50 * mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    for (const std::int32_t i : tri) {
      if (i < 0 || static_cast<std::size_t>(i) >= n_vertices) {
        fail(path, "cannot write: in triangle " + str(t) + ", vertex index " + std::to_string(i) +
                       " does not exist (" + str(n_vertices) + " vertices)");
      }
    }
    const Vec3& a = mesh.vertices[tri[0]];
    const Vec3 normal = (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a).normalized();
    for (int k = 0; k < 3; ++k) append_float(out, std::isfinite(normal[k]) ? normal[k] : 0.0);
    for (const std::int32_t i : tri) {
      for (int k = 0; k < 3; ++k) append_float(out, mesh.vertices[i][k]);
    }
    out.append(2, '\0');  // attribute byte count
  }

  // Write a sibling temporary and rename it over `path`, so readers never see a partial file. O_EXCL with
  // a random suffix avoids clobbering a concurrent writer's temporary; mode 0666 lets the umask decide.
  std::random_device entropy;
  std::string tmp;
  int fd = -1;
  for (int attempt = 0; attempt < 16 && fd < 0; ++attempt) {
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, ".tmp-%08x", static_cast<unsigned>(entropy()));
    tmp = path + suffix;
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) fail(path, "cannot write: " + errno_message(errno));
  FileDescriptor file(fd);
  auto give_up = [&](const std::string& reason) {
    ::unlink(tmp.c_str());
    fail(path, "cannot write: " + reason);
  };
  for (std::size_t done = 0; done < out.size();) {
    const ssize_t n = ::write(file.get(), out.data() + done, out.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) give_up(errno_message(errno));
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(file.get()) != 0) give_up(errno_message(errno));
  if (::close(file.release()) != 0) give_up(errno_message(errno));
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) give_up(ec.message());
}

}  // namespace repose
