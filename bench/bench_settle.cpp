// Settles per second per core, for the shapes the rest-pose statistics are run on.
//
// Each benchmark iteration is one drop on one thread, exactly as `repose poses` runs it (drop i of seed 1:
// uniform random orientation, from rest touching the wall, damping ratio 0.05). Two variants:
//   settle/...   every drop simulated to rest (`repose poses --full-settle`)
//   poses/...    the `repose poses` default: a drop stops once its energy cannot leave its pose
// Run:  build/release/bench/repose_bench   (figures and machine in docs/performance.md)
#include <benchmark/benchmark.h>

#include <cmath>
#include <repose/poses/ensemble.hpp>
#include <repose/poses/landscape.hpp>
#include <repose/poses/rest_poses.hpp>
#include <repose/repose.hpp>

namespace {

void drops(benchmark::State& state, const char* spec, bool decide_early) {
  const repose::Particle particle = repose::load_particle(spec, 1.0);
  const repose::RestLandscape landscape = repose::compute_rest_landscape(particle);
  const bool smooth = repose::is_smooth_surface(particle);
  const repose::RestPoseCatalog catalog =
      repose::catalog_rest_poses(particle, landscape, repose::default_persistence(particle, smooth));
  repose::EnsembleOptions options;
  options.seed = 1;
  options.threads = 1;
  options.decide_early = decide_early;
  options.params.damping =
      0.05 * particle.mass.mass * std::sqrt(options.params.gravity * std::pow(particle.length, 3));
  std::uint64_t next = 0;
  std::uint64_t steps = 0;
  for (auto _ : state) {
    const repose::DropOutcome outcome = repose::simulate_drop(particle, landscape, catalog, options, next);
    steps += static_cast<std::uint64_t>(outcome.steps);
    ++next;
  }
  state.counters["settles/s"] = benchmark::Counter(static_cast<double>(next), benchmark::Counter::kIsRate);
  state.counters["steps/settle"] = static_cast<double>(steps) / static_cast<double>(next);
  state.counters["triangles"] = static_cast<double>(particle.mesh.triangles.size());
}

void landscape(benchmark::State& state, const char* spec) {
  const repose::Particle particle = repose::load_particle(spec, 1.0);
  for (auto _ : state) benchmark::DoNotOptimize(repose::compute_rest_landscape(particle));
  state.counters["hull_faces"] = static_cast<double>(particle.hull.faces.size());
}

// The shapes named in the statistics issue: cube, tetrahedron, 64-segment cylinder, ellipsoid with about
// 2,000 triangles (geodesic frequency 10), irregular particle with about 10,000 triangles (frequency 22).
// Drops cost very different amounts (a near-balanced start tips slowly), so both variants run the same drops,
// 0 .. N-1, with N fixed per shape.
#define REPOSE_SHAPES(X)                                       \
  X(cube, "box:x=1,y=1,z=1", 2000)                             \
  X(tetrahedron, "tetrahedron:edge=1", 2000)                   \
  X(cylinder64, "cylinder:r=0.5,h=1,n=64", 400)                \
  X(ellipsoid2000, "ellipsoid:a=0.625,b=0.5,c=0.285,n=10", 16) \
  X(irregular10k, "irregular:seed=1,n=22", 200)

#define REPOSE_BENCH(name, spec, drops_per_run)        \
  BENCHMARK_CAPTURE(drops, settle_##name, spec, false) \
      ->Unit(benchmark::kMillisecond)                  \
      ->Iterations(drops_per_run)                      \
      ->UseRealTime();                                 \
  BENCHMARK_CAPTURE(drops, poses_##name, spec, true)   \
      ->Unit(benchmark::kMillisecond)                  \
      ->Iterations(drops_per_run)                      \
      ->UseRealTime();                                 \
  BENCHMARK_CAPTURE(landscape, landscape_##name, spec)->Unit(benchmark::kMillisecond);
REPOSE_SHAPES(REPOSE_BENCH)

}  // namespace

BENCHMARK_MAIN();
