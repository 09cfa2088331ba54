// Internal: what every C API source shares — the handles' contents and the guard that turns C++ failures into
// return codes and the thread's last message (include/repose/repose.h).
#pragma once

#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "repose/error.hpp"
#include "repose/model/params.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"
#include "repose/poses/rest_poses.hpp"
#include "repose/repose.h"
#include "repose/sim/settle.hpp"

struct repose_particle {
  std::shared_ptr<const repose::Particle> model;
};

struct repose_params {
  repose::SettleParams params;
};

struct repose_settler {
  std::shared_ptr<const repose::Particle> model;  // the settler refers to it: kept alive here
  repose::SettleParams params;
  repose::Vec3 offset = repose::Vec3::Zero();  // world = the engine's frame + offset
  double lift = 0;                             // how far the start was raised onto the floor
  std::optional<repose::Settler> settler;
};

struct repose_poses {
  std::shared_ptr<const repose::Particle> model;
  repose::RestLandscape landscape;
  repose::RestPoseCatalog catalog;
};

namespace repose::capi {

/// A failure with its C return code (a repose::Error carries the call's default code instead).
class CodedError : public Error {
 public:
  CodedError(int code, const std::string& message) : Error(message), code_(code) {}
  int code() const { return code_; }

 private:
  int code_;
};

/// Records the thread's last message; never throws. Returns `code`.
int fail(int code, const char* function, const char* message) noexcept;

/// Runs `body`, returning REPOSE_OK or the code of what it threw: a CodedError's own, `error_code` for any
/// other repose::Error, REPOSE_ERROR_OUT_OF_MEMORY, or REPOSE_ERROR_INTERNAL. No exception escapes.
template <class Body>
int guarded(const char* function, int error_code, Body&& body) noexcept {
  try {
    body();
    return REPOSE_OK;
  } catch (const CodedError& e) {
    return fail(e.code(), function, e.what());
  } catch (const Error& e) {
    return fail(error_code, function, e.what());
  } catch (const std::bad_alloc&) {
    return fail(REPOSE_ERROR_OUT_OF_MEMORY, function, "out of memory");
  } catch (const std::exception& e) {
    return fail(REPOSE_ERROR_INTERNAL, function, e.what());
  } catch (...) {
    return fail(REPOSE_ERROR_INTERNAL, function, "unknown exception");
  }
}

/// Throws REPOSE_ERROR_NULL_POINTER naming the argument when `pointer` is null.
inline void require(const void* pointer, const char* argument) {
  if (pointer == nullptr) throw CodedError(REPOSE_ERROR_NULL_POINTER, std::string(argument) + " is NULL");
}

}  // namespace repose::capi
