// repose poses MESH|SHAPE -n N ...: rest-pose statistics over many drops from uniformly random orientations.
// repose merge FILE...: merges result files of disjoint drop ranges into the result of their union.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "commands.hpp"
#include "format.hpp"
#include "physics_options.hpp"
#include "repose/model/particle.hpp"
#include "repose/output/files.hpp"
#include "repose/poses/ensemble.hpp"
#include "repose/poses/landscape.hpp"
#include "repose/poses/rest_poses.hpp"
#include "repose/poses/study.hpp"
#include "repose/sim/settle.hpp"

namespace repose::cli {

namespace {

struct PosesOptions {
  std::string source;
  std::uint64_t drops = 0;
  std::string range;
  std::uint64_t seed = 1;
  int threads = 0;
  std::string method = "dynamic";
  PhysicsOptions physics;
  double damping_ratio = 0.05;
  double persistence = -1;  // fraction of L; < 0 = automatic
  bool full_settle = false;
  bool no_progress = false;
  std::string out_dir;
  bool json = false;
};

// A one-line progress bar with rate and ETA on stderr, redrawn a few times a second by its own thread. Only
// when stderr is a terminal, so logs and pipes stay clean.
class ProgressBar {
 public:
  ProgressBar(std::uint64_t total, bool enabled) : total_(total) {
    if (!enabled || total == 0 || !isatty(STDERR_FILENO)) return;
    thread_ = std::thread([this] { loop(); });
  }
  ~ProgressBar() {
    if (!thread_.joinable()) return;
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
    draw();
    std::fputs("\n", stderr);
  }
  std::atomic<std::uint64_t>* counter() { return &done_; }

 private:
  void loop() {
    std::unique_lock lock(mutex_);
    while (!wake_.wait_for(lock, std::chrono::milliseconds(250), [this] { return stop_; })) draw();
  }
  void draw() {
    const std::uint64_t done = done_.load(std::memory_order_relaxed);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double fraction = static_cast<double>(done) / static_cast<double>(total_);
    const double rate = seconds > 0 ? static_cast<double>(done) / seconds : 0;
    const double eta = rate > 0 ? static_cast<double>(total_ - done) / rate : 0;
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::fprintf(stderr, "\r[%s%s] %llu/%llu %5.1f%%  %.1f drops/s  ETA %02d:%02d:%02d ",
                 std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(kWidth - filled), ' ').c_str(),
                 static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_),
                 100 * fraction, rate, static_cast<int>(eta / 3600), static_cast<int>(eta / 60) % 60,
                 static_cast<int>(eta) % 60);
    std::fflush(stderr);
  }

  std::uint64_t total_;
  std::atomic<std::uint64_t> done_{0};
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

// Checks the text of an unsigned option before CLI11 converts it, which would wrap "-5" into a huge count.
CLI::Validator whole_number(std::uint64_t min) {
  return CLI::Validator(
      [min](std::string& text) -> std::string {
        const bool digits =
            !text.empty() && text.size() <= 19 && text.find_first_not_of("0123456789") == std::string::npos;
        if (digits && std::stoull(text) >= min) return {};
        return "must be a whole number >= " + std::to_string(min) + ", got '" + text + "'";
      },
      "INT >= " + std::to_string(min));
}

DropRange parse_range(const std::string& text) {
  const auto colon = text.find(':');
  const auto bad = [&] {
    return Error("option --range must be BEGIN:END with 0 <= BEGIN < END, got '" + text + "'");
  };
  if (colon == std::string::npos) throw bad();
  const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
  const auto parse = [&](const std::string& s) {
    if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos || s.size() > 19) throw bad();
    return static_cast<std::uint64_t>(std::stoull(s));
  };
  DropRange r{parse(a), parse(b)};
  if (r.begin >= r.end) throw bad();
  return r;
}

void emit(const PosesStudy& study, const std::string& out_dir, bool json) {
  const std::string text = poses_json(study);
  if (!out_dir.empty()) {
    write_file_atomically(out_dir + "/poses.json", text);
    write_file_atomically(out_dir + "/poses.csv", poses_csv(study));
  }
  if (json)
    std::cout << text;
  else
    std::cout << poses_table(study);
  const std::uint64_t unrested = study.tally.status_counts[2] + study.tally.status_counts[3];
  if (unrested > 0)
    std::cerr << "repose: warning: " << unrested
              << " drops did not come to rest within the limits (see status_counts; raise --max-time or "
                 "--max-steps)\n";
}

int run_poses(const PosesOptions& o, const CLI::App& sub) {
  const auto given = [&](const char* option) { return sub.count(option) > 0; };
  DropRange drops;
  if (given("--range") && given("--drops")) throw Error("give either -n/--drops or --range, not both");
  if (given("--range"))
    drops = parse_range(o.range);
  else if (given("--drops") && o.drops > 0)
    drops = {0, o.drops};
  else
    throw Error("poses: give the number of drops with -n N (N >= 1) or a drop range with --range BEGIN:END");
  check_positive("--density", o.physics.density);
  if (o.threads < 0)
    throw Error("option --threads must be >= 0 (0 = all cores), got " + std::to_string(o.threads));
  if (!std::isfinite(o.damping_ratio) || o.damping_ratio < 0)
    throw Error("option --damping-ratio must be a finite number >= 0, got " + num(o.damping_ratio));
  if (given("--persistence") && (!std::isfinite(o.persistence) || o.persistence < 0))
    throw Error("option --persistence must be a finite number >= 0, got " + num(o.persistence));

  EnsembleOptions options;
  options.seed = o.seed;
  options.drops = drops;
  options.method = parse_pose_method(o.method);
  options.threads = o.threads;
  options.decide_early = !o.full_settle;
  options.params = o.physics.params;
  options.params.gravity = standard_gravity(o.physics.unit_system());
  options.params.smooth = o.physics.smooth_mode();
  if (!given("--damping")) options.params.damping = 0;  // set from the ratio once the particle is known
  validate(options.params);
  if (!o.out_dir.empty()) ensure_output_directory(o.out_dir);

  const Particle particle = load_particle(o.source, o.physics.density);
  const bool smooth = options.params.smooth == SmoothMode::on ||
                      (options.params.smooth == SmoothMode::automatic && is_smooth_surface(particle));
  if (!given("--damping"))
    options.params.damping = o.damping_ratio * particle.mass.mass *
                             std::sqrt(options.params.gravity * std::pow(particle.length, 3));
  const double persistence =
      given("--persistence") ? o.persistence * particle.length : default_persistence(particle, smooth);
  const RestLandscape landscape = compute_rest_landscape(particle);
  PosesStudy study;
  study.source = particle.name;
  study.density = o.physics.density;
  study.length = particle.length;
  study.mass = particle.mass.mass;
  study.hull_faces = static_cast<int>(particle.hull.faces.size());
  study.smooth = smooth;
  study.params = options.params;
  study.decide_early = options.decide_early;
  study.catalog = catalog_rest_poses(particle, landscape, persistence);
  study.threads = o.threads > 0 ? o.threads : static_cast<int>(std::thread::hardware_concurrency());
  {
    ProgressBar bar(drops.size(), !o.no_progress);
    options.progress = bar.counter();
    study.tally = run_ensemble(particle, landscape, study.catalog, options);
  }
  emit(study, o.out_dir, o.json);
  return 0;
}

}  // namespace

Command add_poses_command(CLI::App& app) {
  auto o = std::make_shared<PosesOptions>();
  CLI::App* sub = app.add_subcommand(
      "poses",
      "Rest-pose statistics: drop the particle from uniformly random orientations, count where it rests");
  sub->add_option("particle", o->source, "Mesh file (STL, OBJ, PLY, OFF) or shape spec")->required();
  sub->add_option("-n,--drops", o->drops, "Number of drops (drop indices 0 .. N-1)")->check(whole_number(1));
  sub->add_option(
      "--range", o->range,
      "Run only drops BEGIN .. END-1 (for splitting a study; merge the results with repose merge)");
  sub->add_option("--seed", o->seed, "Seed: drop i's orientation depends only on (seed, i) (default 1)")
      ->check(whole_number(0));
  sub->add_option("--threads", o->threads, "Worker threads (default 0: all cores)");
  sub->add_option("--method", o->method,
                  "dynamic (the settling engine) or quasi-static (steepest descent of the COM height)")
      ->check(CLI::IsMember({"dynamic", "quasi-static"}));
  add_physics_options(*sub, o->physics,
                      "Damping coefficient C of Eq 4 (mass*length^2/time); overrides --damping-ratio");
  sub->add_option("--damping-ratio", o->damping_ratio,
                  "Damping as C / (m*sqrt(g*L^3)) (default 0.05; the paper's ellipsoid used 0.063)");
  sub->add_option("--persistence", o->persistence,
                  "Merge stable faces whose barrier is below this fraction of L into one pose (default 0, "
                  "0.01 for smooth particles)");
  sub->add_flag("--full-settle", o->full_settle,
                "Simulate every drop to rest instead of stopping once its energy cannot leave its pose");
  sub->add_flag("--no-progress", o->no_progress, "No progress bar (it is shown only on a terminal anyway)");
  sub->add_option("--out", o->out_dir, "Write poses.json and poses.csv into this directory");
  sub->add_flag("--json", o->json, "Print the JSON result instead of the table");
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
            emit(merged, o->out_dir, o->json);
            return 0;
          }};
}

}  // namespace repose::cli
