// Internal: the adaptive contact step's vertices packed for the event tests made at every instant of its
// event search (contact_adaptive_step.cpp), and the pick of those that can decide a search over an interval
// (contact_step_events.cpp).
#pragma once

#include <vector>

#include "repose/geometry/types.hpp"

namespace repose::sim {

// Their offsets from the support point (body frame) and their event levels, all fixed within the step
// (enter: the band's level for a vertex that can enter it, else -inf). Contiguous, so the tests read no
// scattered per-vertex state: on fine hulls they are a third of a drop's time.
struct StepVertices {
  std::vector<Vec3> offset;
  std::vector<double> distance;  // |offset|
  std::vector<double> pierce, rise, enter;
  void clear() {
    offset.clear();
    distance.clear();
    pierce.clear();
    rise.clear();
    enter.clear();
  }
};

/// Of the packed vertices `from` (heights base + r3·offset at the interval's start), into `out`, those that
/// can decide an event search over an interval in which the particle turns by at most `turn` (rad): those
/// that can reach one of their events in it, and those that can hold the smallest margin anywhere in it (the
/// event margin over them is the margin over `from`, to the bit). A vertex whose margin m changes by at most
/// r = turn·d in the interval can be neither where m − r exceeds every other vertex's m + r and zero (with
/// the event tolerance `slack`). `scratch` holds the lower bounds m − r.
void select_event_vertices(const StepVertices& from, const Vec3& r3, double base, double turn, double slack,
                           std::vector<double>& scratch, StepVertices& out);

}  // namespace repose::sim
