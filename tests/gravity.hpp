// The gravities the tests use, one definition each (the test sources are compiled in batches: CMake's unity
// build, so file-local constants of the same name would clash).
#pragma once

namespace repose::test {

inline constexpr double kGravitySI = 9.81;    // m/s²: the tests in SI units
inline constexpr double kGravityCGS = 981.0;  // cm/s²: the tests in the paper's CGS units

}  // namespace repose::test
