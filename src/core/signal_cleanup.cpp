// A fixed table of temporary paths that a signal handler can remove without allocating (async-signal-safe).
#include "stiffpath/core/signal_cleanup.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstring>

namespace stiffpath::core {

namespace {

constexpr int slots = 64;
constexpr std::size_t max_path = 4096;

enum State : int { free_slot = 0, writing = 1, ready = 2 };

// Lock-free states: a slot is claimed (free -> writing), filled, then published (ready).
std::atomic<int> states[slots];
char paths[slots][max_path];

extern "C" void remove_temporaries_and_exit(int signo) {
  for (int i = 0; i < slots; ++i) {
    if (states[i].load(std::memory_order_acquire) == ready) ::unlink(paths[i]);
  }
  ::_exit(128 + signo);
}

}  // namespace

int register_temporary(const char* path) noexcept {
  const std::size_t length = std::strlen(path);
  if (length >= max_path) return -1;
  for (int i = 0; i < slots; ++i) {
    int expected = free_slot;
    if (states[i].compare_exchange_strong(expected, writing, std::memory_order_acq_rel)) {
      std::memcpy(paths[i], path, length + 1);
      states[i].store(ready, std::memory_order_release);
      return i;
    }
  }
  return -1;
}

void unregister_temporary(int slot) noexcept {
  if (slot >= 0 && slot < slots) states[slot].store(free_slot, std::memory_order_release);
}

void install_signal_cleanup() {
  struct sigaction action {};
  action.sa_handler = remove_temporaries_and_exit;
  sigemptyset(&action.sa_mask);
  for (const int signo : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&action.sa_mask, signo);
  for (const int signo : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(signo, &action, nullptr);
}

}  // namespace stiffpath::core
