// Settles per second for built-in shapes from a fixed set of orientations.
// Run: build/release/bench/repose_bench
#include <benchmark/benchmark.h>

#include <repose/repose.hpp>
#include <repose/sim/settle.hpp>

namespace {

void settle_shape(benchmark::State& state, const char* spec) {
  const repose::Particle particle = repose::load_particle(spec, 1.0);
  repose::SettleParams params;
  long i = 0;
  for (auto _ : state) {
    // A deterministic spread of tilted starts.
    const double angle = 0.3 + 0.1 * static_cast<double>(i % 11);
    const repose::Vec3 axis(std::cos(0.7 * i), std::sin(0.7 * i), 0.3);
    const auto r =
        repose::settle(particle, params, repose::Quat(Eigen::AngleAxisd(angle, axis.normalized())));
    benchmark::DoNotOptimize(r.com);
    ++i;
  }
  state.counters["settles/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK_CAPTURE(settle_shape, cube, "box:x=1,y=1,z=1")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(settle_shape, tetrahedron, "tetrahedron:edge=1")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(settle_shape, cylinder64, "cylinder:r=0.5,h=1,n=64")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(settle_shape, ellipsoid2000, "ellipsoid:a=0.625,b=0.5,c=0.285,n=10")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(settle_shape, irregular, "irregular:seed=1")->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
