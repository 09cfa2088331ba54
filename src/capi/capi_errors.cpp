// The C API's error reporting: the thread's last message and the codes' names.
#include <cstdio>

#include "capi_support.hpp"

namespace repose::capi {

namespace {
// One buffer per thread, so that threads using their own handles never see each other's messages. Fixed size:
// recording a failure must not itself fail (a message longer than this is cut).
thread_local char last_message[1024] = "";
}  // namespace

int fail(int code, const char* function, const char* message) noexcept {
  std::snprintf(last_message, sizeof last_message, "%s: %s", function, message);
  return code;
}

}  // namespace repose::capi

extern "C" {

int repose_c_api_version(void) { return REPOSE_C_API_VERSION; }

const char* repose_last_error(void) { return repose::capi::last_message; }

const char* repose_code_name(int code) {
  switch (code) {
    case REPOSE_OK:
      return "REPOSE_OK";
    case REPOSE_ERROR_NULL_POINTER:
      return "REPOSE_ERROR_NULL_POINTER";
    case REPOSE_ERROR_FILE:
      return "REPOSE_ERROR_FILE";
    case REPOSE_ERROR_BAD_MESH:
      return "REPOSE_ERROR_BAD_MESH";
    case REPOSE_ERROR_BAD_PARAMETER:
      return "REPOSE_ERROR_BAD_PARAMETER";
    case REPOSE_ERROR_BAD_STATE:
      return "REPOSE_ERROR_BAD_STATE";
    case REPOSE_ERROR_BAD_INDEX:
      return "REPOSE_ERROR_BAD_INDEX";
    case REPOSE_ERROR_BUFFER_TOO_SMALL:
      return "REPOSE_ERROR_BUFFER_TOO_SMALL";
    case REPOSE_ERROR_OUT_OF_MEMORY:
      return "REPOSE_ERROR_OUT_OF_MEMORY";
    case REPOSE_ERROR_INTERNAL:
      return "REPOSE_ERROR_INTERNAL";
    default:
      return "unknown code";
  }
}

}  // extern "C"
