#include "sys/interrupt.hpp"

#include <csignal>

#include <signal.h>
#include <time.h>
#include <unistd.h>

#include "sys/temporaries.hpp"

namespace stiction::sys {
namespace {

std::atomic<bool> flag{false};
std::atomic<int> received{0};
std::atomic<long long> first_at_ns{0};  // CLOCK_MONOTONIC time of the first signal
static_assert(std::atomic<bool>::is_always_lock_free);
static_assert(std::atomic<long long>::is_always_lock_free);

long long monotonic_ns() {
  timespec t{};
  ::clock_gettime(CLOCK_MONOTONIC, &t);  // async-signal-safe (POSIX)
  return static_cast<long long>(t.tv_sec) * 1000000000LL + t.tv_nsec;
}

// The first signal to reach a handler is the one recorded (compare-and-swap), and its code
// is the exit code whatever comes after. Both signals are blocked while either handler runs
// (sa_mask below): otherwise two signals pending together (SIGINT then SIGTERM sent at once)
// are delivered nested, the later one's handler running before the first one's could record
// it, and the process would exit with the second signal's code.
//
// A SIGTERM that follows a SIGTERM within kTerminateGraceSeconds is the same request again,
// not impatience: GNU timeout signals the command and then its process group, batch
// schedulers signal every process of a job, and exiting on it would throw away what the
// first one asked to keep. A SIGINT (the user pressing Ctrl-C again), a signal of the other
// kind, or any signal after the grace period exits at once.
extern "C" void on_signal(int signal) {
  int expected = 0;
  if (received.compare_exchange_strong(expected, signal)) {
    first_at_ns.store(monotonic_ns());
    flag.store(true);
    return;
  }
  const double since = 1e-9 * static_cast<double>(monotonic_ns() - first_at_ns.load());
  if (signal == SIGTERM && expected == SIGTERM && since < kTerminateGraceSeconds) return;
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
