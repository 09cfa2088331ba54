// Internal: what every phase of a run shares — the particle and parameters, the tolerances, the time and
// the pose, and the recorder of what happened. A phase owns the rest of its state (phases/*.hpp); the
// engine (engine.hpp) holds the run and the current phase. The Particle is shared read-only by every run
// (MuJoCo's mjModel / mjData split); a Run is one run's.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "body/dynamics.hpp"
#include "repose/sim/settle.hpp"
#include "tolerances.hpp"
#include "wall/near_wall.hpp"
#include "wall/surface_model.hpp"

namespace repose::sim {

/// What a run reports about its course (SettleResult): the contact-type timeline, the impacts, the depth.
struct Recorder {
  std::vector<Phase> phases;  ///< the contact-type timeline; its last entry is the current type
  std::vector<ImpactRecord> impacts;
  int bounces = 0;
  double max_penetration = 0;
  double energy_start = 0;
  long unconverged = 0;     ///< paper steps whose pseudo-time iteration hit max_iterations
  double stable_time = -1;  ///< when the paper's stability test first passed
  // The frictional contact phase's ledger (SettleResult).
  double friction_work = 0;
  double damping_work = 0;
  double sliding_distance = 0;
  int painleve = 0;
  FrictionalAccount account;      ///< the rest of the ledger and the fallbacks (finite friction)
  double handover_energy = NAN;   ///< the mechanical energy at a hand-over to the paper's phase
  double frictional_start = NAN;  ///< when the frictional contact phase first began (its time bound's start)

  ContactType type() const { return phases.empty() ? ContactType::free_fall : phases.back().contact; }
  /// A new contact type from time t (nothing if it is the current one).
  void set_type(ContactType type, double t) {
    if (!phases.empty() && phases.back().contact == type) return;
    if (!phases.empty()) phases.back().t1 = t;
    phases.push_back({type, t, t});
  }
  void note_depth(double depth) { max_penetration = std::max(max_penetration, depth); }
};

struct Run {
  Run(const Particle& p, const SettleParams& prm, const Quat& orientation);

  const Particle& particle;
  const SettleParams params;
  const Body body;  ///< mass, inertia, gravity, damping
  const Tolerances tol;
  const SurfaceModel surface;  ///< how it meets the wall: polyhedral or smooth (wall/surface_model.hpp)
  const bool trace;            ///< debugging aid: one line per contact update on stderr (REPOSE_TRACE set)
  const double hull_radius;    ///< largest distance of a hull vertex from the centre of mass
  /// The hull vertices near the wall by walks of the hull's edge graph (scratch and the last lowest vertex:
  /// no part of the run's result, hence usable from a phase's const queries).
  mutable NearWall near_wall;

  double t = 0;
  double limit = INFINITY;  ///< advance_to(): no step goes past this time
  long steps = 0;
  Quat q = Quat::Identity();  ///< body → world
  Vec3 com = Vec3::Zero();    ///< the centre of mass, world frame
  Recorder record;

  double potential_energy() const { return body.mass * params.gravity * com.z(); }
  /// The lowest hull vertex at orientation qq (the first of equals in index order), among the vertices a
  /// walk of the hull's edge graph finds near the lowest (wall/near_wall.hpp), not a scan of the hull.
  int lowest_vertex(const Quat& qq) const {
    const auto& verts = particle.hull.vertices;
    int lowest = 0;
    double lowest_z = INFINITY;
    for (int k : near_wall.near_lowest(qq, tol.event)) {
      const double zk = (qq * verts[static_cast<std::size_t>(k)]).z();
      if (zk < lowest_z) {
        lowest_z = zk;
        lowest = k;
      }
    }
    return lowest;
  }
  /// Its height relative to the centre of mass (negative: below it).
  double lowest_offset(const Quat& qq) const {
    return (qq * particle.hull.vertices[static_cast<std::size_t>(lowest_vertex(qq))]).z();
  }
};

}  // namespace repose::sim
