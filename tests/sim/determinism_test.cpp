// Determinism: the final states of a fixed batch of drops hash to a pinned value.
//
// The engine is deterministic by construction (no threads inside a run, no time- or address-dependent
// choices) and the build keeps floating point reproducible: no -ffast-math, and -ffp-contract=off so the
// compiler never fuses a*b+c into an FMA on one machine and not on another (cmake/ReposeOptions.cmake, and
// PUBLIC on the library target so consumers compiling its headers get it too). This test pins the bits: any
// change to the engine's arithmetic changes the hash. If that change is intended, update kGolden to the value
// the failure prints and say why in the commit message.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <tuple>

#include "repose/poses/ensemble.hpp"
#include "repose/poses/landscape.hpp"
#include "repose/poses/sampling.hpp"
#include "repose/sim/settle.hpp"

namespace {

using namespace repose;

// FNV-1a, 64 bit, over the exact bytes of each value.
struct Fnv1a {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 0x100000001b3ULL;
  }
  void number(double x) { bytes(&x, sizeof x); }
  void integer(std::int64_t x) { bytes(&x, sizeof x); }
};

std::uint64_t batch_hash(std::uint64_t drops_per_shape, Integrator integrator) {
  Fnv1a hash;
  const char* specs[] = {"box:x=1,y=2,z=3", "tetrahedron:edge=1", "cylinder:r=0.5,h=0.4,n=32",
                         "ellipsoid:a=0.625,b=0.5,c=0.285,n=6", "irregular:seed=3"};
  for (const char* spec : specs) {
    const Particle particle = load_particle(spec, 1000.0);
    SettleParams params;
    params.integrator = integrator;
    params.damping = 0.3 * particle.mass.mass * std::sqrt(params.gravity * std::pow(particle.length, 3));
    for (std::uint64_t i = 0; i < drops_per_shape; ++i) {
      params.drop_height = (i % 4) * 0.1 * particle.length;
      const SettleResult r = settle(particle, params, drop_orientation(2021, i));
      for (double c : {r.orientation.w(), r.orientation.x(), r.orientation.y(), r.orientation.z(), r.com.x(),
                       r.com.y(), r.com.z(), r.time, r.energy_end})
        hash.number(c);
      hash.integer(r.steps);
      hash.integer(r.rest_face);
      hash.integer(static_cast<int>(r.status));
    }
  }
  return hash.h;
}

// 30 drops per shape in the optimised build; the first 3 per shape in every build, the sanitizer build
// included (150 drops take minutes there): the same bits from -O1 with sanitizers as from -O2. One pair per
// integrator: the adaptive one (the default) and the paper's fixed step.
constexpr std::uint64_t kGolden = 0x5709cdd2adcb1977;
constexpr std::uint64_t kGoldenFew = 0xdfe5bde1c144e6ce;
constexpr std::uint64_t kGoldenPaper = 0x5a8a1cf2630ca349;
constexpr std::uint64_t kGoldenPaperFew = 0x29068c8fb2e90ef0;

TEST(Determinism, FixedBatchHashesToTheGoldenValue) {
  for (const auto& [integrator, golden, golden_few] :
       {std::tuple{Integrator::adaptive, kGolden, kGoldenFew},
        std::tuple{Integrator::paper, kGoldenPaper, kGoldenPaperFew}}) {
    const std::uint64_t few = batch_hash(3, integrator);
    EXPECT_EQ(few, golden_few) << to_string(integrator) << ": new hash of 3 drops per shape: 0x" << std::hex
                               << few;
    EXPECT_EQ(batch_hash(3, integrator), few) << to_string(integrator) << ": two runs in one process differ";
#ifdef NDEBUG
    const std::uint64_t h = batch_hash(30, integrator);
    EXPECT_EQ(h, golden) << to_string(integrator) << ": new hash: 0x" << std::hex << h;
#endif
  }
}

// The multithreaded batch gives the same tally bits with 1 and 2 threads, also under the sanitizers.
TEST(Determinism, ThreadCountDoesNotChangeTheTally) {
  const Particle particle = load_particle("irregular:seed=4", 1.0);
  const RestLandscape landscape = compute_rest_landscape(particle);
  const RestPoseCatalog catalog = catalog_rest_poses(particle, landscape, 0);
  EnsembleOptions o;
  o.seed = 77;
  o.drops = {0, 24};
  EnsembleTally t[2];
  for (int threads : {1, 2}) {
    o.threads = threads;
    t[threads - 1] = run_ensemble(particle, landscape, catalog, o);
  }
  EXPECT_EQ(t[0].steps, t[1].steps);
  for (std::size_t p = 0; p < catalog.poses.size(); ++p) {
    EXPECT_EQ(t[0].poses[p].count, t[1].poses[p].count);
    EXPECT_EQ(t[0].poses[p].orientation.coeffs(), t[1].poses[p].orientation.coeffs());
  }
}

}  // namespace
