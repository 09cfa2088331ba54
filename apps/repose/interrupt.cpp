#include "interrupt.hpp"

#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <string>

namespace repose::cli {

namespace {

// Set before the handlers are installed and not changed while they are.
InterruptReport g_report;
std::string g_before_count, g_after_count;

void write_text(const char* text, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, size);
    if (n <= 0) return;
    text += n;
    size -= static_cast<std::size_t>(n);
  }
}

void write_number(std::uint64_t x) {
  char digits[24];
  int n = 0;
  do {
    digits[sizeof digits - 1 - n++] = static_cast<char>('0' + x % 10);
    x /= 10;
  } while (x > 0 && n < 20);
  write_text(digits + sizeof digits - n, static_cast<std::size_t>(n));
}

extern "C" void on_interrupt(int signal_number) {
  ::signal(signal_number, SIG_DFL);  // a second Ctrl-C kills at once
  if (!g_report.quiet) {
    if (isatty(STDERR_FILENO)) write_text("\n", 1);  // off the progress bar's line
    const std::atomic<std::uint64_t>* count = g_report.kept ? g_report.kept : g_report.done;
    write_text(g_before_count.data(), g_before_count.size());
    write_number(count ? count->load(std::memory_order_relaxed) : 0);
    write_text(g_after_count.data(), g_after_count.size());
  }
  ::_exit(128 + signal_number);
}

}  // namespace

void install_interrupt_report(const InterruptReport& report) {
  g_report = report;
  const std::string total = std::to_string(report.total);
  g_before_count = "repose: interrupted: ";
  if (report.kept != nullptr)
    g_after_count =
        " of " + total + " drops kept in " + report.checkpoint_dir + "; rerun the same command to resume\n";
  else
    g_after_count = " of " + total +
                    " drops done and not kept (give --out DIR to keep a checkpoint that a rerun resumes)\n";
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

void remove_interrupt_report() {
  ::signal(SIGINT, SIG_DFL);
  ::signal(SIGTERM, SIG_DFL);
}

}  // namespace repose::cli
