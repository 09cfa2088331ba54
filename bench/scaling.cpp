// How the cost per settle grows with the hull (issue 12: "from ~1,000 to ~100,000 hull vertices the cost per
// settle grows at most 10×"): the bumpy ellipsoid of bench/bumpy_ellipsoid.hpp at geodesic frequencies 10,
// 32 and 100 (about 1,000, 10,000 and 100,000 hull vertices; the same shape, finer), each dropped as
// `repose poses` drops it (repose::simulate_drop with the `repose poses` defaults: seed 1, damping ratio
// 0.05, decide early), one thread, SI units (m, kg, s; density 1000 kg/m³). Prints per mesh the hull size,
// the set-up time (hull, landscape, catalogue: paid once per particle) and the time per settle.
//
//   repose_scaling [--drops N] [--frequency F]... [--full-settle]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <repose/poses/ensemble.hpp>
#include <repose/poses/landscape.hpp>
#include <repose/poses/study.hpp>
#include <repose/repose.hpp>
#include <string>
#include <vector>

#include "bumpy_ellipsoid.hpp"

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

int main(int argc, char** argv) {
  int drops = 40;
  bool full_settle = false;
  std::vector<int> frequencies;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--drops" && i + 1 < argc) {
      drops = std::atoi(argv[++i]);
    } else if (a == "--frequency" && i + 1 < argc) {
      frequencies.push_back(std::atoi(argv[++i]));
    } else if (a == "--full-settle") {
      full_settle = true;
    } else {
      std::fprintf(stderr, "usage: repose_scaling [--drops N] [--frequency F]... [--full-settle]\n");
      return 2;
    }
  }
  if (frequencies.empty()) frequencies = {10, 32, 100};
  for (int f : frequencies)
    if (f < 1 || f > 300 || drops < 1) {
      std::fprintf(stderr, "repose_scaling: --frequency must be in [1, 300] and --drops >= 1\n");
      return 2;
    }
  std::printf("| frequency | triangles | hull vertices | set-up s | drops | ms/settle | steps/settle |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int f : frequencies) {
    auto t0 = std::chrono::steady_clock::now();
    const repose::TriangleMesh mesh = bumpy_ellipsoid(f);
    const repose::Particle particle = repose::make_particle(mesh, "bumpy-ellipsoid", 1000.0);
    const repose::RestLandscape landscape = repose::compute_rest_landscape(particle);
    repose::StudySettings settings;
    settings.density = 1000.0;
    settings.decide_early = !full_settle;
    const repose::PosesStudy study = repose::prepare_study(particle, landscape, settings);
    const repose::EnsembleOptions options = repose::ensemble_options(study, {0, 0}, 1);
    const double setup = seconds_since(t0);
    long steps = 0;
    t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < drops; ++i)
      steps +=
          repose::simulate_drop(particle, landscape, study.catalog, options, static_cast<std::uint64_t>(i))
              .steps;
    const double run = seconds_since(t0);
    std::printf("| %d | %zu | %zu | %.2f | %d | %.3f | %.0f |\n", f, mesh.triangles.size(),
                particle.hull.vertices.size(), setup, drops, 1e3 * run / drops,
                static_cast<double>(steps) / drops);
    std::fflush(stdout);
  }
  return 0;
}
