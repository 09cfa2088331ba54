// repose paper [--out DIR]: reproduces the four cases of section 3 of the paper (six runs), with time series,
// summaries, ParaView series, figures and a comparison table.
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.hpp"
#include "format.hpp"
#include "paper_data.hpp"
#include "repose/error.hpp"
#include "repose/model/particle.hpp"
#include "repose/model/scenario.hpp"
#include "repose/output/files.hpp"
#include "repose/output/html.hpp"
#include "repose/output/report.hpp"
#include "repose/output/vtk.hpp"
#include "repose/sim/settle.hpp"

namespace repose::cli {

namespace {

struct PaperOptions {
  std::string out = "paper-results";
  int frames = 100;
  bool plots = true;
};

// One case: the run, its CSV and JSON, and `frames` ParaView frames evenly spread over the run. Returns the
// run for the HTML report (its particle kept in `particles`).
SettleRecording run_case(const PaperCase& c, const PaperOptions& o, std::deque<Particle>& particles) {
  const Scenario s =
      parse_scenario(std::string(c.scenario_json), "scenarios/paper/" + std::string(c.name) + ".json");
  const std::string dir = o.out + "/" + std::string(c.name);
  ensure_output_directory(dir);
  const Particle& particle = particles.emplace_back(load_particle(s.particle, s.density, s.mesh));
  std::vector<Sample> samples;
  const SettleResult r = settle(
      particle, s.params, s.orientation, [&](const Sample& x) { samples.push_back(x); },
      default_sample_dt(particle, s.params));

  std::string csv = time_series_header();
  for (const Sample& x : samples) csv += time_series_row(x);
  write_file_atomically(dir + "/timeseries.csv", csv);
  write_file_atomically(dir + "/summary.json", settle_summary_json(particle, s.params, s.orientation, r));

  const double frame_dt = o.frames > 1 ? r.time / (o.frames - 1) : 0.0;
  VtkRecorder vtk(particle, dir + "/vtk", frame_dt, o.frames, s.params.contact_threshold);
  for (const Sample& x : samples) vtk(x);
  vtk.finish(r);

  std::cout << "  " << c.name << ": " << to_string(r.status) << " after " << num(r.time) << " s, "
            << to_string(r.rest) << " (COM height " << num(r.com.z()) << " cm), " << r.steps << " steps, "
            << vtk.frames() << " frames\n";
  return {.title = std::string(c.name),
          .particle = &particle,
          .params = s.params,
          .initial = s.orientation,
          .result = r,
          .samples = std::move(samples)};
}

// The comparison table and the figures that plot_paper.py listed in OUT/report.json.
void read_comparison(const std::string& out, std::vector<PaperTableRow>& table,
                     std::vector<PaperFigure>& figures) {
  const std::string path = out + "/report.json";
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_text_file(path));
    for (const auto& row : j.at("table")) {
      const auto text = row.get<std::vector<std::string>>();
      if (text.size() != 5) throw Error("a table row needs 5 entries");
      table.push_back({text[0], text[1], text[2], text[3], text[4]});
    }
    for (const auto& f : j.at("figures"))
      figures.push_back({f.at("title").get<std::string>(),
                         read_text_file(out + "/" + f.at("file").get<std::string>(), std::size_t{1} << 26)});
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": " + e.what());
  }
}

void make_figures(const PaperOptions& o) {
  const std::string script = o.out + "/plot_paper.py";
  write_file_atomically(script, std::string(kPlotPaperScript));
  // Debian's interpreter, where python3-matplotlib lives, even when another python3 comes first on PATH.
  const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string command = python + " '" + script + "' '" + o.out + "'";
  if (std::system(command.c_str()) != 0)
    throw Error(
        "figures: '" + command +
        "' failed (needs python3 with numpy and matplotlib: apt-get install python3-matplotlib; or use "
        "--no-plots)");
}

}  // namespace

Command add_paper_command(CLI::App& app) {
  auto o = std::make_shared<PaperOptions>();
  CLI::App* sub =
      app.add_subcommand("paper", "Reproduce the paper's cases (section 3): data, figures, ParaView");
  sub->add_option("--out", o->out, "Output directory (default paper-results)");
  sub->add_option("--frames", o->frames, "ParaView frames per case (default 100)")
      ->check(CLI::Range(2, 100000));
  sub->add_flag("!--no-plots", o->plots, "Skip the figures (no python3/matplotlib needed)");
  return {sub, [o]() {
            if (o->out.find('\'') != std::string::npos)
              throw Error("--out: a directory name with ' is not supported");
            ensure_output_directory(o->out);
            std::cout << "repose paper: " << kPaperCases.size() << " runs into " << o->out << "\n";
            std::deque<Particle> particles;
            std::vector<SettleRecording> runs;
            for (const PaperCase& c : kPaperCases) runs.push_back(run_case(c, *o, particles));
            std::vector<PaperTableRow> table;
            std::vector<PaperFigure> figures;
            if (o->plots) {
              make_figures(*o);
              read_comparison(o->out, table, figures);
            }
            write_file_atomically(o->out + "/report.html", paper_report_html(runs, table, figures));
            std::cout << "report: " << o->out << "/report.html (open it in a browser); ";
            if (o->plots) std::cout << "comparison table: " << o->out << "/report.md; ";
            std::cout << "ParaView: open " << o->out << "/<case>/vtk/settling.pvd\n";
            return 0;
          }};
}

}  // namespace repose::cli
