#include "repose/model/orientation.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <vector>

#include "repose/error.hpp"

namespace repose {

namespace {

std::vector<double> parse_numbers(const std::string& spec, const std::string& text, std::size_t expected) {
  std::vector<double> values;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    double v = 0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
    if (item.empty() || ec != std::errc() || end != item.data() + item.size() || !std::isfinite(v))
      throw Error("orientation '" + spec + "': '" + item + "' is not a finite number");
    values.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (values.size() != expected)
    throw Error("orientation '" + spec + "': expected " + std::to_string(expected) + " numbers, got " +
                std::to_string(values.size()));
  return values;
}

}  // namespace

Quat parse_orientation(const std::string& spec) {
  if (spec == "identity") return Quat::Identity();
  const std::size_t colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::string args = colon == std::string::npos ? "" : spec.substr(colon + 1);
  if (kind == "quat") {
    const auto v = parse_numbers(spec, args, 4);
    Quat q(v[0], v[1], v[2], v[3]);
    const double n = q.norm();
    if (!(n > 1e-12) || !std::isfinite(n)) throw Error("orientation '" + spec + "': zero quaternion");
    return q.normalized();
  }
  if (kind == "axis-angle") {
    const auto v = parse_numbers(spec, args, 4);
    const Vec3 axis(v[0], v[1], v[2]);
    // Scaled by its largest component before normalising: the squares of a tiny axis (1e-160) underflow,
    // which would tilt it or make it "zero" (found by fuzz_orientation_spec); any non-zero axis is accepted.
    const double largest = axis.cwiseAbs().maxCoeff();
    if (!(largest > 0)) throw Error("orientation '" + spec + "': zero axis");
    return Quat(Eigen::AngleAxisd(v[3], (axis / largest).normalized())).normalized();
  }
  throw Error("orientation '" + spec + "': unknown kind '" + kind + "' (expected quat:w,x,y,z, " +
              "axis-angle:x,y,z,radians or identity)");
}

std::string format_orientation(const Quat& q) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "quat:%.17g,%.17g,%.17g,%.17g", q.w(), q.x(), q.y(), q.z());
  return buf;
}

}  // namespace repose
