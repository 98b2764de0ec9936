#include "util/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include "util/error.h"

namespace clpt {
namespace {

// Only lock-free atomics may be touched from a signal handler.
static_assert(std::atomic<bool>::is_always_lock_free, "the interrupt flag must be lock-free");
std::atomic<bool> g_interrupted{false};
std::atomic<bool> g_silent{false};

void write_stderr(const char* text, size_t length) {
  const ssize_t ignored = ::write(STDERR_FILENO, text, length);
  (void)ignored;  // nothing to do about a failed note from a signal handler
}

// Async-signal-safe: an atomic store, write(2) and _exit(2) only.
extern "C" void on_interrupt(int) {
  if (g_interrupted.exchange(true)) {
    static const char kNow[] = "\nclpt: interrupted again: exiting without writing\n";
    if (!g_silent.load()) write_stderr(kNow, sizeof kNow - 1);
    ::_exit(static_cast<int>(ExitCode::Interrupted));
  }
  static const char kNote[] =
      "\nclpt: interrupted: finishing the current pass, then writing what is done "
      "(interrupt again to quit at once)\n";
  if (!g_silent.load()) write_stderr(kNote, sizeof kNote - 1);
}

}  // namespace

void install_interrupt_handlers(InterruptNotes notes) {
  g_silent.store(notes == InterruptNotes::Silent);
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // blocking reads and OpenCL waits resume after the handler
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

const std::atomic<bool>& interrupt_flag() { return g_interrupted; }

}  // namespace clpt
