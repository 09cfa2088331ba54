// A program embedding repose, as a DEM code would: build the particle model once, then settle it from an
// orientation, either in one call or step by step.
#include <cmath>
#include <cstdio>
#include <repose/repose.hpp>

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
  const bool ok = once.status == repose::Status::rest &&
                  std::abs(once.com.z() - std::sqrt(2.0 / 3.0) / 4) < 1e-6 && stepped.com == once.com;
  return ok ? 0 : 1;
}
