// The PLY header, as the PLY body reader needs it (read_ply.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace repose::io {

struct PlyType {
  int size = 0;  // bytes in binary files
  bool is_signed = false;
  bool is_integer = false;
};

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

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  std::size_t body = 0;            // offset of the first byte after the end_header line
  std::int64_t body_line = 0;      // number of the body's first line (ASCII)
  std::size_t vertex = kNone;      // index of the 'vertex' element
  std::size_t xyz[3] = {0, 0, 0};  // indices of its x, y, z properties
  std::size_t face = kNone;        // index of the 'face' element, if any
  std::size_t indices = kNone;     // index of its vertex_indices (or vertex_index) list
};

/// Reads and checks the header: a vertex element with scalar x, y, z; a face element, if any, with a
/// vertex_indices or vertex_index list; element counts that the bytes after the header can hold.
PlyHeader read_ply_header(const std::string& path, std::string_view data);

/// "'face' element 3 of 12", for messages (i counts from 0).
std::string ply_position(const PlyElement& e, std::uint64_t i);

}  // namespace repose::io
