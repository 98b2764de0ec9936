// SIGINT/SIGTERM for long renders: the first signal sets a flag that the pass loop polls between
// passes (the running pass finishes, then the CLI writes what is done and exits 130); a second
// signal exits at once with 130, writing nothing more.
#pragma once

#include <atomic>

namespace clpt {

// Installs the handlers (sigaction, SA_RESTART) for SIGINT and SIGTERM. Idempotent.
void install_interrupt_handlers();

// Set by the first SIGINT/SIGTERM after install_interrupt_handlers(); never cleared.
const std::atomic<bool>& interrupt_flag();

}  // namespace clpt
