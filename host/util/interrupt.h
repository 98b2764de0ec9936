// SIGINT/SIGTERM for long renders: the first signal sets a flag that the pass loop polls between
// passes (the running pass finishes, then the CLI writes what is done and exits 130); a second
// signal exits at once with 130, writing nothing more.
#pragma once

#include <atomic>

namespace clpt {

// How the handler speaks: a single process, and rank 0 of an MPI job, print the notes below; the
// other ranks of a job stay silent, because the launcher forwards every rank's stderr into one
// stream where two ranks' notes, written at the same instant, interleave mid-line.
enum class InterruptNotes { Print, Silent };

// Installs the handlers (sigaction, SA_RESTART) for SIGINT and SIGTERM. Idempotent.
void install_interrupt_handlers(InterruptNotes notes = InterruptNotes::Print);

// Set by the first SIGINT/SIGTERM after install_interrupt_handlers(); never cleared.
const std::atomic<bool>& interrupt_flag();

}  // namespace clpt
