// SIGINT and SIGTERM (DESIGN section 3): the first one asks the program to stop; every phase
// polls interrupted() often enough to stop within a second, keeps what it has done as
// partial output and the command exits 128 + the signal (130 / 143). A second signal exits
// at once (_exit with the first one's code) after unlinking every registered temporary, so
// even an impatient user is left with no half-written file, except a SIGTERM that follows a
// SIGTERM within kTerminateGraceSeconds: that is the same request again (GNU timeout signals
// the command and then its process group; schedulers signal every process of a job), and the
// partial output still lands.
#pragma once

#include <atomic>

#include <signal.h>

namespace stiction::sys {

// How long after the first signal a SIGTERM is still the same request (documented in
// docs/limits.md): long enough for a process-group signal to arrive, short enough that a
// second `kill` soon after is obeyed.
inline constexpr double kTerminateGraceSeconds = 5.0;

// Installs the handlers for the rest of the process (idempotent).
void install_interrupt_handlers();

// Set by the first signal. The flag the simulation and the renderer poll.
const std::atomic<bool>& interrupt_flag();
inline bool interrupted() { return interrupt_flag().load(std::memory_order_relaxed); }

// The signal received (SIGINT or SIGTERM), 0 if none.
int interrupt_signal();
// 128 + interrupt_signal(): 130 for SIGINT, 143 for SIGTERM.
int interrupt_exit_code();
// "SIGINT" or "SIGTERM".
const char* interrupt_signal_name();

// For a program that embeds the services (the Python module): while it lives, SIGINT sets the
// flag as above (a second SIGINT as well: the host, not the services, decides what to do),
// and the host's own handler is put back afterwards. The flag starts cleared; caught()
// tells whether a SIGINT arrived. Only one may live at a time, on the thread that handles
// signals.
class ScopedInterrupt {
 public:
  ScopedInterrupt();
  ~ScopedInterrupt();
  ScopedInterrupt(const ScopedInterrupt&) = delete;
  ScopedInterrupt& operator=(const ScopedInterrupt&) = delete;
  bool caught() const { return interrupted(); }

 private:
  struct sigaction previous_ {};
};

// Thrown by a phase that noticed the interrupt and has nothing of its own to keep.
struct Interrupted {};

}  // namespace stiction::sys
