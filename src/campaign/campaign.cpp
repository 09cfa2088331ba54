// Running a job of work items and merging their results: see campaign.hpp.
#include "repose/campaign/campaign.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>

#include "repose/error.hpp"
#include "repose/model/particle.hpp"
#include "repose/output/files.hpp"
#include "repose/poses/ensemble.hpp"
#include "repose/poses/landscape.hpp"

namespace repose {

namespace {

namespace fs = std::filesystem;

// What a rank needs to run drops of one particle.
struct ParticleModel {
  Particle particle;
  RestLandscape landscape;
  PosesStudy header;  // settings and catalogue, nothing counted
};

std::unique_ptr<ParticleModel> load_model(const CampaignParticle& p, const StudySettings& settings) {
  auto model = std::make_unique<ParticleModel>();
  model->particle = load_particle(p.source, settings.density, p.mesh);
  model->landscape = compute_rest_landscape(model->particle);
  model->header = prepare_study(model->particle, model->landscape, settings);
  return model;
}

std::string describe(const DropRange& r) {
  std::string text = "[";
  text += std::to_string(r.begin) + ", " + std::to_string(r.end) + ")";
  return text;
}

// The root's view of the job: every particle's study so far, what is left, and the checkpoint.
struct RootState {
  std::vector<PosesStudy> studies;
  std::vector<std::vector<DropRange>> remaining;
  std::vector<double> cost_per_drop;
  // One particle's model, kept for the root's own work so that a single scan is not loaded twice (a
  // 200,000-triangle scan's set-up is most of a quasi-static study): the costliest per drop, whose items the
  // plan puts first. The others are loaded again when run, so that a library of scans is never all in memory.
  std::unique_ptr<ParticleModel> kept_model;
  std::uint32_t kept_index = 0;
};

// One particle's part of the root's preparation: its study so far (from the checkpoint) and what is left.
// Returns the model.
std::unique_ptr<ParticleModel> prepare_particle(const CampaignParticle& p, const CampaignOptions& options,
                                                PosesStudy& study, std::vector<DropRange>& left,
                                                double& cost_per_drop) {
  std::unique_ptr<ParticleModel> model = load_model(p, options.settings);
  study = model->header;
  left = {options.drops};
  const std::string path = options.checkpoint_dir.empty() ? "" : checkpoint_path(options.checkpoint_dir, p);
  std::error_code ec;
  if (!path.empty() && fs::exists(path, ec)) {
    const PosesStudy saved = parse_poses_json(read_text_file(path), path);
    try {
      study = merge_studies(study, saved);
      left = remaining_ranges(options.drops, saved.tally.ranges);
    } catch (const Error& e) {
      throw Error(path + ": checkpoint of a different run (" + e.what() +
                  "); delete it to start over, or use another output directory");
    }
  }
  // The engine's cost per step grows with the hull's size; smooth particles also take more steps.
  const double hull = static_cast<double>(model->particle.hull.vertices.size());
  cost_per_drop = hull * (model->header.smooth ? 4.0 : 1.0);
  return model;
}

// The particles are prepared in parallel (a library of large scans loads much faster); the error reported is
// that of the first bad particle in input order, whatever the threads did.
RootState prepare_root(const std::vector<CampaignParticle>& particles, const CampaignOptions& options) {
  const std::size_t n = particles.size();
  RootState state;
  state.studies.resize(n);
  state.remaining.resize(n);
  state.cost_per_drop.resize(n);
  std::vector<std::exception_ptr> errors(n);
  std::mutex keeping;
  tbb::task_arena arena(options.threads > 0 ? options.threads : available_cores());
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
      try {
        std::unique_ptr<ParticleModel> model = prepare_particle(particles[i], options, state.studies[i],
                                                                state.remaining[i], state.cost_per_drop[i]);
        const auto index = static_cast<std::uint32_t>(i);
        const std::lock_guard lock(keeping);
        const double kept_cost = state.kept_model ? state.cost_per_drop[state.kept_index] : -1.0;
        if (state.cost_per_drop[i] > kept_cost ||
            (state.cost_per_drop[i] == kept_cost && index < state.kept_index)) {
          state.kept_model = std::move(model);
          state.kept_index = index;
        }
      } catch (...) {
        errors[i] = std::current_exception();
      }
    });
  });
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
  return state;
}

}  // namespace

std::string checkpoint_path(const std::string& checkpoint_dir, const CampaignParticle& particle) {
  return (fs::path(checkpoint_dir) / (particle.name + ".json")).string();
}

std::vector<PosesStudy> run_campaign(const std::function<std::vector<CampaignParticle>()>& particles_on_root,
                                     const CampaignOptions& options, WorkRunner& runner) {
  using nlohmann::json;
  // The root resolves the particles, loads each once (so that bad input is reported before any work) and
  // reads the checkpoint; the other ranks learn the particle list.
  std::vector<CampaignParticle> particles;
  RootState state;
  std::vector<WorkItem> items;
  const std::string list = prepare_on_root(runner, [&] {
    particles = particles_on_root();
    if (options.drops.size() == 0) throw Error("no drops to run");
    state = prepare_root(particles, options);
    if (!options.checkpoint_dir.empty()) ensure_output_directory(options.checkpoint_dir);
    const std::uint64_t chunk =
        options.chunk ? options.chunk : auto_chunk(options.drops.size(), options.threads);
    items = plan_work(state.remaining, state.cost_per_drop, chunk);
    json j = json::array();
    for (const CampaignParticle& p : particles)
      j.push_back({p.name, p.source, p.mesh.scale, to_string(p.mesh.inertia), p.mesh.repair,
                   p.mesh.largest_component,
                   p.mesh.center_of_mass
                       ? json(std::vector<double>{p.mesh.center_of_mass->x(), p.mesh.center_of_mass->y(),
                                                  p.mesh.center_of_mass->z()})
                       : json(nullptr)});
    return j.dump();
  });
  if (!runner.is_root())
    for (const json& p : json::parse(list)) {
      MeshOptions mesh{p.at(2).get<double>(), parse_inertia_model(p.at(3).get<std::string>()),
                       p.at(4).get<bool>(), p.at(5).get<bool>(), std::nullopt};
      if (!p.at(6).is_null()) {
        const auto c = p.at(6).get<std::vector<double>>();
        mesh.center_of_mass = Vec3(c.at(0), c.at(1), c.at(2));
      }
      particles.push_back({p.at(0).get<std::string>(), p.at(1).get<std::string>(), mesh});
    }

  const int threads = options.threads > 0 ? options.threads : available_cores();
  // Any rank: the model of a particle. The last one is kept, since items of one particle mostly follow each
  // other.
  std::uint32_t cached_index = state.kept_index;
  std::unique_ptr<ParticleModel> cached = std::move(state.kept_model);  // the root's, or none
  const auto model_of = [&](std::uint32_t index) -> const ParticleModel& {
    if (index >= particles.size()) throw Error("work item for an unknown particle");
    if (!cached || cached_index != index) {
      cached.reset();
      cached = load_model(particles[index], options.settings);
      cached_index = index;
    }
    return *cached;
  };
  // Runs drops of one particle. `finish`: simulate each pose's first drop to rest (see below).
  const auto run_drops = [&](const WorkItem& item, std::atomic<std::uint64_t>* progress, bool finish) {
    const ParticleModel& model = model_of(item.particle);
    PosesStudy part = model.header;
    EnsembleOptions ensemble = ensemble_options(part, item.drops, options.threads);
    ensemble.progress = progress;
    ensemble.finish_representatives = finish;
    part.tally = run_ensemble(model.particle, model.landscape, part.catalog, ensemble);
    part.threads = threads;
    return poses_json(part);
  };

  // Phase 1, the drops. Root: merge each item's result and save the checkpoint.
  const WorkRunner::Absorb absorb = [&](const WorkItem& item, const std::string& result) {
    const CampaignParticle& p = particles.at(item.particle);
    const std::string name = p.source + " drops " + describe(item.drops);
    const PosesStudy part = parse_poses_json(result, name);
    try {
      state.studies[item.particle] = merge_studies(state.studies[item.particle], part);
    } catch (const Error& e) {
      throw Error(name + ": " + e.what() + " (ranks computed different results: same binary everywhere?)");
    }
    if (!options.checkpoint_dir.empty()) {
      write_file_atomically(checkpoint_path(options.checkpoint_dir, p),
                            poses_json(state.studies[item.particle]), FileDurability::synced);
      if (options.kept) options.kept->fetch_add(item.drops.size());
    }
  };
  if (runner.is_root()) {
    std::uint64_t left = 0;
    for (const WorkItem& item : items) left += item.drops.size();
    if (options.kept && !options.checkpoint_dir.empty())
      options.kept->store(options.drops.size() * particles.size() - left);
    if (options.on_start) options.on_start(left, state.studies);
  }
  runner.run(
      items,
      [&](const WorkItem& item, std::atomic<std::uint64_t>* progress) {
        return run_drops(item, progress, false);
      },
      absorb, options.progress);

  // Phase 2, the representatives. A pose is shown by the final orientation of its first drop, but drops
  // stop once their pose is decided; only the first drop of each pose over the whole job needs simulating
  // to rest, one work item each (finishing them inside every item would cost a full settle per pose per
  // item).
  std::vector<WorkItem> representatives;
  if (runner.is_root())
    for (std::uint32_t p = 0; p < particles.size(); ++p)
      for (const PoseTally& t : state.studies[p].tally.poses)
        if (t.count > 0 && !t.settled) representatives.push_back({p, {t.first_drop, t.first_drop + 1}});
  const WorkRunner::Absorb settle = [&](const WorkItem& item, const std::string& result) {
    const PosesStudy one = parse_poses_json(result, particles.at(item.particle).source + " representative");
    EnsembleTally& tally = state.studies[item.particle].tally;
    tally.seconds += one.tally.seconds;  // the time it took counts towards the study's
    for (std::size_t q = 0; q < one.tally.poses.size() && q < tally.poses.size(); ++q) {
      if (one.tally.poses[q].count == 0) continue;
      if (tally.poses[q].first_drop != item.drops.begin)
        throw Error(particles[item.particle].source + ": drop " + std::to_string(item.drops.begin) +
                    " ended in another pose when run again");
      tally.poses[q].orientation = one.tally.poses[q].orientation;
      tally.poses[q].settled = true;
    }
  };
  runner.run(
      representatives,
      [&](const WorkItem& item, std::atomic<std::uint64_t>*) { return run_drops(item, nullptr, true); },
      settle, nullptr);
  if (!runner.is_root()) return {};
  if (options.on_complete) options.on_complete(state.studies);

  if (!options.checkpoint_dir.empty()) {
    std::error_code ec;
    for (const CampaignParticle& p : particles) {
      fs::remove(checkpoint_path(options.checkpoint_dir, p), ec);
      remove_temporaries(checkpoint_path(options.checkpoint_dir, p));
    }
    fs::remove(options.checkpoint_dir, ec);  // only if empty
  }
  return std::move(state.studies);
}

}  // namespace repose
