// Shared by the command-line tests: the bad-input contract, JSON output, and a fresh directory per test.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_cli.hpp"

namespace repose::test {

/// Bad input: exit code 2, nothing on stdout, exactly one line on stderr that starts with "repose: error: "
/// and contains every string in `expected` (the input's name and the problem).
inline void expect_bad_input(const CliResult& r, const std::vector<std::string>& expected) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_THAT(r.err, ::testing::StartsWith("repose: error: "));
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.back(), '\n') << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << r.err;
  for (const std::string& s : expected) EXPECT_THAT(r.err, ::testing::HasSubstr(s));
}

/// A whole file ("" if it cannot be read).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// `s` single-quoted for /bin/sh.
inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// A JSON array of numbers as a vector (empty if `v` is not an array).
inline std::vector<double> numbers(const nlohmann::json& v) {
  std::vector<double> out;
  if (v.is_array())
    for (const nlohmann::json& x : v) out.push_back(x.get<double>());
  return out;
}

/// The rows of a CSV file after its header, each split at commas.
inline std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream in(text);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::stringstream fs(line);
    std::string f;
    while (std::getline(fs, f, ',')) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

/// The JSON without its timing object, the only part allowed to differ between equivalent runs.
inline nlohmann::json without_timing(nlohmann::json j) {
  j.erase("timing");
  return j;
}

/// Standard output parsed as JSON, after checking the exit code.
inline nlohmann::json parse_json(const CliResult& r, int exit_code = 0) {
  EXPECT_EQ(r.exit_code, exit_code) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out, nullptr, /*allow_exceptions=*/false);
  EXPECT_FALSE(j.is_discarded()) << "stdout is not JSON:\n" << r.out;
  return j;
}

/// Every test gets a fresh temporary directory `dir_`, removed afterwards.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (std::filesystem::temp_directory_path() / "repose_cli_test_XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  /// Names in a directory (default: the test's own), sorted.
  std::vector<std::string> entries(const std::filesystem::path& d = {}) const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(d.empty() ? dir_ : d))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  std::filesystem::path dir_;
};

// The sanitizer build runs the engine ~200x slower: the campaign tests make the same checks on fewer drops
// and smaller items.
#ifdef NDEBUG
inline constexpr int kCampaignScale = 1;
#else
inline constexpr int kCampaignScale = 20;
#endif

#ifdef REPOSE_MPIEXEC
/// The launcher prefix of a command run on `ranks` MPI ranks.
inline std::string mpirun(int ranks) {
  return std::string(REPOSE_MPIEXEC) + " -np " + std::to_string(ranks) + " ";
}
#endif

}  // namespace repose::test
