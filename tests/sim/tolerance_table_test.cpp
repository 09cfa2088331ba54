// Every tolerance and solver constant of the engine is in the tolerance table (src/sim/tolerances.hpp), each
// with its reason (issue 48). This scans the code of src/sim — comments and strings left out — for what a
// tolerance looks like anywhere else: a literal in scientific or hexadecimal notation, a decimal fraction
// that is not a simple one (a multiple of 1/4, as in ½·a·t²), an integer above 19 (a bound, a sample count;
// smaller ones index the integrator's state and size the solvers' systems) and a named constant set from a
// number.
#include <gtest/gtest.h>

// GCC 12's libstdc++ <regex> at -O1 under the sanitizers warns of a std::function it may read uninitialized
// inside its own compiler (a false positive in the library's code, with -Werror an error).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace repose::sim {
namespace {

// The code with comments, string and character literals replaced by spaces (line breaks kept).
std::string code_only(const std::string& text) {
  std::string out = text;
  enum { code, line, block, string, character } state = code;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const char c = out[i], next = i + 1 < out.size() ? out[i + 1] : '\0';
    switch (state) {
      case code:
        if (c == '/' && next == '/')
          state = line, out[i] = ' ';
        else if (c == '/' && next == '*')
          state = block, out[i] = ' ';
        else if (c == '"')
          state = string, out[i] = ' ';
        else if (c == '\'' && !(i > 0 && std::isxdigit(static_cast<unsigned char>(out[i - 1]))))
          state = character, out[i] = ' ';  // (a digit separator, 0x48'0000, is no character literal)
        break;
      case line:
        if (c == '\n')
          state = code;
        else
          out[i] = ' ';
        break;
      case block:
        if (c == '*' && next == '/')
          out[i] = out[i + 1] = ' ', ++i, state = code;
        else if (c != '\n')
          out[i] = ' ';
        break;
      case string:
      case character:
        if (c == '\\')
          out[i] = ' ', out[i + 1] = out[i + 1] == '\n' ? '\n' : ' ', ++i;
        else if (c == (state == string ? '"' : '\''))
          out[i] = ' ', state = code;
        else if (c != '\n')
          out[i] = ' ';
        break;
    }
  }
  return out;
}

// What looks like a tolerance in `code` (one line each: the line number and the text found).
std::vector<std::string> tolerance_literals(const std::string& text) {
  static const std::regex scientific(R"((^|[^\w.])(\d+\.?\d*[eE][-+]?\d+|0[xX][\da-fA-F.]+[pP][-+]?\d+))");
  static const std::regex decimal(R"((^|[^\w.])(\d+\.\d+)(?![\w.]))");
  static const std::regex integer(R"((^|[^\w.])(\d+)(?![\w.]))");
  static const std::regex named(
      R"(constexpr\s+(?:static\s+)?(?:double|float|int|long|unsigned|std::size_t|std::u?int\d+_t|auto)\s+k[A-Z]\w*\s*=[^;]*[^\w.]\d)");
  std::vector<std::string> found;
  std::istringstream lines(code_only(text));
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    const auto flag = [&](const std::string& what) { found.push_back(std::to_string(number) + ": " + what); };
    std::smatch m;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), scientific); it != std::sregex_iterator();
         ++it)
      flag((*it)[2]);
    for (auto it = std::sregex_iterator(line.begin(), line.end(), decimal); it != std::sregex_iterator();
         ++it) {
      const double v = std::stod((*it)[2]);
      if (std::floor(4 * v) != 4 * v) flag((*it)[2]);
    }
    for (auto it = std::sregex_iterator(line.begin(), line.end(), integer); it != std::sregex_iterator();
         ++it)
      if (std::stod((*it)[2]) > 19) flag((*it)[2]);
    if (std::regex_search(line, m, named)) flag(m[0]);
  }
  return found;
}

TEST(ToleranceTable, TheScanFindsWhatATolerancePlantedInCodeLooksLike) {
  EXPECT_FALSE(tolerance_literals("x = 1e-9 * L;").empty());
  EXPECT_FALSE(tolerance_literals("x = 0x1p-44;").empty());
  EXPECT_FALSE(tolerance_literals("if (a > 0.2 * b) return;").empty());
  EXPECT_FALSE(tolerance_literals("for (int i = 0; i < 60; ++i) {}").empty());
  EXPECT_FALSE(tolerance_literals("constexpr int kSweeps = 8;").empty());
  EXPECT_FALSE(tolerance_literals("static constexpr std::size_t kCached = 4;").empty());
  // Simple fractions, small integers, names with digits, comments and strings are not tolerances.
  EXPECT_TRUE(tolerance_literals("y = 0.5 * a * t * t + 1.0 + x2 + v.head<2>() + M(11, 3) + s[16];").empty());
  EXPECT_TRUE(tolerance_literals("constexpr std::size_t kBits = std::numeric_limits<std::uint64_t>::digits;")
                  .empty());
  EXPECT_TRUE(tolerance_literals("z = 1; // 1e-9 of L\n/* 0.2 */ s = \"60 1e-3\";").empty());
}

TEST(ToleranceTable, NoToleranceLiteralInSrcSimOutsideTheTable) {
  const std::filesystem::path root = std::filesystem::path(REPOSE_SOURCE_DIR) / "src" / "sim";
  std::vector<std::string> offences;
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    const std::filesystem::path& p = entry.path();
    if (!entry.is_regular_file() || (p.extension() != ".cpp" && p.extension() != ".hpp")) continue;
    if (p.stem() == "tolerances") continue;  // the table itself
    ++files;
    std::ifstream in(p);
    std::stringstream text;
    text << in.rdbuf();
    for (const std::string& f : tolerance_literals(text.str()))
      offences.push_back(std::filesystem::relative(p, root).string() + ":" + f);
  }
  EXPECT_GT(files, 20);
  std::string list;
  for (const std::string& o : offences) list += "\n  src/sim/" + o;
  EXPECT_TRUE(offences.empty()) << offences.size()
                                << " tolerance literals outside src/sim/tolerances.hpp:" << list;
}

}  // namespace
}  // namespace repose::sim
