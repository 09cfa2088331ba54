// A program embedding repose, as a DEM code would: build the particle model once, then settle it from an
// orientation, either in one call or step by step; then a small rest-pose job of two particles.
#include <cmath>
#include <cstdio>
#include <memory>
#include <repose/repose.hpp>
#ifdef CONSUMER_HAS_MPI
#include <repose/campaign/mpi_runner.hpp>
#endif

int main() {
  // The paper's tetrahedron (CGS units: cm, g, s).
  const repose::Particle tet = repose::load_particle("tetrahedron:edge=1", 1.2);
  repose::SettleParams params;
  params.gravity = repose::standard_gravity(repose::UnitSystem::cgs);
  const repose::Quat start = repose::parse_orientation("axis-angle:1,0.3,0,2.5");

  // One call.
  const repose::SettleResult once = repose::settle(tet, params, start);

  // Step by step: the caller owns the loop.
  repose::Settler settler(tet, params, start);
  long steps = 0;
  while (settler.step()) ++steps;
  const repose::SettleResult stepped = settler.result();

  std::printf("%s after %.6f s, COM height %.7f cm (%ld steps)\n", repose::to_string(once.status), once.time,
              once.com.z(), steps);
  // Resting flush on a face, the COM is at a quarter of the height sqrt(2/3).
  bool ok = once.status == repose::Status::rest && std::abs(once.com.z() - std::sqrt(2.0 / 3.0) / 4) < 1e-6 &&
            stepped.com == once.com;

  // A rest-pose job over two particles, on this process, or across ranks when started by mpirun.
  std::unique_ptr<repose::WorkRunner> runner = std::make_unique<repose::LocalRunner>();
#ifdef CONSUMER_HAS_MPI
  if (repose::launched_by_mpi()) runner = repose::make_mpi_runner();
#endif
  repose::CampaignOptions job;
  job.drops = {0, 200};
  const auto studies = repose::run_campaign(
      [] {
        return repose::resolve_particles({"tetrahedron:edge=1", "box:x=1,y=1,z=1"});
      },
      job, *runner);
  if (runner->is_root()) {
    ok = ok && studies.size() == 2 && studies[0].tally.drops() == 200 && studies[0].catalog.poses.size() == 4;
    std::printf("tetrahedron: %zu poses over %llu drops\n", studies[0].catalog.poses.size(),
                static_cast<unsigned long long>(studies[0].tally.drops()));
  }
  return ok ? 0 : 1;
}
