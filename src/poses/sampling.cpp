#include "repose/poses/sampling.hpp"

#include <Random123/philox.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "repose/error.hpp"

namespace repose {

namespace {

// Keeps this generator's stream apart from any other use of the same seed (ASCII "reposeSO3").
constexpr std::uint64_t kStreamKey = 0x7265706f736553ULL;

// The top 53 bits as a double in [0, 1): exact, and never 1.
double to_unit_interval(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

// Three uniforms of drop `index` from counter word `word` (0: the orientation; 1, 2: the toss).
std::array<double, 3> uniforms(std::uint64_t seed, std::uint64_t index, std::uint64_t word) {
  using Philox = r123::Philox4x64;
  const Philox::ctr_type counter = {{index, word, 0, 0}};
  const Philox::key_type key = {{seed, kStreamKey}};
  const Philox::ctr_type bits = Philox{}(counter, key);
  return {to_unit_interval(bits[0]), to_unit_interval(bits[1]), to_unit_interval(bits[2])};
}

// A vector of length uniform in [0, max] in a uniformly random direction (Archimedes: z uniform in [−1, 1]).
Vec3 random_vector(const std::array<double, 3>& u, double max) {
  const double z = 2 * u[1] - 1, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * std::numbers::pi * u[2];
  return max * u[0] * Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

}  // namespace

void validate(const TossDistribution& toss) {
  if (!(std::isfinite(toss.velocity_max) && toss.velocity_max >= 0))
    throw Error("the tosses' largest speed (--velocity-max) must be a finite number >= 0");
  if (!(std::isfinite(toss.spin_max) && toss.spin_max >= 0))
    throw Error("the tosses' largest angular speed (--spin-max) must be a finite number >= 0");
}

std::array<double, 3> drop_uniforms(std::uint64_t seed, std::uint64_t index) {
  return uniforms(seed, index, 0);
}

Toss drop_toss(std::uint64_t seed, std::uint64_t index, const TossDistribution& distribution) {
  return {random_vector(uniforms(seed, index, 1), distribution.velocity_max),
          random_vector(uniforms(seed, index, 2), distribution.spin_max)};
}

Quat drop_orientation(std::uint64_t seed, std::uint64_t index) {
  const auto [u1, u2, u3] = drop_uniforms(seed, index);
  const double r1 = std::sqrt(1.0 - u1);
  const double r2 = std::sqrt(u1);
  const double a = 2.0 * std::numbers::pi * u2;
  const double b = 2.0 * std::numbers::pi * u3;
  return Quat(r2 * std::cos(b), r1 * std::sin(a), r1 * std::cos(a), r2 * std::sin(b));
}

}  // namespace repose
