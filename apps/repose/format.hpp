// Small formatting and option-checking helpers shared by the subcommands.
#pragma once

#include <cmath>
#include <exception>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "repose/error.hpp"
#include "repose/geometry/types.hpp"

namespace repose::cli {

/// A number with 10 significant digits, for human-readable output.
inline std::string num(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

/// "[x, y, z]" with 10 significant digits.
template <class V>
std::string vec(const V& v) {
  std::string s = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) s += (i ? ", " : "") + num(v[i]);
  return s + "]";
}

inline nlohmann::json to_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

inline nlohmann::json to_json(const Mat3& m) {
  return {to_json(Vec3(m.row(0))), to_json(Vec3(m.row(1))), to_json(Vec3(m.row(2)))};
}

/// Throws repose::Error unless `value` is finite and > 0.
inline void check_positive(const std::string& option, double value) {
  if (!std::isfinite(value) || value <= 0)
    throw Error("option " + option + " must be a finite positive number, got " + num(value));
}

/// "X,Y,Z" as a vector of three finite numbers; throws repose::Error naming `option` otherwise.
inline Vec3 parse_vector(const std::string& option, const std::string& text) {
  Vec3 v;
  std::istringstream in(text);
  for (int i = 0; i < 3; ++i) {
    std::string part;
    if (!std::getline(in, part, i < 2 ? ',' : '\n') || part.empty())
      throw Error("option " + option + " takes X,Y,Z (three numbers), got '" + text + "'");
    std::size_t used = 0;
    try {
      v[i] = std::stod(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != part.size() || !std::isfinite(v[i]))
      throw Error("option " + option + " takes X,Y,Z (three finite numbers), got '" + text + "'");
  }
  return v;
}

/// Prints the one-line message of a failed command on stderr, flushed, and returns its exit code: 2 for
/// bad input (repose::Error), 1 for an internal error.
inline int report_error(const std::exception_ptr& error) {
  int code = 1;
  try {
    std::rethrow_exception(error);
  } catch (const Error& e) {
    std::cerr << "repose: error: " << e.what() << "\n";
    code = 2;
  } catch (const std::exception& e) {
    std::cerr << "repose: internal error: " << e.what() << "\n";
  } catch (...) {
    std::cerr << "repose: internal error: unknown exception\n";
  }
  std::cerr.flush();
  return code;
}

}  // namespace repose::cli
