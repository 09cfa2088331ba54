// libFuzzer harness for the shape-spec parser (make_shape: "box:x=1,y=2,z=3", "ellipsoid:a=..,n=..", ...).
//
// Oracle: the spec is rejected with repose::Error, or it gives a mesh that validate_mesh() accepts, with
// finite vertices and triangle indices in range. Size parameters are capped in shapes.cpp, so no spec can
// allocate more than the fuzzer's cap (-malloc_limit_mb=1024); the harness skips icosphere frequencies
// above 40 only to stay within -timeout=10 (see docs/fuzzing.md).
#include <algorithm>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "repose/error.hpp"
#include "repose/geometry/mesh.hpp"
#include "repose/geometry/shapes.hpp"

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

// The harness's own cap on the icosphere frequency n (the library allows up to 200): a 200-frequency
// ellipsoid has 800k triangles and takes over a minute to build and validate under ASan, far past
// -timeout=10, although its size is bounded. Cylinders (n <= 4096) are fast enough to keep.
constexpr std::uint64_t kMaxFrequency = 40;

bool too_slow(std::string_view spec) {
  const auto colon = spec.find(':');
  const std::string_view name = trim(spec.substr(0, colon));
  if (colon == std::string_view::npos || (name != "ellipsoid" && name != "irregular")) return false;
  for (std::size_t start = colon + 1; start <= spec.size();) {
    const std::size_t comma = std::min(spec.find(',', start), spec.size());
    const std::string_view item = spec.substr(start, comma - start);
    const std::size_t eq = item.find('=');
    if (eq != std::string_view::npos && trim(item.substr(0, eq)) == "n") {
      const std::string_view value = trim(item.substr(eq + 1));
      std::uint64_t n = 0;
      const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
      if (ec == std::errc() && ptr == value.data() + value.size() && n > kMaxFrequency) return true;
    }
    start = comma + 1;
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string spec(reinterpret_cast<const char*>(data), size);
  if (too_slow(spec)) return 0;
  repose::TriangleMesh mesh;
  try {
    mesh = repose::make_shape(spec);
  } catch (const repose::Error&) {
    return 0;
  } catch (...) {
    __builtin_trap();
  }
  // A spec that parses must give a valid solid: a repose::Error from here on is a bug too.
  try {
    repose::validate_mesh(mesh, spec);
  } catch (...) {
    __builtin_trap();
  }
  const auto n = static_cast<std::int64_t>(mesh.vertices.size());
  require(!mesh.triangles.empty());
  for (const repose::Vec3& v : mesh.vertices) require(v.allFinite());
  for (const repose::Triangle& t : mesh.triangles) {
    for (const std::int32_t i : t) require(i >= 0 && i < n);
  }
  return 0;
}
