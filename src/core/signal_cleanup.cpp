// Fixed tables of temporary paths and child processes that a signal handler can clean up without allocating (async-signal-safe).
#include "stiffpath/core/signal_cleanup.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstring>

namespace stiffpath::core {

namespace {

constexpr int slots = 64;
constexpr std::size_t max_path = 4096;
constexpr int max_tree_depth = 16;

enum State : int { free_slot = 0, writing = 1, ready = 2 };

// Lock-free states: a slot is claimed (free -> writing), filled, then published (ready).
std::atomic<int> states[slots];
char paths[slots][max_path];
bool is_directory[slots];

std::atomic<int> child_states[slots];
pid_t children[slots];

void empty_directory(int fd, int depth);

// One pass of getdents64 over `fd`, removing each entry (directories emptied first).
void remove_entries(int fd, int depth, char* buffer, std::size_t size, int& removed) {
  for (;;) {
    const long n = ::syscall(SYS_getdents64, fd, buffer, size);
    if (n <= 0) break;
    for (long at = 0; at < n;) {
      // glibc's dirent64 has the layout of the kernel's getdents64 records
      const auto* entry = reinterpret_cast<const struct dirent64*>(buffer + at);
      at += entry->d_reclen;
      const char* name = entry->d_name;
      if (name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0'))) continue;
      bool directory = entry->d_type == DT_DIR;
      if (entry->d_type == DT_UNKNOWN) {
        struct stat info {};
        directory = ::fstatat(fd, name, &info, AT_SYMLINK_NOFOLLOW) == 0 && S_ISDIR(info.st_mode);
      }
      if (directory && depth < max_tree_depth) {
        const int sub = ::openat(fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (sub >= 0) empty_directory(sub, depth + 1);
      }
      if (::unlinkat(fd, name, directory ? AT_REMOVEDIR : 0) == 0) ++removed;
    }
  }
}

// Removes everything inside the directory open as `fd` (closing it), depth-first; only system calls.
// Read again from the start while a pass removed something, as entries may move while others go.
void empty_directory(int fd, int depth) {
  alignas(8) char buffer[2048];
  for (int pass = 0, removed = 1; removed > 0 && pass < 8; ++pass) {
    removed = 0;
    ::lseek(fd, 0, SEEK_SET);
    remove_entries(fd, depth, buffer, sizeof buffer, removed);
  }
  ::close(fd);
}

extern "C" void clean_up_and_exit(int signo) {
  for (int i = 0; i < slots; ++i) {
    if (child_states[i].load(std::memory_order_acquire) != ready) continue;
    ::kill(children[i], SIGKILL);
    while (::waitpid(children[i], nullptr, 0) < 0 && errno == EINTR) {
    }
  }
  for (int i = 0; i < slots; ++i) {
    if (states[i].load(std::memory_order_acquire) != ready) continue;
    if (!is_directory[i]) {
      ::unlink(paths[i]);
      continue;
    }
    const int fd = ::open(paths[i], O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd >= 0) empty_directory(fd, 1);
    ::rmdir(paths[i]);
  }
  ::_exit(128 + signo);
}

int claim(const char* path, bool directory) noexcept {
  const std::size_t length = std::strlen(path);
  if (length >= max_path) return -1;
  for (int i = 0; i < slots; ++i) {
    int expected = free_slot;
    if (states[i].compare_exchange_strong(expected, writing, std::memory_order_acq_rel)) {
      std::memcpy(paths[i], path, length + 1);
      is_directory[i] = directory;
      states[i].store(ready, std::memory_order_release);
      return i;
    }
  }
  return -1;
}

}  // namespace

int register_temporary(const char* path) noexcept { return claim(path, false); }

int register_temporary_directory(const char* path) noexcept { return claim(path, true); }

void unregister_temporary(int slot) noexcept {
  if (slot >= 0 && slot < slots) states[slot].store(free_slot, std::memory_order_release);
}

int register_child(pid_t pid) noexcept {
  for (int i = 0; i < slots; ++i) {
    int expected = free_slot;
    if (child_states[i].compare_exchange_strong(expected, writing, std::memory_order_acq_rel)) {
      children[i] = pid;
      child_states[i].store(ready, std::memory_order_release);
      return i;
    }
  }
  return -1;
}

void unregister_child(int slot) noexcept {
  if (slot >= 0 && slot < slots) child_states[slot].store(free_slot, std::memory_order_release);
}

void install_signal_cleanup() {
  struct sigaction action {};
  action.sa_handler = clean_up_and_exit;
  sigemptyset(&action.sa_mask);
  for (const int signo : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&action.sa_mask, signo);
  for (const int signo : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(signo, &action, nullptr);
}

}  // namespace stiffpath::core
