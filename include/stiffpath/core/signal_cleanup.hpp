// Removal of temporary outputs, and of the child processes writing them, when the process is interrupted (SIGINT, SIGTERM, SIGHUP).
#pragma once

#include <sys/types.h>

namespace stiffpath::core {

//! Records a temporary path to remove if a cleanup signal arrives; returns its slot, or -1 when the
//! fixed table (64 paths of up to 4 KiB) is full or the path too long (the file is then not covered).
int register_temporary(const char* path) noexcept;

//! As register_temporary, for a temporary directory: the handler removes it with everything in it
//! (up to 16 levels deep).
int register_temporary_directory(const char* path) noexcept;

//! Forgets a slot from register_temporary() (after the file was renamed or removed). -1 is ignored.
void unregister_temporary(int slot) noexcept;

//! Records a child process writing into a temporary output (gnuplot): the handler kills it and waits
//! for it before removing anything, so it cannot write after the cleanup. Returns its slot, or -1.
int register_child(pid_t pid) noexcept;
//! Forgets a slot from register_child() once the child has been waited for. -1 is ignored.
void unregister_child(int slot) noexcept;

//! Installs handlers for SIGINT, SIGTERM and SIGHUP that kill and reap every registered child,
//! unlink(2) every registered temporary file, remove every registered temporary directory and
//! _exit(128 + signal). Async-signal-safe: the handler reads fixed tables and calls only kill,
//! waitpid, open, getdents64, unlinkat, close and _exit. Call once at program start (the CLI does);
//! libraries embedding stiffpath may skip it.
void install_signal_cleanup();

}  // namespace stiffpath::core
