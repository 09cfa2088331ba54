// libFuzzer harness for the scenario-file reader (parse_scenario: JSON text).
//
// Oracle: the text is rejected with repose::Error, or it gives a scenario with a finite positive density, a
// finite unit orientation quaternion and parameters that pass validate(). The particle is not loaded (the
// shape-spec and mesh harnesses cover that).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "repose/error.hpp"
#include "repose/model/params.hpp"
#include "repose/model/scenario.hpp"

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  repose::Scenario s;
  try {
    // A fixed origin: relative mesh paths resolve against its directory, and nothing is read from disk.
    s = repose::parse_scenario(text, "fuzz/scenario.json");
  } catch (const repose::Error&) {
    return 0;
  } catch (...) {
    __builtin_trap();
  }
  require(std::isfinite(s.density) && s.density > 0);
  require(s.orientation.coeffs().allFinite() && std::abs(s.orientation.norm() - 1.0) < 1e-12);
  require(!s.particle.empty());
  try {
    repose::validate(s.params);
  } catch (...) {
    __builtin_trap();
  }
  return 0;
}
