// PLY bodies, ASCII and binary (either byte order). The vertex element's x, y, z (any numeric type) become
// the vertices, in order; the face element's index list, fan-triangulated, the triangles. Every other
// element and property is read past. Faces of 1 or 2 vertices are no part of the surface; an empty face
// is an error, as is an index outside the vertex element's count.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

#include "ply.hpp"
#include "readers.hpp"
#include "text_scan.hpp"

namespace repose::io {
namespace {

// Collects one face's corners and checks them against the vertex count the header gave. Faces are named
// by number, and by line in ASCII files. The first bad face is reported only after the whole body has been
// read (check()), so that a malformed or truncated file is reported as such, whatever its faces hold.
class FaceBuilder {
 public:
  FaceBuilder(const std::string& path, std::uint64_t n_vertices) : path_(path), n_vertices_(n_vertices) {}

  void start(std::int64_t line, std::uint64_t i) {
    line_ = line;
    face_ = i + 1;
    corners_.clear();
  }
  void add(std::int64_t index) {
    if (index < 0 || static_cast<std::uint64_t>(index) >= n_vertices_) {
      bad("in face " + str(face_) + ", vertex index " + std::to_string(index) + " does not exist (" +
          str(n_vertices_) + " vertices)");
    }
    corners_.push_back(static_cast<std::int32_t>(index));
  }
  // A float-typed list: only whole numbers are indices.
  void add(double value) {
    if (!(std::abs(value) < 0x1p62) || value != std::floor(value)) {
      char text[32];
      std::snprintf(text, sizeof text, "%.17g", value);
      bad("in face " + str(face_) + ", vertex index " + text + " is not an integer");
      return;
    }
    add(static_cast<std::int64_t>(value));
  }
  void finish(Polygons& out) {
    if (corners_.empty()) bad("face " + str(face_) + " has no vertices");
    if (error_.empty()) out.add(corners_.data(), corners_.size());
  }
  void check() const {
    if (!error_.empty()) fail(path_, error_);
  }

 private:
  void bad(const std::string& what) {
    if (error_.empty()) error_ = (line_ > 0 ? at_line(line_) : std::string()) + what;
  }

  const std::string& path_;
  std::uint64_t n_vertices_;
  std::int64_t line_ = 0;  // 0 in binary files
  std::uint64_t face_ = 0;
  std::vector<std::int32_t> corners_;
  std::string error_;  // the first bad face
};

// ---------------------------------------------------------------------------------------------------------
// ASCII: one element per line, with exactly the values its properties call for.

void read_ascii_body(const std::string& path, std::string_view data, const PlyHeader& h, TriangleMesh& mesh,
                     Polygons& polygons) {
  check_control_characters(path, data.substr(h.body), h.body_line);
  const auto& elements = h.elements;
  FaceBuilder face(path, elements[h.vertex].count);
  std::vector<std::string_view> tokens;
  std::size_t e = 0;
  std::uint64_t i = 0;
  auto skip_empty = [&] {
    while (e < elements.size() && i == elements[e].count) {
      ++e;
      i = 0;
    }
  };
  skip_empty();
  for_each_line(data, h.body, h.body_line, [&](std::int64_t line_no, std::string_view line, std::size_t) {
    if (e == elements.size()) return false;
    split_tokens(line, tokens);
    if (tokens.empty()) return true;
    const PlyElement& el = elements[e];
    const bool is_vertex = e == h.vertex, is_face = e == h.face;
    const auto where = [&] { return at_line(line_no) + ply_position(el, i) + ": "; };
    const auto number = [&](std::string_view token) {
      double value = 0;
      if (!parse_double(token, value)) fail(path, where() + "'" + std::string(token) + "' is not a number");
      return value;
    };
    double xyz[3] = {0, 0, 0};
    if (is_face) face.start(line_no, i);
    std::size_t t = 0;
    for (std::size_t k = 0; k < el.properties.size(); ++k) {
      const PlyProperty& p = el.properties[k];
      if (t == tokens.size()) fail(path, where() + "too few values");
      if (!p.is_list) {
        const double value = number(tokens[t++]);
        if (is_vertex)
          for (int a = 0; a < 3; ++a)
            if (k == h.xyz[a]) xyz[a] = value;
        continue;
      }
      std::int64_t length = 0;
      if (!parse_int(tokens[t], length) || length < 0) {
        fail(path, where() + "bad list length '" + std::string(tokens[t]) + "'");
      }
      if (static_cast<std::uint64_t>(length) > tokens.size() - t - 1) fail(path, where() + "too few values");
      const bool indices = is_face && k == h.indices;
      for (std::int64_t m = 1; m <= length; ++m) {
        const std::string_view token = tokens[t + static_cast<std::size_t>(m)];
        std::int64_t index = 0;
        if (indices && parse_int(token, index)) {
          face.add(index);
        } else {
          const double value = number(token);
          if (indices) face.add(value);
        }
      }
      t += static_cast<std::size_t>(length) + 1;
    }
    if (t != tokens.size()) fail(path, where() + "too many values");
    if (is_vertex) mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
    if (is_face) face.finish(polygons);
    ++i;
    skip_empty();
    return true;
  });
  if (e < elements.size()) fail(path, "truncated PLY: file ends in " + ply_position(elements[e], i));
  face.check();
}

// ---------------------------------------------------------------------------------------------------------
// Binary: values of the declared sizes, back to back.

std::uint64_t read_raw(const unsigned char* p, int size, bool big_endian) {
  std::uint64_t raw = 0;
  for (int b = 0; b < size; ++b) raw |= std::uint64_t{p[b]} << (8 * (big_endian ? size - 1 - b : b));
  return raw;
}

// An integer value, sign-extended when its type is signed.
std::int64_t read_integer(const unsigned char* p, const PlyType& type, bool big_endian) {
  const std::uint64_t raw = read_raw(p, type.size, big_endian);
  const int unused = 64 - 8 * type.size;
  if (!type.is_signed || unused == 0) return static_cast<std::int64_t>(raw);
  return static_cast<std::int64_t>(raw << unused) >> unused;
}

double read_real(const unsigned char* p, const PlyType& type, bool big_endian) {
  if (type.is_integer) return static_cast<double>(read_integer(p, type, big_endian));
  const std::uint64_t raw = read_raw(p, type.size, big_endian);
  if (type.size == 4) return std::bit_cast<float>(static_cast<std::uint32_t>(raw));
  return std::bit_cast<double>(raw);
}

void read_binary_body(const std::string& path, std::string_view data, const PlyHeader& h, TriangleMesh& mesh,
                      Polygons& polygons) {
  const bool big = h.format == PlyFormat::kBinaryBig;
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  FaceBuilder face(path, h.elements[h.vertex].count);
  std::size_t pos = h.body;
  for (std::size_t e = 0; e < h.elements.size(); ++e) {
    const PlyElement& el = h.elements[e];
    const bool is_vertex = e == h.vertex, is_face = e == h.face;
    const auto truncated = [&](std::uint64_t i) {
      fail(path, "truncated PLY: file ends in " + ply_position(el, i));
    };
    const bool has_list = std::any_of(el.properties.begin(), el.properties.end(),
                                      [](const PlyProperty& p) { return p.is_list; });
    if (!has_list) {
      // Fixed-size records: one bounds check for the whole element.
      std::uint64_t fixed = 0;
      std::size_t offset[3] = {0, 0, 0};
      for (std::size_t k = 0; k < el.properties.size(); ++k) {
        for (int a = 0; a < 3; ++a)
          if (is_vertex && k == h.xyz[a]) offset[a] = fixed;
        fixed += static_cast<std::uint64_t>(el.properties[k].value.size);
      }
      if (fixed == 0) continue;
      // Counts were checked against the file size, so this product cannot overflow.
      if (fixed * el.count > data.size() - pos) truncated((data.size() - pos) / fixed);
      for (std::uint64_t i = 0; is_vertex && i < el.count; ++i) {
        const unsigned char* record = bytes + pos + i * fixed;
        double xyz[3];
        for (int a = 0; a < 3; ++a)
          xyz[a] = read_real(record + offset[a], el.properties[h.xyz[a]].value, big);
        mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
      }
      pos += fixed * el.count;
      continue;
    }
    for (std::uint64_t i = 0; i < el.count; ++i) {
      double xyz[3] = {0, 0, 0};
      if (is_face) face.start(0, i);
      for (std::size_t k = 0; k < el.properties.size(); ++k) {
        const PlyProperty& p = el.properties[k];
        const std::uint64_t head = static_cast<std::uint64_t>(p.is_list ? p.count.size : p.value.size);
        if (head > data.size() - pos) truncated(i);
        if (!p.is_list) {
          if (is_vertex)
            for (int a = 0; a < 3; ++a)
              if (k == h.xyz[a]) xyz[a] = read_real(bytes + pos, p.value, big);
          pos += head;
          continue;
        }
        const std::int64_t length = read_integer(bytes + pos, p.count, big);
        if (length < 0) fail(path, "negative list length in " + ply_position(el, i));
        pos += head;
        // length < 2^32 and values take at most 8 bytes: no overflow.
        const std::uint64_t size =
            static_cast<std::uint64_t>(length) * static_cast<std::uint64_t>(p.value.size);
        if (size > data.size() - pos) truncated(i);
        if (is_face && k == h.indices) {
          for (std::int64_t m = 0; m < length; ++m) {
            const unsigned char* v = bytes + pos + static_cast<std::size_t>(m) * p.value.size;
            if (p.value.is_integer) {
              face.add(read_integer(v, p.value, big));
            } else {
              face.add(read_real(v, p.value, big));
            }
          }
        }
        pos += size;
      }
      if (is_vertex) mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
      if (is_face) face.finish(polygons);
    }
  }
  face.check();
}

}  // namespace

TriangleMesh read_ply(const std::string& path, std::string_view data) {
  const PlyHeader h = read_ply_header(path, data);
  const std::uint64_t n_vertices = h.elements[h.vertex].count;
  check_vertex_count(path, n_vertices);
  TriangleMesh mesh;
  // Both counts were checked against the bytes that must hold them.
  mesh.vertices.reserve(n_vertices);
  if (h.face != kNone) mesh.triangles.reserve(h.elements[h.face].count);
  Polygons polygons(mesh.triangles);
  if (h.format == PlyFormat::kAscii) {
    read_ascii_body(path, data, h, mesh, polygons);
  } else {
    read_binary_body(path, data, h, mesh, polygons);
  }
  polygons.finish(mesh.vertices);
  return mesh;
}

}  // namespace repose::io
