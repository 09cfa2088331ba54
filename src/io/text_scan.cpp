#include "text_scan.hpp"

#include <charconv>
#include <cstdlib>
#include <limits>
#include <system_error>
#include <type_traits>

#include "repose/error.hpp"

namespace repose::io {

void fail(const std::string& path, const std::string& what) { throw Error(path + ": " + what); }

std::string str(std::uint64_t n) { return std::to_string(n); }

std::string at_line(std::int64_t number) { return "line " + std::to_string(number) + ": "; }

std::string shown(std::string_view token) {
  if (token.empty()) return "end of file";
  std::string out = "'";
  out.append(token.substr(0, 40));
  if (token.size() > 40) out += "...";
  out += '\'';
  return out;
}

void split_tokens(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t pos = 0;
  for (std::string_view t = next_token(line, pos); !t.empty(); t = next_token(line, pos)) out.push_back(t);
}

void check_control_characters(const std::string& path, std::string_view text, std::int64_t first_line) {
  const auto control = [](char c) {
    return (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r' && c != '\n') || c == 0x7f;
  };
  const auto report = [&](std::string_view::const_iterator at) {
    const auto line = first_line + std::count(text.begin(), at, '\n');
    fail(path, at_line(line) + "control character (byte " + str(static_cast<unsigned char>(*at)) + ")");
  };
  const auto at = std::adjacent_find(
      text.begin(), text.end(), [&](char c, char next) { return control(c) || (c == '\r' && next != '\n'); });
  if (at != text.end()) report(at);
  // adjacent_find never tests the last character alone.
  if (!text.empty() && (control(text.back()) || text.back() == '\r')) report(text.end() - 1);
}

bool parse_int(std::string_view s, std::int64_t& out) {
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && ptr == s.data() + s.size() && !s.empty();
}

bool parse_count(std::string_view s, std::uint64_t& out) {
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  if (ptr != s.data() + s.size() || s.empty()) return false;
  if (ec == std::errc::result_out_of_range) out = std::numeric_limits<std::uint64_t>::max();
  return ec == std::errc() || ec == std::errc::result_out_of_range;
}

namespace {

// std::from_chars leaves the value alone when it is out of range; strtod/strtof then give ±inf, or the
// denormal or zero an underflow rounds to. Such tokens are rare, so the copy they need costs nothing.
template <typename T>
bool parse_real(std::string_view s, T& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);  // from_chars takes '-' only
  if (s.empty()) return false;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  if (ptr != s.data() + s.size()) return false;
  if (ec == std::errc::result_out_of_range) {
    const std::string copy(s);
    if constexpr (std::is_same_v<T, float>) {
      out = std::strtof(copy.c_str(), nullptr);
    } else {
      out = std::strtod(copy.c_str(), nullptr);
    }
    return true;
  }
  return ec == std::errc();
}

}  // namespace

bool parse_double(std::string_view s, double& out) { return parse_real(s, out); }

bool parse_float(std::string_view s, float& out) { return parse_real(s, out); }

}  // namespace repose::io
