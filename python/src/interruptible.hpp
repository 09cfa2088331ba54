// Long runs from Python: released from the GIL and stopped on Ctrl-C (runs.cpp, design.cpp).
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

namespace repose::python {

namespace py = pybind11;

// Runs `work` on a thread of its own while the calling thread, without the GIL, wakes every 50 ms to let
// Python handle signals: on Ctrl-C the cancel flag is set, the work stops at its next check, and the
// KeyboardInterrupt propagates. The result or the work's exception is returned or rethrown here.
template <class Result>
Result interruptible(const std::function<Result(const std::atomic<bool>& cancel)>& work) {
  std::atomic<bool> cancel{false};
  std::optional<Result> result;
  std::exception_ptr error;
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::thread worker([&] {
    try {
      result.emplace(work(cancel));
    } catch (...) {
      error = std::current_exception();
    }
    const std::lock_guard lock(mutex);
    done = true;
    finished.notify_one();
  });
  for (;;) {
    bool over = false;
    {
      py::gil_scoped_release release;
      std::unique_lock lock(mutex);
      over = finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; });
    }
    if (over) break;
    if (PyErr_CheckSignals() != 0) {
      cancel = true;
      {
        py::gil_scoped_release release;
        worker.join();
      }
      throw py::error_already_set();
    }
  }
  worker.join();
  if (error) std::rethrow_exception(error);
  return std::move(*result);
}

}  // namespace repose::python
