#include "repose/campaign/runner.hpp"

#include <cstdlib>
#include <exception>

#include "repose/error.hpp"

namespace repose {

bool launched_by_mpi() {
  for (const char* name :
       {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "MV2_COMM_WORLD_RANK"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

std::string prepare_on_root(WorkRunner& runner, const std::function<std::string()>& prepare) {
  // The first character says how the root fared: '0' success, else the exit code the others should use.
  std::string message;
  std::exception_ptr failure;
  if (runner.is_root()) {
    try {
      const std::string result = prepare();
      message.push_back('0');
      message.append(result);
    } catch (const Error&) {
      failure = std::current_exception();
      message.assign(1, '2');
    } catch (...) {
      failure = std::current_exception();
      message.assign(1, '1');
    }
  }
  if (runner.ranks() > 1) message = runner.broadcast(message);
  if (failure) std::rethrow_exception(failure);
  if (message.empty() || message[0] != '0') throw RootFailed{message.empty() ? 1 : message[0] - '0'};
  return message.substr(1);
}

}  // namespace repose
