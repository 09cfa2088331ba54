// The Fortran example's run (examples/fortran/settle_grain.f90) through repose's C++ API, written for the
// example to compare with: status, face, steps, bounces, then time, world position and orientation.
//   fortran_reference OUT
#include <algorithm>
#include <cstdio>

#include "repose/model/particle.hpp"
#include "repose/sim/settle.hpp"

int main(int argc, char** argv) {
  using repose::Vec3;
  if (argc != 2) {
    std::fprintf(stderr, "usage: fortran_reference OUT\n");
    return 2;
  }
  repose::TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0},    {0.01, 0, 0},    {0.01, 0.02, 0},    {0, 0.02, 0},
                   {0, 0, 0.03}, {0.01, 0, 0.03}, {0.01, 0.02, 0.03}, {0, 0.02, 0.03}};
  mesh.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                    {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  const repose::Particle brick = repose::make_particle(mesh, "brick", 2650);

  // The hand-over as a C++ caller writes it: the lowest point's height above the floor, the motion.
  const Vec3 position(0.10, -0.20, 0.05);
  const repose::Quat q = repose::Quat(0.9, 0.3, -0.2, 0.1).normalized();
  const double floor = 0.01;
  double lowest = 1e300;
  for (const Vec3& v : brick.hull.vertices) lowest = std::min(lowest, (q * v).z());
  repose::SettleParams params;
  params.restitution = 0.4;
  params.friction = 0.5;
  params.drop_height = position.z() - floor + lowest;
  params.velocity = Vec3(0.15, 0.05, -0.4);
  params.spin = Vec3(2, -3, 1);
  repose::Settler settler(brick, params, q);
  const Vec3 offset = position - settler.sample().com;
  while (settler.step()) {
  }
  const repose::SettleResult r = settler.result();
  const Vec3 p = r.com + offset;

  std::FILE* out = std::fopen(argv[1], "w");
  if (out == nullptr) return 2;
  std::fprintf(out, "%d %d %ld %d\n", static_cast<int>(r.status), r.rest_face, r.steps, r.bounces);
  std::fprintf(out, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", r.time, p.x(), p.y(), p.z(),
               r.orientation.w(), r.orientation.x(), r.orientation.y(), r.orientation.z());
  // The frictional ledger's terms and counts, as repose_settler_friction_account gives them.
  const repose::FrictionalAccount f = r.frictional.value_or(repose::FrictionalAccount{});
  std::fprintf(out, "%.17g %.17g %.17g %.17g %d %d %d\n", r.friction_work, f.normal_work, f.drift_corrections,
               f.repositioning, f.zeno_captures, f.handovers_stalled + f.handovers_timed_out, r.painleve);
  return std::fclose(out) == 0 ? 0 : 2;
}
