// repose poses MESH|SHAPE -n N ...: rest-pose statistics over many drops from uniformly random orientations.
// Several particles (files, directories, a manifest) and MPI ranks: see repose/campaign/campaign.hpp.
// repose merge FILE...: merges result files of disjoint drop ranges into the result of their union.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli_numbers.hpp"
#include "commands.hpp"
#include "format.hpp"
#include "interrupt.hpp"
#include "mesh_options.hpp"
#include "physics_options.hpp"
#include "progress_bar.hpp"
#include "repose/campaign/campaign.hpp"
#include "repose/campaign/summary.hpp"
#ifdef REPOSE_HAVE_MPI
#include "repose/campaign/mpi_runner.hpp"
#endif
#include "repose/model/particle.hpp"
#include "repose/output/files.hpp"
#include "repose/output/html.hpp"
#include "repose/poses/ensemble.hpp"
#include "repose/poses/landscape.hpp"
#include "repose/poses/rest_poses.hpp"
#include "repose/poses/study.hpp"
#include "repose/sim/settle.hpp"

namespace repose::cli {

namespace {

struct PosesOptions {
  std::vector<std::string> inputs;
  std::string manifest;
  std::uint64_t drops = 0;
  std::string range;
  std::uint64_t seed = 1;
  int threads = 0;
  std::uint64_t chunk = 0;
  std::string method = "dynamic";
  PhysicsOptions physics;
  MeshCliOptions mesh;
  TossDistributionOptions toss;
  double persistence = -1;  // fraction of L; < 0 = automatic
  bool full_settle = false;
  bool no_progress = false;
  std::string out_dir;
  std::string html;
  bool json = false;
};

DropRange parse_range(const std::string& text) {
  const auto colon = text.find(':');
  const auto bad = [&] {
    return Error("option --range must be BEGIN:END with 0 <= BEGIN < END, got '" + text + "'");
  };
  if (colon == std::string::npos) throw bad();
  const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
  const auto parse = [&](const std::string& s) {
    const std::optional<std::string> digits = exact_whole_number(s);
    if (!digits) throw bad();
    return static_cast<std::uint64_t>(std::stoull(*digits));
  };
  DropRange r{parse(a), parse(b)};
  if (r.begin >= r.end) throw bad();
  return r;
}

// Exit code 3 (as settle's) when drops ended before coming to rest: they are in no pose, and the
// probabilities (count / all drops) add up to less than 1. The result files are written all the same.
constexpr int kNotAtRest = 3;

std::uint64_t unrested(const PosesStudy& study) {
  return study.tally.status_counts[2] + study.tally.status_counts[3];
}

// The warning, and the exit code.
int report_unrested(const std::string& what, const PosesStudy& study) {
  const std::uint64_t n = unrested(study);
  if (n == 0) return 0;
  std::cerr << "repose: warning: " << what << n << " of " << study.tally.drops()
            << " drops did not come to rest within the limits: they are in no pose, so the probabilities add "
               "up to less than 1 (status_counts; raise --max-time or --max-steps); exit code 3\n";
  return kNotAtRest;
}

// Writes BASE.json and BASE.csv.
void write_result(const std::string& base, const PosesStudy& study) {
  for (const char* ext : {".json", ".csv"}) {
    const std::string path = base + ext;
    write_file_atomically(path, ext[1] == 'j' ? poses_json(study) : poses_csv(study));
    remove_temporaries(path);
  }
}

int print_result(const PosesStudy& study, bool json) {
  std::cout << (json ? poses_json(study) : poses_table(study));
  std::cout.flush();
  return report_unrested("", study);
}

// What --method quasi-static (steepest descent of the centre of mass, no dynamics) would ignore.
constexpr const char* kDynamicOnly[] = {
    "--full-settle",       "--damping",        "--damping-ratio", "--integrator", "--dt",       "--tolerance",
    "--contact-threshold", "--line-threshold", "--drop-height",   "--drop-speed", "--max-time", "--max-steps",
    "--restitution",       "--friction",       "--velocity-max",  "--spin-max"};

// The job's settings from the options (the same on every rank). Throws repose::Error for bad values.
CampaignOptions campaign_options(const PosesOptions& o, const CLI::App& sub, int threads) {
  const auto given = [&](const char* option) { return sub.count(option) > 0; };
  CampaignOptions c;
  if (given("--range") && given("--drops")) throw Error("give either -n/--drops or --range, not both");
  if (given("--range"))
    c.drops = parse_range(o.range);
  else if (given("--drops") && o.drops > 0)
    c.drops = {0, o.drops};
  else
    throw Error("poses: give the number of drops with -n N (N >= 1) or a drop range with --range BEGIN:END");
  check_positive("--density", o.physics.density);
  if (o.threads < 0)
    throw Error("option --threads must be >= 0 (0 = all cores), got " + std::to_string(o.threads));
  if (o.method == "quasi-static")
    for (const char* option : kDynamicOnly)
      if (given(option))
        throw Error(std::string("poses: ") + option +
                    " has no effect with --method quasi-static (it sets the dynamic engine's drops); remove "
                    "it or use --method dynamic");
  if (given("--persistence") && (!std::isfinite(o.persistence) || o.persistence < 0))
    throw Error("option --persistence must be a finite number >= 0, got " + num(o.persistence));
  StudySettings& s = c.settings;
  s.seed = o.seed;
  s.method = parse_pose_method(o.method);
  s.density = o.physics.density;
  o.physics.apply_given(sub, s.params);
  s.params.gravity = standard_gravity(o.physics.unit_system());
  s.damping_given = given("--damping");
  if (!s.damping_given) s.params.damping = 0;  // set from the ratio once the particle is known
  validate(s.params);
  apply_toss_distribution(o.toss, s);
  s.persistence = given("--persistence") ? o.persistence : -1;
  s.decide_early = !o.full_settle;
  c.threads = threads;
  c.chunk = o.chunk;
  if (!o.out_dir.empty())
    c.checkpoint_dir = (std::filesystem::path(o.out_dir) / ".repose-checkpoint").string();
  return c;
}

std::unique_ptr<WorkRunner> make_runner() {
#ifdef REPOSE_HAVE_MPI
  if (launched_by_mpi()) return make_mpi_runner();
#else
  if (launched_by_mpi())
    std::cerr << "repose: warning: this repose was built without MPI (REPOSE_MPI=OFF): every rank runs the "
                 "whole job\n";
#endif
  return std::make_unique<LocalRunner>();
}

// The job on this rank; the root prints the result. Errors are thrown (RootFailed on the other ranks).
int run_job(const PosesOptions& o, const CLI::App& sub, WorkRunner& runner) {
  const auto start = std::chrono::steady_clock::now();
  // Ranks that share a node share its cores.
  const int cores = available_cores();
  int threads = o.threads > 0 ? o.threads : std::max(1, cores / runner.ranks_on_this_node());
  if (threads > cores) {  // TBB would run no more threads than cores anyway, and say so in its own words
    if (runner.is_root())
      std::cerr << "repose: warning: --threads " << threads << " is more than the " << cores
                << " cores this process may use; using " << cores << "\n";
    threads = cores;
  }
  // Options are checked on every rank alike, but only the root reports a problem.
  CampaignOptions campaign;
  std::exception_ptr bad_options;
  try {
    campaign = campaign_options(o, sub, threads);
  } catch (const Error&) {
    bad_options = std::current_exception();
  }
  std::vector<CampaignParticle> particles;
  const auto resolve = [&] {
    if (bad_options) std::rethrow_exception(bad_options);
    if (!o.out_dir.empty()) ensure_output_directory(o.out_dir);
    particles =
        resolve_particles(o.inputs, o.manifest, o.mesh.resolve(o.physics.unit_system() == UnitSystem::cgs),
                          o.physics.unit_system() == UnitSystem::cgs);
    if (!o.html.empty() && particles.size() > 1)
      throw Error("poses: --html writes the report of one particle, and this job has " +
                  std::to_string(particles.size()) + " (run repose poses on one of them with --html)");
    if (!o.html.empty()) ensure_output_file(o.html);
    if (particles.size() > 1 && o.out_dir.empty())
      throw Error("poses: " + std::to_string(particles.size()) +
                  " particles need --out DIR (one result file per particle and a summary)");
    return particles;
  };

  std::atomic<std::uint64_t> done{0}, kept{0};
  std::unique_ptr<ProgressBar> bar;
  campaign.progress = &done;
  campaign.kept = &kept;
  campaign.on_start = [&](std::uint64_t remaining, const std::vector<PosesStudy>& prepared) {
    for (const PosesStudy& study : prepared)
      warn_implausible_size(study.source, study.length, o.physics.unit_system());
    const std::uint64_t total = campaign.drops.size() * particles.size();
    if (remaining < total)
      std::cerr << "repose: resuming from " << campaign.checkpoint_dir << ": " << total - remaining << " of "
                << total << " drops found there, " << remaining << " to run\n";
    install_interrupt_report({.total = total,
                              .kept = o.out_dir.empty() ? nullptr : &kept,
                              .done = &done,
                              .checkpoint_dir = campaign.checkpoint_dir});
    bar = std::make_unique<ProgressBar>(remaining, done, !o.no_progress);
  };
  // One particle: DIR/poses.json; several: DIR/NAME.poses.json. Written before the checkpoint goes.
  const auto result_base = [&](std::size_t i) {
    return (std::filesystem::path(o.out_dir) /
            (particles.size() == 1 ? "poses" : particles[i].name + ".poses"))
        .string();
  };
  CampaignSummary summary;
  campaign.on_complete = [&](const std::vector<PosesStudy>& studies) {
    summary.particles = particles;
    summary.studies = studies;
    for (std::size_t i = 0; i < particles.size(); ++i)
      summary.result_files.push_back(std::filesystem::path(result_base(i)).filename().string() + ".json");
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary.ranks = runner.ranks();
    summary.threads = threads;
    if (o.out_dir.empty()) return;
    for (std::size_t i = 0; i < particles.size(); ++i) write_result(result_base(i), studies[i]);
    if (particles.size() == 1) return;
    write_file_atomically(o.out_dir + "/summary.csv", summary_csv(summary));
    write_file_atomically(o.out_dir + "/summary.md", summary_markdown(summary));
    write_file_atomically(o.out_dir + "/summary.json", summary_json(summary));
  };
  const std::vector<PosesStudy> studies = run_campaign(resolve, campaign, runner);
  remove_interrupt_report();
  bar.reset();
  if (!runner.is_root()) return 0;

  if (studies.size() == 1) {
    if (!o.html.empty())
      write_file_atomically(
          o.html, poses_report_html(load_particle(particles[0].source, studies[0].density, particles[0].mesh),
                                    studies[0]));
    return print_result(studies[0], o.json);
  }
  std::cout << (o.json ? summary_json(summary) : summary_markdown(summary));
  std::cout.flush();
  int code = 0;
  for (std::size_t i = 0; i < particles.size(); ++i)
    code = std::max(code, report_unrested(particles[i].name + ": ", studies[i]));
  return code;
}

// The job ends collectively: the root prints its result or its one-line error and flushes, then tells every
// rank the exit code, and no rank returns before that. mpirun ends the whole job as soon as one rank exits
// non-zero, so a rank that left first with code 2 could kill the root before it printed the error.
int run_poses(const PosesOptions& o, const CLI::App& sub) {
  const std::unique_ptr<WorkRunner> runner = make_runner();
  int code = 0;
  try {
    code = run_job(o, sub, *runner);
  } catch (const RootFailed& failed) {
    code = failed.exit_code;  // the root reports
  } catch (...) {
    // Only the root reaches the agreement below with an error of its own; an error that only another rank
    // met is outside the protocol (the root would wait for it forever): that rank reports and exits now.
    if (!runner->is_root()) throw;
    code = report_error(std::current_exception());
  }
  std::cout.flush();
  return std::stoi(runner->broadcast(std::to_string(code)));
}

}  // namespace

Command add_poses_command(CLI::App& app) {
  auto o = std::make_shared<PosesOptions>();
  CLI::App* sub = app.add_subcommand(
      "poses",
      "Rest-pose statistics: drop the particle from uniformly random orientations, count where it rests");
  sub->add_option("particles", o->inputs,
                  "Mesh files (STL, OBJ, PLY, OFF), shape specs or directories of mesh files; with several "
                  "particles, --out is required");
  sub->add_option("--manifest", o->manifest,
                  "File listing particles, one mesh path or shape spec per line (# comments; paths relative "
                  "to the file)");
  sub->add_option("-n,--drops", o->drops, "Number of drops (drop indices 0 .. N-1)")->check(whole_number(1));
  sub->add_option(
      "--range", o->range,
      "Run only drops BEGIN .. END-1 (for splitting a study; merge the results with repose merge)");
  sub->add_option("--seed", o->seed, "Seed: drop i's orientation depends only on (seed, i) (default 1)")
      ->check(whole_number(0));
  sub->add_option("--threads", o->threads,
                  "Worker threads per process (default 0: all the cores this process may use, shared among "
                  "the MPI ranks of a node)");
  sub->add_option("--chunk", o->chunk,
                  "Drops per work item: the unit of load balancing and of checkpointing (default: about 64 "
                  "items per particle, 128 to 65536 drops each)")
      ->check(whole_number(1));
  sub->add_option("--method", o->method,
                  "dynamic (the settling engine) or quasi-static (steepest descent of the COM height)")
      ->check(CLI::IsMember({"dynamic", "quasi-static"}));
  add_physics_options(*sub, o->physics, "Damping coefficient C of Eq 4 ({unit}); overrides --damping-ratio");
  add_mesh_options(*sub, o->mesh);
  add_impact_options(*sub, o->physics);
  add_toss_distribution_options(*sub, o->toss, "Tosses: ");
  sub->add_option("--persistence", o->persistence,
                  "Merge stable faces whose barrier is below this fraction of L into one pose (default 0, "
                  "0.01 for smooth particles)");
  sub->add_flag("--full-settle", o->full_settle,
                "Simulate every drop to rest instead of stopping once its energy cannot leave its pose");
  sub->add_flag("--no-progress", o->no_progress, "No progress bar (it is shown only on a terminal anyway)");
  sub->add_option(
      "--out", o->out_dir,
      "Write poses.json and poses.csv (several particles: NAME.poses.json/.csv and summary.csv/.md/"
      ".json) into this directory, with a checkpoint in DIR/.repose-checkpoint: rerunning the same "
      "command after an interruption resumes");
  sub->add_option("--html", o->html,
                  "Write a self-contained HTML report: every rest pose drawn at rest, with its probability "
                  "(one particle; docs/reports.md)");
  sub->add_flag("--json", o->json, "Print the JSON result instead of the table");
  sub->footer(
      "Exit codes: 0 done; 2 bad input; 3 some drops did not come to rest within --max-time/--max-steps (the "
      "result is printed and written all the same); 130 interrupted by Ctrl-C (143 by SIGTERM): with --out, "
      "rerunning the same command resumes.");
  return {sub, [o, sub]() { return run_poses(*o, *sub); }};
}

Command add_merge_command(CLI::App& app) {
  struct MergeOptions {
    std::vector<std::string> files;
    std::string out_dir;
    bool json = false;
  };
  auto o = std::make_shared<MergeOptions>();
  CLI::App* sub = app.add_subcommand(
      "merge", "Merge repose poses result files of disjoint drop ranges (same particle, seed and settings)");
  sub->add_option("files", o->files, "poses.json files")->required();
  sub->add_option("--out", o->out_dir, "Write the merged poses.json and poses.csv into this directory");
  sub->add_flag("--json", o->json, "Print the merged JSON instead of the table");
  return {sub, [o]() {
            if (!o->out_dir.empty()) ensure_output_directory(o->out_dir);
            PosesStudy merged;
            for (std::size_t i = 0; i < o->files.size(); ++i) {
              const PosesStudy part = parse_poses_json(read_text_file(o->files[i]), o->files[i]);
              try {
                merged = i == 0 ? part : merge_studies(merged, part);
              } catch (const Error& e) {
                throw Error(o->files[i] + ": " + e.what());
              }
            }
            if (!o->out_dir.empty()) write_result(o->out_dir + "/poses", merged);
            return print_result(merged, o->json);
          }};
}

}  // namespace repose::cli
