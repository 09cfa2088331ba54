// libFuzzer harness for the orientation-spec parser (parse_orientation: "quat:w,x,y,z",
// "axis-angle:x,y,z,radians", "identity").
//
// Oracle: the spec is rejected with repose::Error, or it gives a finite unit quaternion that
// - is the rotation the spec names, computed here independently in long double: for "quat:" the four numbers
//   divided by their norm; for "axis-angle:" (cos θ/2, sin θ/2 · axis/|axis|); for "identity" (1, 0, 0, 0) —
//   equal up to the sign of the whole quaternion (q and −q are the same rotation), within kValueTolerance;
// - survives the round trip: parse_orientation(format_orientation(q)) is the same quaternion (same sign),
//   within kRoundTripTolerance.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "repose/error.hpp"
#include "repose/model/orientation.hpp"

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

// format_orientation prints 17 significant digits, which identify a double exactly (IEEE 754 §5.12.2), and
// the parser reads them with std::from_chars, correctly rounded: the parser sees q's own four doubles and
// only renormalises them. q's norm is 1 within 2 ulp, so each component moves by at most ~3 ulp of 1
// (3.3e-16). 1e-15 (4.5 ulp) is that bound with a little room, and far below any change of rotation a
// formatting bug (a lost digit: 1e-17 relative at %.16g, 1e-7 at %g) would make.
constexpr double kRoundTripTolerance = 1e-15;

// Against the independent value: the library computes a norm (sum of squares, square root), a division,
// and for axis-angle a sine and cosine, an axis normalisation and a final renormalisation, each correctly
// rounded or within 1 ulp: at most ~8 ulp of 1 (1.8e-15) in all. 4e-15 (~18 ulp) leaves a factor 2.
constexpr double kValueTolerance = 4e-15;

struct Q {
  long double w, x, y, z;
};

double distance_up_to_sign(const repose::Quat& q, const Q& e) {
  const auto dist = [&](long double s) {
    return static_cast<double>(std::fmax(std::fmax(std::fabs(q.w() - s * e.w), std::fabs(q.x() - s * e.x)),
                                         std::fmax(std::fabs(q.y() - s * e.y), std::fabs(q.z() - s * e.z))));
  };
  return std::fmin(dist(1), dist(-1));
}

// The comma-separated numbers after the first ':' (the parser accepted them all, with std::from_chars; here
// std::strtod reads the same decimal text to the same double).
std::vector<long double> numbers(const std::string& spec) {
  std::vector<long double> v;
  std::size_t start = spec.find(':') + 1;
  while (true) {
    const std::size_t comma = spec.find(',', start);
    const std::string item =
        spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    v.push_back(std::strtod(item.c_str(), nullptr));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return v;
}

// The rotation the spec names, in long double (64-bit mantissa: 2^11 times finer than the library's double).
Q expected(const std::string& spec) {
  if (spec == "identity") return {1, 0, 0, 0};
  const std::vector<long double> v = numbers(spec);
  require(v.size() == 4);
  if (spec.rfind("quat:", 0) == 0) {
    const long double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
    return {v[0] / n, v[1] / n, v[2] / n, v[3] / n};
  }
  require(spec.rfind("axis-angle:", 0) == 0);
  const long double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  const long double half = v[3] / 2, s = std::sin(half) / n;
  return {std::cos(half), s * v[0], s * v[1], s * v[2]};
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
  require(distance_up_to_sign(q, expected(spec)) <= kValueTolerance);
  try {
    const repose::Quat back = repose::parse_orientation(repose::format_orientation(q));
    require(back.coeffs().allFinite());
    require((back.coeffs() - q.coeffs()).cwiseAbs().maxCoeff() <= kRoundTripTolerance);
  } catch (...) {
    __builtin_trap();
  }
  return 0;
}
