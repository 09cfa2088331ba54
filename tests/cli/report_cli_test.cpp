// `--html FILE` of settle and poses: the page carries the same numbers as `--json` for the same run, and a
// file name it cannot write is a bad input reported before any run, with nothing written. (What a browser
// draws of the page: tests/output/report_browser_test.py; the paper's report.html: check_paper_output.py.)
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "../support/report_page.hpp"
#include "cli_test_support.hpp"
#include "run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using repose::test::expect_bad_input;
using repose::test::parse_json;
using repose::test::read_file;
using repose::test::run_cli;
using repose::test::shell_quote;
using repose::test::without_timing;

// The JSON a report page embeds.
json page_data(const fs::path& page) { return repose::test::report_page_data(read_file(page)); }

class ReportCli : public repose::test::TempDirTest {};

TEST_F(ReportCli, SettlePageCarriesTheRunsJsonSummary) {
  const std::string run =
      "settle tetrahedron:edge=1 --orientation axis-angle:1,0.3,0,0.7 --damping 0.01 --json";
  const json printed = parse_json(run_cli(run + " --html " + shell_quote((dir_ / "a/run.html").string())));
  const json page = page_data(dir_ / "a/run.html");  // the missing directory a/ was made
  EXPECT_EQ(page["kind"], "settle");
  EXPECT_EQ(page["summary"], printed);
  EXPECT_EQ(page["shape"]["triangles"].size(), 12u);  // the tetrahedron's 4 faces
  // The last frame is where the run ended (the time to 17 digits, as printed).
  EXPECT_EQ(page["frames"]["t"].back(), printed["time"]);
}

TEST_F(ReportCli, PosesPageCarriesTheStudy) {
  const json printed = parse_json(
      run_cli("poses box:x=1,y=2,z=3 -n 400 --json --html " + shell_quote((dir_ / "poses.html").string())));
  const json page = page_data(dir_ / "poses.html");
  EXPECT_EQ(page["kind"], "poses");
  EXPECT_EQ(without_timing(page["study"]), without_timing(printed));
  EXPECT_EQ(page["study"]["poses"].size(), 6u);
}

TEST_F(ReportCli, AnHtmlFileThatCannotBeWrittenIsABadInputBeforeTheRun) {
  fs::create_directory(dir_ / "taken");
  expect_bad_input(run_cli("settle cube --html " + shell_quote((dir_ / "taken").string())),
                   {(dir_ / "taken").string(), "is a directory"});
  expect_bad_input(run_cli("settle tetrahedron:edge=1 --html /dev/null/run.html"),
                   {"/dev/null/run.html: cannot be written", "not a directory"});
  expect_bad_input(run_cli("poses box:x=1,y=2,z=3 -n 10 --html /dev/null/poses.html"),
                   {"/dev/null/poses.html: cannot be written", "not a directory"});
  // Several particles: one report per particle is the rule.
  expect_bad_input(
      run_cli("poses tetrahedron:edge=1 box:x=1,y=2,z=3 -n 10 --out " + shell_quote((dir_ / "out").string()) +
              " --html " + shell_quote((dir_ / "two.html").string())),
      {"--html", "one particle", "2"});
  EXPECT_FALSE(fs::exists(dir_ / "two.html"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "summary.json"));
}

}  // namespace
