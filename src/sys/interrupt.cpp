#include "sys/interrupt.hpp"

#include <csignal>

#include <signal.h>
#include <unistd.h>

#include "sys/temporaries.hpp"

namespace stiction::sys {
namespace {

std::atomic<bool> flag{false};
std::atomic<int> received{0};
static_assert(std::atomic<bool>::is_always_lock_free);

// The first signal to reach a handler is the one recorded (compare-and-swap), and its code
// is the exit code whatever comes after. Both signals are blocked while either handler runs
// (sa_mask below): otherwise two signals pending together (SIGINT then SIGTERM sent at once)
// are delivered nested, the later one's handler running before the first one's could record
// it, and the process would exit with the second signal's code.
extern "C" void on_signal(int signal) {
  int expected = 0;
  if (received.compare_exchange_strong(expected, signal)) {
    flag.store(true);
    return;
  }
  // Second signal: leave no temporary behind and go, with the first signal's code.
  remove_registered_temporaries();
  ::_exit(128 + received.load());
}

extern "C" void on_embedded_signal(int signal) {
  int expected = 0;
  received.compare_exchange_strong(expected, signal);
  flag.store(true);
}

}  // namespace

ScopedInterrupt::ScopedInterrupt() {
  flag.store(false);
  received.store(0);
  struct sigaction action {};
  action.sa_handler = on_embedded_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &action, &previous_);
}

ScopedInterrupt::~ScopedInterrupt() {
  ::sigaction(SIGINT, &previous_, nullptr);
  flag.store(false);
  received.store(0);
}

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaddset(&action.sa_mask, SIGINT);
  sigaddset(&action.sa_mask, SIGTERM);
  action.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

const std::atomic<bool>& interrupt_flag() { return flag; }
int interrupt_signal() { return received.load(); }
int interrupt_exit_code() { return 128 + received.load(); }
const char* interrupt_signal_name() { return received.load() == SIGTERM ? "SIGTERM" : "SIGINT"; }

}  // namespace stiction::sys
