// `repose paper` produces every file the reproduction promises, and they are non-trivial (checked by
// tests/cli/check_paper_output.py: PNGs decode and are not blank, CSVs have the columns and rows, VTK files
// parse and each .pvd lists exactly the frames on disk).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli_test_support.hpp"
#include "run_cli.hpp"

namespace {

TEST(PaperCli, ProducesEveryFileNonTrivially) {
  namespace fs = std::filesystem;
  const fs::path out = fs::temp_directory_path() / ("repose_paper_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const auto r = repose::test::run_cli("paper --out '" + out.string() + "' --frames 20");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("report.md"), std::string::npos);
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string check = python + " '" + std::string(REPOSE_SOURCE_DIR) +
                            "/tests/cli/check_paper_output.py' '" + out.string() + "' 20";
  EXPECT_EQ(std::system(check.c_str()), 0);
  fs::remove_all(out);
}

TEST(PaperCli, UnwritableOutputIsABadInput) {
  repose::test::expect_bad_input(repose::test::run_cli("paper --out /dev/null/paper"),
                                 {"/dev/null/paper", "cannot create output directory"});
}

TEST(PaperCli, BadOptions) {
  using repose::test::expect_bad_input;
  using repose::test::run_cli;
  expect_bad_input(run_cli("paper --frames 1"), {"--frames", "1"});
  expect_bad_input(run_cli("paper --frames abc"), {"--frames", "abc"});
  expect_bad_input(run_cli("paper --bogus"), {"--bogus"});
}

// repose merge with nothing to merge, or a missing file.
TEST(MergeCli, BadInput) {
  using repose::test::expect_bad_input;
  using repose::test::run_cli;
  expect_bad_input(run_cli("merge"), {"files"});
  expect_bad_input(run_cli("merge /nonexistent/poses.json"), {"/nonexistent/poses.json", "cannot read"});
}

}  // namespace
