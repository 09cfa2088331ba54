// What every mesh reader shares: errors that name the file, line walking, whitespace tokens and numbers.
// Nothing here allocates per token: tokens are views into the file's bytes.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace repose::io {

/// Throws repose::Error("PATH: WHAT").
[[noreturn]] void fail(const std::string& path, const std::string& what);

std::string str(std::uint64_t n);

/// "line N: ", the prefix of a message about one line.
std::string at_line(std::int64_t number);

/// A token quoted for a message (at most 40 characters), or "end of file" for an empty one.
std::string shown(std::string_view token);

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/// The whitespace-separated token starting at or after `pos` (empty at the end); advances `pos` past it.
inline std::string_view next_token(std::string_view s, std::size_t& pos) {
  while (pos < s.size() && (is_space(s[pos]) || s[pos] == '\n')) ++pos;
  const std::size_t start = pos;
  while (pos < s.size() && !is_space(s[pos]) && s[pos] != '\n') ++pos;
  return s.substr(start, pos - start);
}

/// Replaces `out` with the tokens of `line`; reusing one vector keeps its capacity from line to line.
void split_tokens(std::string_view line, std::vector<std::string_view>& out);

inline std::string_view strip_comment(std::string_view line) { return line.substr(0, line.find('#')); }

/// Calls f(number, line, next) for the lines from offset `start` on, numbering them from `first_number`
/// ('\r' of CRLF removed; `next` is the offset of the following line). f returns false to stop.
template <typename F>
void for_each_line(std::string_view text, std::size_t start, std::int64_t first_number, F&& f) {
  std::int64_t number = first_number;
  for (std::size_t pos = start; pos < text.size(); ++number) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view line = text.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = std::min(end + 1, text.size());
    if (!f(number, line, pos)) return;
  }
}

/// Text formats allow tab, and CR only as part of CRLF, besides the line feed: a file with other control
/// characters (a NUL, a lone CR that some readers take for a line end) means different things to different
/// programs, so it is rejected ("line N: control character (byte B)"). `first_line` numbers text's first
/// line.
void check_control_characters(const std::string& path, std::string_view text, std::int64_t first_line = 1);

/// A whole token as a decimal integer.
bool parse_int(std::string_view s, std::int64_t& out);

/// A whole token as a count; values too large for 64 bits saturate (they fail the size checks later).
bool parse_count(std::string_view s, std::uint64_t& out);

/// A whole token as a real number: optional sign, decimal digits with an optional exponent, or nan/inf.
/// Values that overflow give ±inf and are accepted, like nan: validate_mesh rejects non-finite ones later.
bool parse_double(std::string_view s, double& out);

/// As parse_double, rounded once to float (STL stores float; rounding a double again could differ).
bool parse_float(std::string_view s, float& out);

}  // namespace repose::io
