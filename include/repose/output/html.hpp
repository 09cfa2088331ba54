// Self-contained HTML reports: one file that any browser opens with no network. The page's code and the two
// JavaScript libraries it uses (three.js for the 3-D views, uPlot for the plots; vendored from npm with their
// licences in third_party/) are embedded in the file, and so is the run's data, as JSON in a
// <script id="repose-data" type="application/json"> element (field names in docs/reports.md).
//
//   settle  a 3-D view of the particle and the wall that plays the run (play/pause, a time slider, the
//           contact points and the centre of mass marked, the contact type shown) and plots of the angular
//           speed, the energies and the contact type against time.
//   poses   every rest pose drawn at rest, its probability with the 95 % interval beside the quasi-static
//           probability (a bar chart), the counts and the run's settings.
//   paper   the comparison table with the paper, every figure, and the player of each case.
//   design  an inverse design: target against achieved per outcome, the design in each rest pose, its
//   history.
//
// Lengths are in the particle's length unit, times in the run's time unit (whatever SettleParams::gravity
// fixes), exactly as in the JSON summary and the time series.
#pragma once

#include <string>
#include <vector>

#include "repose/model/params.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/study.hpp"
#include "repose/sim/settle.hpp"

namespace repose {

/// One settling run as a report shows it: the samples an observer received (any spacing; thinned to at most
/// kReportMaxFrames, always keeping the first and the last) and the result.
struct SettleRecording {
  std::string title;  ///< shown as the page's heading (the particle's name if empty)
  const Particle* particle = nullptr;
  SettleParams params;
  Quat initial = Quat::Identity();
  SettleResult result;
  std::vector<Sample> samples;
};

/// The most frames a report keeps of one run: smooth playback and plots (a frame per pixel of a plot's width
/// and more), and a light page (a frame is 150 bytes of JSON, plus 6 per hull vertex within the contact
/// threshold: the smooth ellipsoid's 44 make it 400).
inline constexpr std::size_t kReportMaxFrames = 2500;

/// The surface a report draws: the particle's mesh, or its convex hull when the mesh has more than this many
/// triangles (a 2,000,000-triangle scan would make a page of 100 MB).
inline constexpr std::size_t kReportMaxTriangles = 200000;

/// The report of one run. Throws repose::Error if the recording has no particle.
std::string settle_report_html(const SettleRecording& run);

/// The report of a rest-pose study of `particle` (the particle the study was made of).
std::string poses_report_html(const Particle& particle, const PosesStudy& study);

/// The report of an inverse design (`repose design --html`; repose/design/design_report.hpp builds its
/// arguments): `design` the designed particle, `face_outcome` the outcome of each of its hull faces (−1:
/// none), `title` its heading and `design_json` its design.json text (target, achieved, history, checks).
std::string design_report_page(const std::string& title, const Particle& design,
                               const std::vector<int>& face_outcome, const std::string& design_json);

/// A row of the paper's comparison table, as text (already formatted by scripts/plot_paper.py).
struct PaperTableRow {
  std::string case_name, quantity, paper, exact, repose;
};

/// A figure: its title and the PNG file's bytes.
struct PaperFigure {
  std::string title;
  std::string png;
};

/// The paper report: every case's player, the comparison table and the figures (either may be empty when
/// the figures were not made: `repose paper --no-plots`).
std::string paper_report_html(const std::vector<SettleRecording>& cases,
                              const std::vector<PaperTableRow>& table,
                              const std::vector<PaperFigure>& figures);

}  // namespace repose
