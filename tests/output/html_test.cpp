// The HTML reports' pages (what a browser then draws is tested in report_browser_test.py): the embedded data
// read back as JSON must describe the run (frames in time order, ending on the rest pose; the touching
// vertices those the test finds at the wall itself), the page must stay one well-formed file whatever the
// particle is called, and the helpers must match their standards (RFC 4648 for base64).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <repose/error.hpp>
#include <repose/model/orientation.hpp>
#include <repose/model/particle.hpp>
#include <repose/output/html.hpp>
#include <repose/poses/landscape.hpp>
#include <repose/poses/study.hpp>
#include <repose/sim/settle.hpp>
#include <string>
#include <vector>

#include "../support/report_page.hpp"
#include "output/html_page.hpp"

namespace repose {
namespace {

using nlohmann::json;

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

SettleRecording cube_run(const Particle& cube, std::vector<Sample>& samples_out) {
  SettleParams params;
  params.damping = 0.5;
  const Quat q0 = parse_orientation("axis-angle:1,0.4,0.2,0.6");
  std::vector<Sample> samples;
  const SettleResult r = settle(
      cube, params, q0, [&](const Sample& s) { samples.push_back(s); }, 2e-4);
  samples_out = samples;
  return {
      .title = "a cube", .particle = &cube, .params = params, .initial = q0, .result = r, .samples = samples};
}

TEST(HtmlReport, SettleDataDescribesTheRunAndEndsOnItsRestPose) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  std::vector<Sample> samples;
  const SettleRecording run = cube_run(cube, samples);
  ASSERT_EQ(run.result.status, Status::rest);
  ASSERT_GT(samples.size(), kReportMaxFrames);  // so that thinning is exercised
  const std::string page = settle_report_html(run);
  const json data = test::report_page_data(page);
  EXPECT_EQ(data["kind"], "settle");
  EXPECT_EQ(data["title"], "a cube");
  EXPECT_EQ(data["summary"]["status"], "rest");
  const json& f = data["frames"];
  const std::size_t n = f["t"].size();
  EXPECT_LE(n, kReportMaxFrames + 1);  // the thinned samples and, if later, the rest
  EXPECT_GE(n, kReportMaxFrames / 2);
  for (const char* key : {"contact", "kinetic", "potential", "contacts"}) EXPECT_EQ(f[key].size(), n) << key;
  EXPECT_EQ(f["q"].size(), 4 * n);
  EXPECT_EQ(f["com"].size(), 3 * n);
  EXPECT_DOUBLE_EQ(f["t"][0].get<double>(), samples.front().t);
  for (std::size_t i = 1; i < n; ++i) EXPECT_LT(f["t"][i - 1].get<double>(), f["t"][i].get<double>());
  EXPECT_DOUBLE_EQ(f["t"][n - 1].get<double>(), run.result.time);

  // The last frame is the rest pose: the orientation to the 7 digits the page keeps, and the four corners of
  // the resting face, found here from the body-frame corners (±0.5 each) at that orientation, on the wall.
  const Quat& q = run.result.orientation;
  const double qs[4] = {q.w(), q.x(), q.y(), q.z()};
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(f["q"][4 * (n - 1) + k].get<double>(), qs[k], 1e-6);
  std::vector<int> expected;
  const auto hull = data["shape"]["hull_vertices"].get<std::vector<double>>();
  ASSERT_EQ(hull.size(), 24u);
  for (std::size_t i = 0; i < 8; ++i) {
    const Vec3 corner(hull[3 * i], hull[3 * i + 1], hull[3 * i + 2]);
    EXPECT_DOUBLE_EQ(corner.cwiseAbs().maxCoeff(), 0.5);
    if ((q * corner).z() + run.result.com.z() < 1e-9) expected.push_back(static_cast<int>(i));
  }
  EXPECT_EQ(expected.size(), 4u);
  EXPECT_EQ(f["contacts"][n - 1].get<std::vector<int>>(), expected);
  EXPECT_EQ(f["contact"][n - 1].get<int>(), static_cast<int>(ContactType::surface));
  EXPECT_DOUBLE_EQ(f["kinetic"][n - 1].get<double>(), 0.0);
  // Potential energy m·g·z of the 1 × 1 × 1 unit-density cube on a face: 9.81 · 0.5.
  EXPECT_NEAR(f["potential"][n - 1].get<double>(), 9.81 * 0.5, 1e-6);
  // The surface drawn: the cube's 12 triangles.
  EXPECT_EQ(data["shape"]["surface"], "mesh");
  EXPECT_EQ(data["shape"]["triangles"].size(), 36u);
}

TEST(HtmlReport, APageIsOneWellFormedFileWhateverTheNames) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  std::vector<Sample> samples;
  SettleRecording run = cube_run(cube, samples);
  run.title = "</script><script>alert(1)</script> & <b>";
  const std::string page = settle_report_html(run);
  // The four scripts (data, uPlot, three.js as text, the page module) end where they should, and nowhere
  // else does a script end: the title cannot close the data element.
  EXPECT_EQ(count(page, "<script"), 4u);
  EXPECT_EQ(count(page, "</script>"), 4u);
  EXPECT_EQ(test::report_page_data(page)["title"], run.title);
  EXPECT_NE(page.find("<title>repose settle: &lt;/script&gt;&lt;script&gt;alert(1)&lt;/script&gt; &amp; "
                      "&lt;b&gt;</title>"),
            std::string::npos);
  // No address outside the page: nothing to fetch at view time.
  EXPECT_EQ(page.find("src=\"http"), std::string::npos);
  EXPECT_EQ(page.find("href=\"http"), std::string::npos);
  // The libraries' licences travel with them.
  EXPECT_NE(page.find("Copyright © 2010-2024 three.js authors"), std::string::npos);
  EXPECT_NE(page.find("Copyright (c) 2022 Leon Sorokin"), std::string::npos);
}

TEST(HtmlReport, ALargeMeshIsDrawnAsItsHull) {
  // 20·n² triangles: n = 101 is 204,020 > kReportMaxTriangles.
  const Particle grain = load_particle("ellipsoid:a=1,b=0.8,c=0.6,n=101", 1.0);
  ASSERT_GT(grain.mesh.triangles.size(), kReportMaxTriangles);
  SettleRecording run;
  run.particle = &grain;
  run.result.status = Status::max_steps;
  const json shape = test::report_page_data(settle_report_html(run))["shape"];
  EXPECT_EQ(shape["surface"], "convex hull");
  EXPECT_EQ(shape["vertices"].size(), 3 * grain.hull.vertices.size());
  std::size_t triangles = 0;
  for (const HullFace& f : grain.hull.faces) triangles += f.loop.size() - 2;
  EXPECT_EQ(shape["triangles"].size(), 3 * triangles);
}

TEST(HtmlReport, PosesAndPaperPagesCarryTheirResults) {
  const Particle box = load_particle("box:x=1,y=2,z=3", 1.0);
  const RestLandscape landscape = compute_rest_landscape(box);
  StudySettings settings;
  settings.method = PoseMethod::quasi_static;
  PosesStudy study = prepare_study(box, landscape, settings);
  const json data = test::report_page_data(poses_report_html(box, study));
  EXPECT_EQ(data["kind"], "poses");
  EXPECT_EQ(data["study"], json::parse(poses_json(study)));

  std::vector<Sample> samples;
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  const std::vector<SettleRecording> runs = {cube_run(cube, samples)};
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + "pixels";
  const json paper = test::report_page_data(
      paper_report_html(runs, {{"cube", "rest face", "—", "1", "1"}}, {{"a figure", png}}));
  EXPECT_EQ(paper["cases"].size(), 1u);
  EXPECT_EQ(paper["table"][0], json({"cube", "rest face", "—", "1", "1"}));
  EXPECT_EQ(paper["figures"][0]["src"], "data:image/png;base64,iVBORw0KGgpwaXhlbHM=");
}

TEST(HtmlReport, Base64FollowsRfc4648) {
  // The test vectors of RFC 4648, section 10.
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foo"), "Zm9v");
  EXPECT_EQ(base64("foob"), "Zm9vYg==");
  EXPECT_EQ(base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64(std::string("\xff\xfe\x00", 3)), "//4A");
}

TEST(HtmlReport, UnknownAssetsAndRunsWithoutAParticleAreErrors) {
  EXPECT_THROW(report_asset("html/missing.js"), Error);
  EXPECT_THROW(settle_report_html(SettleRecording{}), Error);
}

}  // namespace
}  // namespace repose
