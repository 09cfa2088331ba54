// The quasi-static probabilities recorded on an ADOL-C tape as functions of the hull's vertices and the
// centre of mass, for their exact gradients (docs/inverse-design.md). The double landscape decides the
// structure (routes, crossing arcs, balance sides); the tape replays its geometry (map_replay.hpp).
#pragma once

#include <Eigen/Core>
#include <mutex>
#include <vector>

#include "repose/design/basin_gradient.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace repose::detail {

// The recording. Variables: every hull vertex's body-frame position (3i + k) and the centre of mass's offset
// (3n + k): the offset from the centroid (follows_shape) or the position (fixed); at the recorded point the
// centre of mass is the body frame's origin. Outputs: every hull face's probability.
class BasinTape {
 public:
  BasinTape(const Particle& particle, const RestLandscape& landscape, MassModel mass);
  ~BasinTape();
  BasinTape(const BasinTape&) = delete;
  BasinTape& operator=(const BasinTape&) = delete;

  int variables() const { return variables_; }
  // Per hull face, recomputed on the tape (equal to the landscape's to round-off).
  const std::vector<double>& probability() const { return probability_; }
  // Row r: the gradient of Σ_f weights(r, f)·P_f over the variables. One reverse sweep for all rows; a tape
  // answers once (ADOL-C keeps the forward values for one sweep).
  Eigen::MatrixXd gradients(const Eigen::MatrixXd& weights);
  // Column j: the probabilities' derivatives along column j of `directions` (variables × p), by one forward
  // sweep (cheaper than reverse sweeps when p is below the number of faces). Any number of times.
  Eigen::MatrixXd directional(const Eigen::MatrixXd& directions) const;

 private:
  std::unique_lock<std::mutex> lock_;  // ADOL-C's tapes are process-global
  int variables_ = 0;
  std::vector<double> point_;  // the variables' recorded values
  std::vector<double> probability_;
  bool swept_ = false;
};

}  // namespace repose::detail
