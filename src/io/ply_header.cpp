// The PLY header: "ply", "format ascii|binary_little_endian|binary_big_endian 1.0", then elements with
// their properties ("element NAME COUNT", "property TYPE NAME", "property list COUNT_TYPE TYPE NAME"),
// comments and obj_info lines, and "end_header" alone on its line.
#include <algorithm>
#include <array>
#include <utility>

#include "ply.hpp"
#include "text_scan.hpp"

namespace repose::io {
namespace {

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

std::size_t find_property(const PlyElement& e, std::string_view name, bool list) {
  for (std::size_t k = 0; k < e.properties.size(); ++k)
    if (e.properties[k].name == name && e.properties[k].is_list == list) return k;
  return kNone;
}

// Fail fast on impossible counts: every ASCII value takes at least 2 bytes (digit and separator), every
// binary element at least its fixed-size part.
void check_counts(const std::string& path, const PlyHeader& h, std::uint64_t room) {
  std::uint64_t claimed = 0;
  for (const PlyElement& e : h.elements) {
    std::uint64_t min_size = 0;
    for (const PlyProperty& p : e.properties) {
      min_size += h.format == PlyFormat::kAscii ? 2 : (p.is_list ? p.count.size : p.value.size);
    }
    min_size = std::max<std::uint64_t>(min_size, 1);
    if (e.count > (room - claimed) / min_size) {
      fail(path, "PLY header claims " + str(e.count) + " '" + e.name + "' elements, more than the " +
                     str(room) + " bytes after it can hold");
    }
    claimed += e.count * min_size;
  }
}

}  // namespace

std::string ply_position(const PlyElement& e, std::uint64_t i) {
  return "'" + e.name + "' element " + str(i + 1) + " of " + str(e.count);
}

PlyHeader read_ply_header(const std::string& path, std::string_view data) {
  PlyHeader h;
  bool have_format = false, ended = false;
  std::size_t pos = 0;
  std::int64_t line_no = 0;
  std::vector<std::string_view> tokens;
  while (!ended && pos < data.size()) {
    ++line_no;
    const std::size_t end = std::min(data.find('\n', pos), data.size());
    const std::string_view text = data.substr(pos, end - pos);
    split_tokens(text, tokens);
    pos = std::min(end + 1, data.size());
    const std::string where = "cannot parse: PLY header line " + str(line_no) + ": ";
    // A vertical tab or form feed splits words for some readers and not for others, so they would
    // disagree on where a binary body starts (found by fuzz_mesh_ply, against the reader used then).
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
      if (have_format) fail(path, where + "second format line");
      if (tokens[1] == "ascii") {
        h.format = PlyFormat::kAscii;
      } else if (tokens[1] == "binary_little_endian") {
        h.format = PlyFormat::kBinaryLittle;
      } else if (tokens[1] == "binary_big_endian") {
        h.format = PlyFormat::kBinaryBig;
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
      for (const PlyElement& other : h.elements)
        if ((e.name == "vertex" || e.name == "face") && other.name == e.name)
          fail(path, where + "second '" + e.name + "' element");
      h.elements.push_back(std::move(e));
    } else if (key == "property" && !h.elements.empty() && tokens.size() >= 3) {
      PlyProperty p;
      p.is_list = tokens[1] == "list";
      const bool ok = p.is_list ? tokens.size() == 5 && ply_type(tokens[2], p.count) && p.count.is_integer &&
                                      ply_type(tokens[3], p.value)
                                : tokens.size() == 3 && ply_type(tokens[1], p.value);
      if (!ok) fail(path, where + "unsupported property");
      p.name = std::string(tokens.back());
      for (const PlyProperty& q : h.elements.back().properties)
        if (q.name == p.name) fail(path, where + "property '" + p.name + "' appears twice");
      h.elements.back().properties.push_back(std::move(p));
    } else {
      fail(path, where + "unexpected '" + std::string(key) + "'");
    }
  }
  if (!ended) fail(path, "cannot parse: PLY header has no end_header line");
  if (!have_format) fail(path, "cannot parse: PLY header has no format line");
  h.body = pos;
  h.body_line = line_no + 1;

  // Positions x, y, z and, when there are faces, their index list, by the standard lower-case names.
  for (std::size_t k = 0; k < h.elements.size(); ++k) {
    if (h.elements[k].name == "vertex") h.vertex = k;
    if (h.elements[k].name == "face") h.face = k;
  }
  if (h.vertex == kNone) fail(path, "cannot parse: PLY header has no 'vertex' element");
  const char* axes[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    h.xyz[k] = find_property(h.elements[h.vertex], axes[k], false);
    if (h.xyz[k] == kNone)
      fail(path, std::string("cannot parse: PLY 'vertex' element has no scalar property '") + axes[k] + "'");
  }
  if (h.face != kNone) {
    const PlyElement& face = h.elements[h.face];
    h.indices = find_property(face, "vertex_indices", true);
    if (h.indices == kNone) h.indices = find_property(face, "vertex_index", true);
    if (h.indices == kNone) fail(path, "cannot parse: PLY 'face' element has no 'vertex_indices' list");
  }
  check_counts(path, h, data.size() - pos);
  return h;
}

}  // namespace repose::io
