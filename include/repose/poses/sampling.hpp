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

}  // namespace repose
