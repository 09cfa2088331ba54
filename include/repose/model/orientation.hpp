// Orientation spec strings, as given on the command line and in scenario files.
//
//   quat:w,x,y,z            a quaternion (normalised; order w, x, y, z)
//   axis-angle:x,y,z,angle  rotation by `angle` radians about the axis (x, y, z), which need not be unit
//   identity                no rotation
// The orientation maps body coordinates to world coordinates (gravity along world −z).
#pragma once

#include <string>

#include "repose/geometry/types.hpp"

namespace repose {

/// Parses an orientation spec. Throws repose::Error naming the spec and the problem (unknown kind, wrong
/// number of values, a value that is not a finite number, a zero quaternion or axis).
Quat parse_orientation(const std::string& spec);

/// "quat:w,x,y,z" with 17 significant digits, which parse_orientation reads back exactly.
std::string format_orientation(const Quat& q);

}  // namespace repose
