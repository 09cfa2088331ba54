// Initial orientations for batches of drops: uniform on SO(3), drop i a pure function of (seed, i).
//
// A counter-based generator (Philox4x64-10, Salmon et al., SC'11, from Random123) maps (seed, i) straight to
// random bits, with no state carried from drop to drop. So drop i gets the same orientation whichever thread,
// rank or sub-range runs it, and results are bit-identical for any split of the work.
#pragma once

#include <cstdint>

#include "repose/geometry/types.hpp"

namespace repose {

/// Three independent uniform deviates in [0, 1) for drop `index` of the batch with `seed` (53-bit
/// resolution).
std::array<double, 3> drop_uniforms(std::uint64_t seed, std::uint64_t index);

/// The initial orientation (body → world) of drop `index`: uniform (Haar measure) on SO(3), by Shoemake's
/// subgroup algorithm (Graphics Gems III, 1992) applied to drop_uniforms(seed, index).
Quat drop_orientation(std::uint64_t seed, std::uint64_t index);

/// Tosses for batches of drops (issue 14): the centre of mass's speed uniform in [0, velocity_max] and the
/// angular speed uniform in [0, spin_max], each in a uniformly random direction (world frame).
struct TossDistribution {
  double velocity_max = 0;  ///< length/time
  double spin_max = 0;      ///< rad/time
  bool active() const { return velocity_max > 0 || spin_max > 0; }
};

/// Throws repose::Error naming the option (--velocity-max, --spin-max) unless both are finite and >= 0.
void validate(const TossDistribution& toss);

struct Toss {
  Vec3 velocity = Vec3::Zero();
  Vec3 spin = Vec3::Zero();
};

/// The toss of drop `index`: from the same counter-based stream as its orientation (further counter words),
/// so it too is a pure function of (seed, index).
Toss drop_toss(std::uint64_t seed, std::uint64_t index, const TossDistribution& distribution);

}  // namespace repose
