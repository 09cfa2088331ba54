// libFuzzer harness for the orientation-spec parser (parse_orientation: "quat:w,x,y,z",
// "axis-angle:x,y,z,radians", "identity").
//
// Oracle: the spec is rejected with repose::Error, or it gives a finite unit quaternion, which
// format_orientation() writes in a form parse_orientation() reads back.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "repose/error.hpp"
#include "repose/model/orientation.hpp"

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string spec(reinterpret_cast<const char*>(data), size);
  repose::Quat q;
  try {
    q = repose::parse_orientation(spec);
  } catch (const repose::Error&) {
    return 0;
  } catch (...) {
    __builtin_trap();
  }
  require(q.coeffs().allFinite());
  require(std::abs(q.norm() - 1.0) < 1e-12);
  try {
    const repose::Quat back = repose::parse_orientation(repose::format_orientation(q));
    require(back.coeffs().allFinite() && std::abs(back.norm() - 1.0) < 1e-12);
  } catch (...) {
    __builtin_trap();
  }
  return 0;
}
