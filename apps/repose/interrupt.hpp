// Ctrl-C (SIGINT) and SIGTERM during `repose poses`: one line on stderr saying how many drops are kept and
// how to resume, then exit 128 + the signal (130 for Ctrl-C, 143 for SIGTERM, as shells report them).
//
// The process ends at once, as a user pressing Ctrl-C expects: nothing needs finishing, because the
// checkpoint is only ever replaced by an atomic rename, so it always holds whole work items. The handler
// only reads atomics and calls write(2) and _exit(2), which are async-signal-safe.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

namespace repose::cli {

struct InterruptReport {
  std::uint64_t total = 0;                           ///< drops the command asks for (all particles)
  const std::atomic<std::uint64_t>* kept = nullptr;  ///< drops held in the checkpoint, or nullptr: none kept
  const std::atomic<std::uint64_t>* done =
      nullptr;                 ///< drops finished in this process (without a checkpoint)
  std::string checkpoint_dir;  ///< where the kept drops are
  bool quiet = false;          ///< a rank other than the root: exit without a word
};

/// Installs the handlers for SIGINT and SIGTERM with what their message reports. A second signal while the
/// message is written ends the process by the default action.
void install_interrupt_report(const InterruptReport& report);

/// Restores the default handlers.
void remove_interrupt_report();

}  // namespace repose::cli
