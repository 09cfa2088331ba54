// Errors reported by the repose library.
//
// The library never exits the process: every failure a user can cause (bad file, bad spec string, bad
// parameter) is thrown as repose::Error with a one-line message that names the input and the problem,
// e.g. "cube.stl: open surface: 3 boundary edges". The CLI prints the message and exits non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace repose {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A run stopped because its caller asked it to (EnsembleOptions::cancel): not a failure of the input.
class Cancelled : public Error {
 public:
  using Error::Error;
};

}  // namespace repose
