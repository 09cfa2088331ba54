// ParaView output of a settling run: an animation of the particle falling, rotating and coming to rest, like
// the paper's S1-S4 videos.
//
// A VtkRecorder is the observer of a run. Every frame it writes two VTK XML PolyData files (format version
// 0.1, ASCII, byte_order LittleEndian) into its output directory; finish() writes the final frame and the
// collections that ParaView opens as time series:
//
//   particle_NNNNN.vtp  the particle surface in WORLD coordinates (x = orientation·body_vertex + com), the
//                       mesh triangles as Polys; point data "height" = z of each vertex above the wall.
//   markers_NNNNN.vtp   Verts: the centre of mass and the contact points (convex-hull vertices with world
//                       z ≤ contact_threshold·L); point data "kind" (Int32): 0 = centre of mass,
//                       1 = contact point. The centre of mass is always point 0.
//   wall.vtp            written once, with the first frame: the wall z = 0 as one square quad centred under
//                       the particle's initial centre of mass, side max(4·L, 4·R) with R the largest
//                       distance of a surface vertex from the centre of mass.
//   settling.pvd        VTK Collection listing every particle_NNNNN.vtp with its time (timestep="t").
//   markers.pvd         the same for markers_NNNNN.vtp.
// Each .vtp also carries its time as field data "TimeValue". NNNNN is the frame index, from 0, zero-padded
// to five digits (more digits past 99999). Lengths are in the particle's length unit and times in the run's
// time unit (whatever unit system SettleParams::gravity fixes). Coordinates are written with 9 significant
// digits and times with the shortest representation that reads back exactly, all locale-independent. Every
// file is written with write_file_atomically; the .pvd files are written last, by finish(), so they only
// ever list complete frames. Frames are never deleted: use a fresh directory per run (stale frames left by
// an earlier, longer run in the same directory are not listed in the new .pvd files).
//
// Frame cadence: a frame at the first sample (t = 0 for a run from the start), then at every sample with
// t ≥ t_last + frame_dt, where t_last is the time of the last frame written (frame_dt = 0: every sample with
// a time later than the last frame's), and always the final state, written by finish() from the
// SettleResult's pose at result.time (it replaces the last frame if that frame is already at result.time).
// With max_frames > 0 at most max_frames frames are written: once max_frames − 1 frames exist, further
// samples are skipped and the last slot is kept for the final state.
//
// Usage:
//   VtkRecorder vtk(particle, "out/vtk", /*frame_dt=*/0.01);
//   SettleResult r = settle(particle, params, q0, vtk.observer());   // or std::ref(vtk)
//   vtk.finish(r);
// A VtkRecorder is neither copyable nor movable: the observer refers to it, and a copy inside a
// std::function would record into the copy.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "repose/model/particle.hpp"
#include "repose/sim/settle.hpp"

namespace repose {

class VtkRecorder {
 public:
  /// Records `particle` (which must outlive the recorder) into `dir`, created if needed. `frame_dt` ≥ 0 is
  /// the minimum time between frames (0 = every sample); `max_frames` is 0 (no limit) or ≥ 2;
  /// `contact_threshold` > 0 is the contact distance as a fraction of L (use SettleParams::
  /// contact_threshold to mark the points the engine treats as contacts). Throws repose::Error for an
  /// invalid argument or a directory that cannot be created or written.
  VtkRecorder(const Particle& particle, std::string dir, double frame_dt = 0, int max_frames = 0,
              double contact_threshold = 0.05);

  VtkRecorder(const VtkRecorder&) = delete;
  VtkRecorder& operator=(const VtkRecorder&) = delete;

  /// Observes one sample: writes a frame if the cadence rule says so. Throws repose::Error if a file
  /// cannot be written or if called after finish().
  void operator()(const Sample& sample);

  /// An observer for settle() / Settler::run that forwards to this recorder.
  std::function<void(const Sample&)> observer();

  /// Writes the final frame (the rest pose, or wherever the run stopped) and then settling.pvd and
  /// markers.pvd. Call once, after the run. Throws repose::Error if a file cannot be written or if called
  /// twice.
  void finish(const SettleResult& result);

  /// Number of frames written so far.
  int frames() const { return static_cast<int>(times_.size()); }
  /// Times of the frames written so far, increasing.
  const std::vector<double>& frame_times() const { return times_; }
  const std::string& directory() const { return dir_; }

 private:
  void write_frame(int index, double t, const Quat& orientation, const Vec3& com);
  void write_wall(const Vec3& com);

  const Particle& particle_;
  std::string dir_;
  double frame_dt_;
  int max_frames_;
  double contact_threshold_;
  std::string polys_;  // the particle's Polys element, the same in every frame
  std::vector<double> times_;
  bool finished_ = false;
};

}  // namespace repose
