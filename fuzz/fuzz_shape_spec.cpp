// libFuzzer harness for the shape-spec parser (make_shape: "box:x=1,y=2,z=3", "ellipsoid:a=..,n=..", ...).
//
// Oracle: the spec is rejected with repose::Error, or it gives a mesh that validate_mesh() accepts, with
// finite vertices, and that is a solid by the harness's own checks (solid_checks.hpp): closed and
// consistently wound (each directed edge once, its reverse once), with a positive volume computed here. A
// built-in shape needs no repair: validate_mesh must weld, drop and flip nothing. Size parameters are capped
// in shapes.cpp, so no spec can allocate more than the fuzzer's cap (-malloc_limit_mb=1024); the harness
// skips icosphere frequencies above 40 only to stay within -timeout=10 (see docs/fuzzing.md).
#include <algorithm>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "repose/error.hpp"
#include "repose/geometry/mesh.hpp"
#include "repose/geometry/shapes.hpp"
#include "solid_checks.hpp"

namespace {

using repose_fuzz::require;

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
  repose::MeshReport report;
  try {
    report = repose::validate_mesh(mesh, spec);
  } catch (...) {
    __builtin_trap();
  }
  require(report.welded_vertices == 0 && report.degenerate_triangles == 0 && report.unused_vertices == 0 &&
          !report.flipped);
  for (const repose::Vec3& v : mesh.vertices) require(v.allFinite());
  require(repose_fuzz::closed_and_consistently_wound(mesh));
  const repose_fuzz::SolidSums sums = repose_fuzz::solid_sums(mesh);
  require(std::isfinite(sums.volume) && sums.volume > repose_fuzz::volume_round_off(mesh, sums));
  return 0;
}
